/* test_indefinite_dead - FEM_INDEFINITE_MODIFY under dead loads (no follower pressure), as in
 * the FEM-DEM coupling's dynamic steps: an indefinite tangent at an iterate steps back toward
 * the last accepted iterate, or cuts the increment, and never takes an UMFPACK LU direction.
 *
 * Body: the bar 1 x 0.2 x 0.2 (10 x 2 x 2 tet10 cells), nearly incompressible neo-Hookean
 * (mu = 1, kappa = 500 mu, the actuator's K/mu), clamped at x = 0; a dead transverse load
 * F = (0, 0, -Fz) spread equally over the nodes of the end face x = 1, applied in one increment
 * (dl_init = 1). Its linear first iterate goes far past the equilibrium
 * (0.31 L), where the consistent tangent is indefinite. References:
 *  1. Static balance (conservation of momentum at rest): the clamp's reactions carry the load,
 *     |sum R + F| <= 1e-8 |F| (the Newton tolerance is rtol = 1e-10 of the force scale), and
 *     the moment about the clamp centre balances that of the load at the deformed end nodes.
 *  2. The same equilibrium (unique on this stable path) as the default path (LU for an
 *     indefinite tangent) to 1e-8 relative; the default path must have used LU (else the case
 *     does not exercise the change), the modified one none and at least one step-back.
 *  3. The same in one implicit dynamic step (fem_solver_step_dynamic, the coupling's solve)
 *     of 1e5 s, far longer than the bar's 18 s period: no LU, and the end state within 1e-6
 *     of the static equilibrium. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

#define FZ 4e-4 /* total tip load [N]: tip deflection 0.31 L */

static int build(const FemMesh *m, const FemMaterial *mat, FemIndefinite indef, FemSolver **out) {
  FemSolverParams prm = fem_solver_params_default();
  prm.indefinite = indef;
  prm.dl_init = 1.0;
  prm.rtol = 1e-10;
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, mat, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *end = fem_mesh_find_surface(m, "end");
  double *f = calloc(3 * (size_t)end->nnodes, sizeof *f);
  for (int k = 0; k < end->nnodes; k++) f[3 * k + 2] = -FZ / end->nnodes;
  int rc = fem_solver_set_nodal_forces(s, end->nnodes, end->nodes, f);
  free(f);
  TU_CHECK(rc);
  *out = s;
  return 0;
}

static double rel_diff(const double *a, const double *b, int n) {
  double num = 0, den = 0;
  for (int i = 0; i < n; i++) num += (a[i] - b[i]) * (a[i] - b[i]), den += b[i] * b[i];
  return sqrt(num / fmax(den, 1e-300));
}

/* Solve (static or one dynamic step of length 1e5 s), copy the displacements to u. */
static int run(const FemMesh *m, const FemMaterial *mat, FemIndefinite indef, int dynamic,
               double *u, FemSolverStats *st, FemSolver **keep) {
  FemSolver *s;
  TU_CHECK(build(m, mat, indef, &s));
  TU_CHECK(dynamic ? fem_solver_step_dynamic(s, 1e5) : fem_solver_solve(s));
  const double *ud = fem_solver_displacements(s);
  for (int i = 0; i < 3 * m->nnodes; i++) u[i] = ud[i];
  fem_solver_stats(s, st);
  if (keep) *keep = s;
  else fem_solver_destroy(&s);
  return 0;
}

int main(void) {
  int verbose = getenv("SA_TEST_VERBOSE") != NULL;
  sa_log_set_level(verbose ? SA_LOG_DEBUG : SA_LOG_ERROR);
  SmeshBlock blk = {{10, 2, 2}, smesh_map_bar, NULL, {"clamp", "end", "front", "back", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 500, .rho = 1};
  int n = 3 * m->nnodes, fails = 0;
  double *u0 = malloc(sizeof(double) * n), *u1 = malloc(sizeof(double) * n);
  double *R = malloc(sizeof(double) * n);
  FemSolverStats st0, st1;

  /* the reference equilibrium: the default path (static, LU on an indefinite tangent) */
  TU_CHECK(run(m, &mat, FEM_INDEFINITE_LU, 0, u0, &st0, NULL));
  if (st0.n_lu == 0) {
    fprintf(stderr, "the default path took no LU (the case must exercise an indefinite tangent)\n");
    fails++;
  }
  for (int dynamic = 0; dynamic <= 1; dynamic++) {
    const char *kind = dynamic ? "dynamic step, modify: displacement against the static equilibrium"
                               : "static solve, modify: displacement against the default path";
    FemSolver *s = NULL;
    TU_CHECK(run(m, &mat, FEM_INDEFINITE_MODIFY, dynamic, u1, &st1, &s));
    double d = rel_diff(u1, u0, n), tip = 0;
    for (int i = 0; i < m->nnodes; i++) tip = fmin(tip, u1[3 * i + 2]);
    if (verbose)
      printf("%s: default path %d factorisations (%d LU); modify %d (%d LU, %d step-backs); tip "
             "deflection %.4f; |u1 - u0|/|u0| = %.2e\n", dynamic ? "dynamic" : "static",
             st0.n_factor, st0.n_lu, st1.n_factor, st1.n_lu, st1.n_indef_backtrack, -tip, d);
    if (st1.n_lu != 0 || st1.n_indef_backtrack == 0) {
      fprintf(stderr, "%s: indefinite = modify took %d LU factorisation(s), %d step-backs "
              "(expected none, at least one)\n", dynamic ? "dynamic" : "static", st1.n_lu,
              st1.n_indef_backtrack);
      fails++;
    }
    /* static: both paths converge to rtol 1e-10 of the force scale on the same equilibrium;
     * dynamic: substeps of >= 1e5/2^10 s against the bar's 18 s period leave inertia forces of
     * order (T/dt)^2 ~ 1e-4 of the load at the most, measured 1e-7 */
    fails += tu_close(kind, d, 0.0, dynamic ? 1e-6 : 1e-8, 0.0);
    if (!dynamic) { /* 1: the clamp carries the load (force and moment about x = 0) */
      TU_CHECK(fem_solver_reactions(s, R));
      const double *x = fem_solver_positions(s);
      const FemSurface *end = fem_mesh_find_surface(m, "end");
      double Rs[3] = {0, 0, 0}, M_r = 0, M_f = 0; /* moments about the y axis through (0,0.1,0.1) */
      for (int i = 0; i < m->nnodes; i++) {
        for (int c = 0; c < 3; c++) Rs[c] += R[3 * i + c];
        M_r += (x[3 * i + 2] - 0.1) * R[3 * i] - x[3 * i] * R[3 * i + 2];
      }
      for (int k = 0; k < end->nnodes; k++) {
        const double *p = x + 3 * end->nodes[k];
        M_f += -p[0] * (-FZ / end->nnodes);
      }
      fails += tu_close("clamp reaction x against 0", Rs[0], 0.0, 1e-8 * FZ, 0.0);
      fails += tu_close("clamp reaction z against the load", Rs[2], FZ, 1e-8 * FZ, 0.0);
      fails += tu_close("moment of the reactions against the load's", M_r, -M_f, 1e-8 * FZ, 0.0);
    }
    fem_solver_destroy(&s);
  }
  free(u0), free(u1), free(R);
  smesh_free(&m);
  return fails ? 1 : 0;
}
