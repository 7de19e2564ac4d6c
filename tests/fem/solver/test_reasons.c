/* test_reasons - every Newton divergence path ends with its FemNewtonReason (fem.h), and a
 * user contributor (fem_contrib.h) runs through the solver.
 *
 * Cantilever bar (tet10, neo-Hookean), clamped at x = 0, end load. A contributor adds ground
 * springs f = k u on every node with k = 100 times the bar's stiffness scale, and reports the
 * tangent c k I: with k dominating, Newton's error is multiplied by about 1 - 1/c per
 * iteration, which gives each path on purpose:
 *   c = 1     exact tangent                    -> FEM_CONVERGED_RESIDUAL (the contributor works)
 *   c = 1.6   factor 0.375, max_iter = 4       -> FEM_DIVERGED_MAX_ITER
 *   c = 5     factor 0.8 (not halved)          -> FEM_DIVERGED_STALLED
 *   c = -1    factor 2, no line search         -> FEM_DIVERGED_GROWTH
 *   a NaN force                                -> FEM_DIVERGED_NAN
 *   a domain hook refusing |u| > 1e-9          -> FEM_DIVERGED_DOMAIN (after the line search)
 *   an unsupported node in no element          -> FEM_DIVERGED_LINEAR_SOLVE (+ floating body)
 *   volume control, pressure surface fixed     -> FEM_DIVERGED_BORDERED (dV/dp = 0)
 * dl_min = 0.6 stops the ramp at the first failed substep, so the report's reason is that
 * substep's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "fem_contrib.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

typedef struct {
  double k, c;
  int nan;
  const int *fixed; /* per node: 1 if clamped */
} Ground;

static int ground_eval(void *ctx, FemAsmView *v) {
  const Ground *g = ctx;
  const FemMesh *m = fem_asm_mesh(v);
  const double *x = fem_asm_positions(v);
  double K[9] = {g->c * g->k, 0, 0, 0, g->c * g->k, 0, 0, 0, g->c * g->k};
  for (int i = 0; i < m->nnodes; i++) {
    if (g->fixed[i]) continue;
    double f[3];
    for (int j = 0; j < 3; j++) f[j] = g->k * (x[3 * i + j] - m->xyz[3 * i + j]);
    if (g->nan && i == m->nnodes / 2) f[0] = NAN;
    fem_asm_add_force(v, i, f);
    fem_asm_add_block(v, i, i, K);
  }
  return 0;
}

static int refuse_motion(const FemSolver *s, const double *x, void *ctx) {
  (void)ctx;
  const FemMesh *m = fem_solver_mesh(s);
  for (int i = 0; i < 3 * m->nnodes; i++)
    if (fabs(x[i] - m->xyz[i]) > 1e-9) return 1;
  return 0;
}

enum { PLAIN, CONTRIB, HOOK, ORPHAN, VOLUME };

static int run(FemMesh *m, int kind, Ground *g, int max_iter, int line_search,
               FemNewtonReason want, const char *what) {
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 50, .rho = 1};
  FemSolverParams prm = fem_solver_params_default();
  prm.dl_min = 0.6;
  prm.max_iter = max_iter;
  prm.line_search = line_search;
  prm.max_stall = want == FEM_DIVERGED_STALLED ? 6 : 1000;
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  if (kind == CONTRIB) {
    FemContributor c = {"ground", NULL, ground_eval, g, NULL};
    TU_CHECK(fem_solver_add_contributor(s, &c));
  }
  if (kind == HOOK) fem_solver_set_domain_check(s, refuse_motion, NULL);
  if (kind == VOLUME) {
    TU_CHECK(fem_solver_fix_surface(s, "end", FEM_XYZ));
    TU_CHECK(fem_solver_add_pressure_surface(s, "end"));
  }
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *end = fem_mesh_find_surface(m, "end");
  double *f = calloc((size_t)3 * end->nnodes, sizeof *f);
  for (int k = 0; k < end->nnodes; k++) f[3 * k + 2] = -1e-4 / end->nnodes;
  TU_CHECK(fem_solver_set_nodal_forces(s, end->nnodes, end->nodes, f));
  free(f);
  if (kind == VOLUME) {
    TU_CHECK(fem_solver_set_control(s, FEM_CONTROL_VOLUME));
    TU_CHECK(fem_solver_set_volume(s, 1.1 * fem_solver_cavity_volume(s)));
  }
  int rc = fem_solver_solve(s);
  FemSolveReport rep;
  fem_solver_report(s, &rep);
  int fail = 0;
  if (rep.newton_reason != want || (want > 0) != (rc == 0)) {
    fprintf(stderr, "%s: rc %d, reason %d '%s', expected %d '%s' (%s)\n", what, rc,
            rep.newton_reason, fem_newton_reason_string(rep.newton_reason), want,
            fem_newton_reason_string(want), sa_error_message());
    fail = 1;
  }
  if (kind == ORPHAN && fem_solver_floating_bodies(s) != 1) {
    fprintf(stderr, "%s: the orphan node is not reported as a floating body\n", what);
    fail = 1;
  }
  if (kind == CONTRIB && want > 0) { /* the springs carry the load: |u| ~ F / (k n) */
    const double *u = fem_solver_displacements(s);
    double umax = 0;
    for (int i = 0; i < 3 * m->nnodes; i++) umax = fmax(umax, fabs(u[i]));
    if (!(umax > 0 && umax < 1e-4 / g->k)) {
      fprintf(stderr, "%s: max |u| %g not held by the contributor\n", what, umax);
      fail = 1;
    }
  }
  sa_error_clear();
  fem_solver_destroy(&s);
  return fail;
}

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_ERROR);
  SmeshBlock blk = {{6, 2, 2}, smesh_map_bar, NULL,
                    {"clamp", "end", "front", "back", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  int *fixed = calloc((size_t)m->nnodes, sizeof *fixed);
  const FemSurface *cl = fem_mesh_find_surface(m, "clamp");
  for (int k = 0; k < cl->nnodes; k++) fixed[cl->nodes[k]] = 1;
  double k = 100.0; /* bar stiffness scale mu * 0.04 / 1 ~ 0.04: k dominates */
  int fails = 0;
  Ground g = {k, 1.0, 0, fixed};
  fails += run(m, CONTRIB, &g, 25, 1, FEM_CONVERGED_RESIDUAL, "user contributor, exact tangent");
  g.c = 1.6;
  fails += run(m, CONTRIB, &g, 4, 1, FEM_DIVERGED_MAX_ITER, "max_iter");
  g.c = 5.0;
  fails += run(m, CONTRIB, &g, 25, 1, FEM_DIVERGED_STALLED, "stalled");
  g.c = -1.0;
  fails += run(m, CONTRIB, &g, 100, 0, FEM_DIVERGED_GROWTH, "growth");
  g.c = 1.0, g.nan = 1;
  fails += run(m, CONTRIB, &g, 25, 1, FEM_DIVERGED_NAN, "nan");
  fails += run(m, HOOK, NULL, 25, 1, FEM_DIVERGED_DOMAIN, "domain hook");
  /* the end face encloses a positive volume with the origin once the bar lies at x < 0 */
  for (int i = 0; i < m->nnodes; i++) m->xyz[3 * i] -= 2.0;
  fails += run(m, VOLUME, NULL, 25, 1, FEM_DIVERGED_BORDERED, "bordered");
  for (int i = 0; i < m->nnodes; i++) m->xyz[3 * i] += 2.0;
  /* a node in no element, not fixed */
  double *xyz = realloc(m->xyz, sizeof(double) * 3 * (m->nnodes + 1));
  if (!xyz) return 1;
  m->xyz = xyz;
  xyz[3 * m->nnodes] = 5, xyz[3 * m->nnodes + 1] = 5, xyz[3 * m->nnodes + 2] = 5;
  m->nnodes++;
  fails += run(m, ORPHAN, NULL, 25, 1, FEM_DIVERGED_LINEAR_SOLVE, "linear solve");
  free(fixed);
  smesh_free(&m);
  return fails != 0;
}
