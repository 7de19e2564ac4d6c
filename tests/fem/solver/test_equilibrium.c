/* test_equilibrium - global equilibrium and the symmetry of the pressure load stiffness.
 *
 * A cantilever block 1 x 0.2 x 0.2 (clamped at x = 0, tet10, compressible neo-Hookean
 * mu = 1, kappa = 20) under a follower pressure on its top face and its free end face, bent
 * well into the nonlinear range. Checks:
 *  1. force balance: the support reactions at the clamped nodes plus the resultant of the
 *     deformed-configuration pressure forces vanish, |R + F| <= 1e-6 |F| (Newton converged to
 *     rtol 1e-8 of the force scale; the residual of the free dofs is the only imbalance);
 *     moment balance about the origin likewise;
 *  2. the pressure faces have free rims, so the assembled tangent is unsymmetric and the solver
 *     must have used the LU fallback (asymmetry >= 1e-6);
 *  3. with the rim of the loaded end face fixed, the load stiffness on the free dofs is
 *     symmetric (a potential -p V exists): asymmetry <= 1e-12, and the solve uses CHOLMOD only.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_WARN);
  SmeshBlock blk = {{10, 2, 2}, smesh_map_bar, NULL, {"clamp", "end", "front", "back", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 20, .rho = 1};
  int fails = 0;

  /* 1 + 2: open pressure surfaces */
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, NULL, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  TU_CHECK(fem_solver_add_pressure_surface(s, "top"));
  TU_CHECK(fem_solver_add_pressure_surface(s, "end"));
  TU_CHECK(fem_solver_setup(s));
  TU_CHECK(fem_solver_set_pressure(s, 2e-3));
  TU_CHECK(fem_solver_solve(s));
  int n3 = 3 * m->nnodes;
  double *r = malloc(sizeof(double) * n3), *f = malloc(sizeof(double) * n3);
  TU_CHECK(fem_solver_reactions(s, r));
  TU_CHECK(fem_solver_pressure_forces(s, f));
  const double *x = fem_solver_positions(s);
  const FemSurface *cl = fem_mesh_find_surface(m, "clamp");
  double R[3] = {0}, F[3] = {0}, MR[3] = {0}, MF[3] = {0}, F2[3];
  for (int k = 0; k < cl->nnodes; k++) {
    int A = cl->nodes[k];
    const double *xa = x + 3 * A, *ra = r + 3 * A;
    for (int i = 0; i < 3; i++) R[i] += ra[i];
    MR[0] += xa[1] * ra[2] - xa[2] * ra[1];
    MR[1] += xa[2] * ra[0] - xa[0] * ra[2];
    MR[2] += xa[0] * ra[1] - xa[1] * ra[0];
  }
  for (int A = 0; A < m->nnodes; A++) {
    const double *xa = x + 3 * A, *fa = f + 3 * A;
    for (int i = 0; i < 3; i++) F[i] += fa[i];
    MF[0] += xa[1] * fa[2] - xa[2] * fa[1];
    MF[1] += xa[2] * fa[0] - xa[0] * fa[2];
    MF[2] += xa[0] * fa[1] - xa[1] * fa[0];
  }
  TU_CHECK(fem_solver_pressure_resultant(s, F2));
  double Fn = sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
  double Mn = sqrt(MF[0] * MF[0] + MF[1] * MF[1] + MF[2] * MF[2]);
  const char *ax = "xyz";
  for (int i = 0; i < 3; i++) {
    char w[64];
    snprintf(w, sizeof w, "force balance %c", ax[i]);
    fails += tu_close(w, R[i] + F[i], 0.0, 1e-6 * Fn, 0);
    snprintf(w, sizeof w, "moment balance %c", ax[i]);
    fails += tu_close(w, MR[i] + MF[i], 0.0, 1e-6 * Mn, 0);
    snprintf(w, sizeof w, "pressure resultant %c", ax[i]);
    fails += tu_close(w, F2[i], F[i], 1e-12 * Fn, 0);
  }
  const double *u = fem_solver_displacements(s);
  double tipz = 0;
  for (int A = 0; A < m->nnodes; A++) tipz = fmin(tipz, u[3 * A + 2]);
  FemSolverStats st;
  fem_solver_stats(s, &st);
  double asym = fem_solver_tangent_asymmetry(s);
  if (getenv("SA_TEST_VERBOSE"))
    printf("open surfaces: tip deflection %.4f, |F| %.4g, R+F = (%.2e %.2e %.2e), asym %.2e, "
           "LU %d, Cholesky %d\n", tipz, Fn, R[0] + F[0], R[1] + F[1], R[2] + F[2], asym,
           st.n_lu, st.n_chol);
  if (!(tipz < -0.1)) {
    fprintf(stderr, "block not bent into the nonlinear range (tip %.4f)\n", tipz);
    fails++;
  }
  if (!(asym >= 1e-6) || st.n_lu == 0) {
    fprintf(stderr, "open pressure surface: asymmetry %.3g, LU factorisations %d (expected an "
            "unsymmetric tangent solved by LU)\n", asym, st.n_lu);
    fails++;
  }
  fem_solver_destroy(&s);

  /* 3: end face loaded, its rim fixed -> symmetric */
  TU_CHECK(fem_solver_create(m, &mat, NULL, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  const FemSurface *end = fem_mesh_find_surface(m, "end");
  for (int k = 0; k < end->nnodes; k++) {
    const double *X = m->xyz + 3 * end->nodes[k];
    int rim = fabs(X[1]) < 1e-12 || fabs(X[1] - 0.2) < 1e-12 || fabs(X[2]) < 1e-12 ||
              fabs(X[2] - 0.2) < 1e-12;
    if (rim) TU_CHECK(fem_solver_fix_nodes(s, 1, &end->nodes[k], FEM_XYZ));
  }
  TU_CHECK(fem_solver_add_pressure_surface(s, "end"));
  TU_CHECK(fem_solver_setup(s));
  TU_CHECK(fem_solver_set_pressure(s, -0.05)); /* suction: the end face bulges outward */
  TU_CHECK(fem_solver_solve(s));
  asym = fem_solver_tangent_asymmetry(s);
  fem_solver_stats(s, &st);
  if (getenv("SA_TEST_VERBOSE"))
    printf("rim fixed: asym %.2e, LU %d, Cholesky %d\n", asym, st.n_lu, st.n_chol);
  if (!(asym <= 1e-12) || st.n_lu != 0) {
    fprintf(stderr, "rim fixed: asymmetry %.3g (expected <= 1e-12), LU factorisations %d\n",
            asym, st.n_lu);
    fails++;
  }
  fem_solver_destroy(&s);
  smesh_free(&m);
  free(r);
  free(f);
  return fails ? 1 : 0;
}
