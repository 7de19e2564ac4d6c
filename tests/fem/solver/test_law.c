/* test_law - a constitutive law defined and registered here, outside fem/ (fem_law.h), runs
 * through the whole solver.
 *
 * The law: compressible neo-Hookean of kind FEM_LAW_FULL (Bonet & Wood),
 *   W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,  P = mu (F - F^-T) + lambda ln J F^-T,
 *   A_iJkL = mu d_ik d_JL + (mu - lambda ln J) Fi_Li Fi_Jk + lambda Fi_Ji Fi_Lk  (Fi = F^-1),
 * with mu scaled by the element's data value (FemLawCtx.elem_data[0]), one history variable
 * initialised to -1 by the law's hook and incremented at every evaluation from the committed
 * value (so after n converged substeps it reads -1 + n), and a recoverable failure
 * (SA_ERR_DOMAIN) when J exceeds the parameter jmax.
 * 1. fem_solver_check_tangent (central differences through the whole assembly) of a deformed
 *    cantilever: relative error <= 1e-6 (h = 1e-7: truncation ~h^2, round-off ~1e-16/h).
 * 2. Small strain (end load giving strains ~1e-4): equal to the built-in stiff_neohooke of the
 *    same E, nu (both Hooke's law in the limit) to 1e-3 of the largest displacement.
 * 3. Element data 2 with mu equals element data 1 with 2 mu (same equations: 1e-12).
 * 4. History: -1 before the first solve (init hook), -1 + substeps after (read back).
 * 5. jmax = 1 + 1e-9 under a tensile load: the solve fails with FEM_DIVERGED_DOMAIN.
 * 6. Unknown law or parameter names are input errors naming them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "fem_element.h"
#include "fem_law.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static double inv3(const double F[9], double Fi[9]) {
  double J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
             F[2] * (F[3] * F[7] - F[4] * F[6]);
  Fi[0] = (F[4] * F[8] - F[5] * F[7]) / J;
  Fi[1] = (F[2] * F[7] - F[1] * F[8]) / J;
  Fi[2] = (F[1] * F[5] - F[2] * F[4]) / J;
  Fi[3] = (F[5] * F[6] - F[3] * F[8]) / J;
  Fi[4] = (F[0] * F[8] - F[2] * F[6]) / J;
  Fi[5] = (F[2] * F[3] - F[0] * F[5]) / J;
  Fi[6] = (F[3] * F[7] - F[4] * F[6]) / J;
  Fi[7] = (F[1] * F[6] - F[0] * F[7]) / J;
  Fi[8] = (F[0] * F[4] - F[1] * F[3]) / J;
  return J;
}

/* par: mu, lambda, jmax */
static int nh_eval(const double *par, const FemLawCtx *ctx, const double F[9],
                   const double *hist_old, double *hist_new, double *W, double P[9],
                   double A[81]) {
  double Fi[9], J = inv3(F, Fi);
  if (!(J > 0)) return SA_ERR_INVERTED;
  if (J > par[2]) return SA_ERR_DOMAIN;
  double mu = par[0] * (ctx->elem_data ? ctx->elem_data[0] : 1.0), lam = par[1], lnJ = log(J);
  double I1 = 0;
  for (int i = 0; i < 9; i++) I1 += F[i] * F[i];
  *W = 0.5 * mu * (I1 - 3) - mu * lnJ + 0.5 * lam * lnJ * lnJ;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) P[3 * i + j] = mu * F[3 * i + j] + (lam * lnJ - mu) * Fi[3 * j + i];
  if (A)
    for (int i = 0; i < 3; i++)
      for (int J_ = 0; J_ < 3; J_++)
        for (int k = 0; k < 3; k++)
          for (int L = 0; L < 3; L++)
            A[9 * (3 * i + J_) + 3 * k + L] = mu * (i == k) * (J_ == L) +
                                              (mu - lam * lnJ) * Fi[3 * L + i] * Fi[3 * J_ + k] +
                                              lam * Fi[3 * J_ + i] * Fi[3 * L + k];
  if (hist_new) hist_new[0] = hist_old[0] + 1;
  return 0;
}

static void nh_init(const double *par, double *hist) {
  (void)par;
  hist[0] = -1.0;
}

static int nh_check(const double *par) {
  if (!(par[0] > 0)) return SA_ERROR(SA_ERR_INPUT, "test law: mu = %g must be > 0", par[0]);
  return 0;
}

static const char *const nh_names[] = {"mu", "lambda", "jmax"};
static const FemLaw nh_law = {"test_compressible_neohooke", 3, nh_names, 1, 1, FEM_LAW_FULL,
                              nh_init, nh_eval, nh_check, NULL, NULL, NULL};

static int cantilever(const FemMesh *m, const FemMaterial *mat, double fz, const double *edata,
                      FemSolver **out) {
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, mat, NULL, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  TU_CHECK(fem_solver_setup(s));
  if (edata) TU_CHECK(fem_solver_set_element_data(s, 1, edata));
  const FemSurface *end = fem_mesh_find_surface(m, "end");
  double *f = calloc((size_t)3 * end->nnodes, sizeof *f);
  for (int k = 0; k < end->nnodes; k++) f[3 * k] = 0.3 * fz / end->nnodes, f[3 * k + 2] = fz / end->nnodes;
  TU_CHECK(fem_solver_set_nodal_forces(s, end->nnodes, end->nodes, f));
  free(f);
  *out = s;
  return 0;
}

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_ERROR);
  TU_CHECK(fem_law_register(&nh_law));
  TU_CHECK(fem_law_register(&nh_law)); /* the same law again: fine */
  SmeshBlock blk = {{8, 2, 2}, smesh_map_bar, NULL,
                    {"clamp", "end", "front", "back", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  int n3 = 3 * m->nnodes, fails = 0;
  const double E = 1000, nu = 0.3, mu = E / (2 * (1 + nu)), lam = E * nu / ((1 + nu) * (1 - 2 * nu));
  const char *nm[] = {"mu", "lambda", "jmax"};
  double par[] = {mu, lam, 10.0};
  FemMaterial mat;
  TU_CHECK(fem_material_from_law("test_compressible_neohooke", 3, nm, par, 1.0, &mat));

  /* 1 + 4: tangent check at a deformed state; history */
  FemSolver *s;
  TU_CHECK(cantilever(m, &mat, -0.05, NULL, &s));
  int nh = 0;
  const double *h = fem_solver_history(s, 0, &nh);
  if (!h || nh != 1 || h[0] != -1.0) fprintf(stderr, "history before solve: %g\n", h ? h[0] : NAN), fails++;
  TU_CHECK(fem_solver_solve(s));
  FemSolveReport rep;
  fem_solver_report(s, &rep);
  double rel;
  TU_CHECK(fem_solver_check_tangent(s, 1e-7, &rel));
  fails += tu_close("user law: FD check of the assembled tangent", rel, 0.0, 1e-6, 0.0);
  h = fem_solver_history(s, m->nelem - 1, &nh);
  fails += tu_close("user law: history read back = -1 + substeps", h[0], -1.0 + rep.substeps, 0, 0);
  double umax = 0;
  for (int i = 0; i < n3; i++) umax = fmax(umax, fabs(fem_solver_displacements(s)[i]));
  if (!(umax > 0.01)) fprintf(stderr, "deflection %g too small\n", umax), fails++;
  fem_solver_destroy(&s);

  /* 2. small strain against the built-in stiff neo-Hookean */
  const char *sn[] = {"e", "nu"};
  double sv[] = {E, nu};
  FemMaterial stiff;
  TU_CHECK(fem_material_from_law("stiff_neohooke", 2, sn, sv, 1.0, &stiff));
  FemSolver *a, *b;
  TU_CHECK(cantilever(m, &mat, -2e-4, NULL, &a));
  TU_CHECK(cantilever(m, &stiff, -2e-4, NULL, &b));
  TU_CHECK(fem_solver_solve(a));
  TU_CHECK(fem_solver_solve(b));
  double d = 0;
  umax = 0;
  for (int i = 0; i < n3; i++) {
    d = fmax(d, fabs(fem_solver_displacements(a)[i] - fem_solver_displacements(b)[i]));
    umax = fmax(umax, fabs(fem_solver_displacements(b)[i]));
  }
  fails += tu_close("user law vs built-in, small strain: max |du|", d, 0.0, 1e-3 * umax, 0.0);
  fem_solver_destroy(&a);
  fem_solver_destroy(&b);

  /* 3. element data */
  double *two = malloc(sizeof(double) * m->nelem);
  for (int e = 0; e < m->nelem; e++) two[e] = 2.0;
  FemMaterial mat2 = mat;
  mat2.par[0] = 2 * mu;
  TU_CHECK(cantilever(m, &mat, -0.05, two, &a));
  TU_CHECK(cantilever(m, &mat2, -0.05, NULL, &b));
  TU_CHECK(fem_solver_solve(a));
  TU_CHECK(fem_solver_solve(b));
  d = umax = 0;
  for (int i = 0; i < n3; i++) {
    d = fmax(d, fabs(fem_solver_displacements(a)[i] - fem_solver_displacements(b)[i]));
    umax = fmax(umax, fabs(fem_solver_displacements(b)[i]));
  }
  fails += tu_close("element data 2 x mu vs parameter 2 mu: max |du|", d, 0.0, 1e-12 * umax, 0.0);
  fem_solver_destroy(&a);
  fem_solver_destroy(&b);
  free(two);

  /* 5. recoverable failure of the law */
  FemMaterial tight = mat;
  tight.par[2] = 1 + 1e-9;
  FemSolverParams prm = fem_solver_params_default();
  prm.dl_min = 0.3;
  TU_CHECK(fem_solver_create(m, &tight, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *end = fem_mesh_find_surface(m, "end");
  double *f = calloc((size_t)3 * end->nnodes, sizeof *f);
  for (int k = 0; k < end->nnodes; k++) f[3 * k] = 1.0 / end->nnodes; /* tension: J > 1 */
  TU_CHECK(fem_solver_set_nodal_forces(s, end->nnodes, end->nodes, f));
  free(f);
  int rc = fem_solver_solve(s);
  fem_solver_report(s, &rep);
  if (rc == 0 || rep.newton_reason != FEM_DIVERGED_DOMAIN) {
    fprintf(stderr, "law domain error: rc %d, reason '%s'\n", rc,
            fem_newton_reason_string(rep.newton_reason));
    fails++;
  }
  sa_error_clear();
  fem_solver_destroy(&s);

  /* 6. input errors */
  FemMaterial bad;
  rc = fem_material_from_law("no_such_law", 0, NULL, NULL, 1.0, &bad);
  if (rc != SA_ERR_INPUT || !strstr(sa_error_message(), "no_such_law")) fails++, fprintf(stderr, "unknown law accepted\n");
  sa_error_clear();
  const char *wrong[] = {"mu", "lambda", "kmax"};
  rc = fem_material_from_law("test_compressible_neohooke", 3, wrong, par, 1.0, &bad);
  if (rc != SA_ERR_INPUT || !strstr(sa_error_message(), "kmax")) fails++, fprintf(stderr, "unknown parameter accepted\n");
  sa_error_clear();
  smesh_free(&m);
  return fails != 0;
}
