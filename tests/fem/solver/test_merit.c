/* test_merit - the energy merit line search and the modified Cholesky for indefinite tangents
 * (FEM_MERIT_ENERGY, FEM_INDEFINITE_MODIFY; docs/fem_time_to_accuracy.md), against
 * independent references.
 *
 * Body: the bar 1 x 0.2 x 0.2 (10 x 2 x 2 tet10 cells), nearly incompressible neo-Hookean
 * (mu = 1, kappa = 500 mu, the actuator's K/mu), clamped at x = 0; the end face x = 1 carries a
 * follower pressure and its rim is fixed, so p V(u) is the pressure's potential on the free dofs
 * (docs/fem.md) and Pi = W - p V is the total potential.
 *  1. Finite difference of Pi: at a state that is not an equilibrium (converged at p1, evaluated
 *     at p2 = 3 p1), R.v against (Pi(u + h v) - Pi(u - h v)) / 2h. The central difference errs
 *     by h^2 Pi'''/6, large here (kappa = 500 and |v| ~ 10: measured 3e-1 at h = 1e-4, 3e-3
 *     at 1e-5, 3e-5 at 1e-6); an inconsistent merit would leave an O(1) error instead. Checked:
 *     relative error <= 1e-4 at h = 1e-6 and e(h)/e(2h) = 0.25 +- 0.05 (second order).
 *  2. The same equilibria: a ramp in two large increments with the defaults (lazy merit, LU for
 *     indefinite tangents) and with energy merit + modified Cholesky reaches the same
 *     displacement to 1e-8 relative (both converge to rtol = 1e-8 of the force scale; the
 *     equilibrium is unique on this stable path).
 *  4. PCG directions (krylov_max = 20, krylov_rtol = 1e-3) preconditioned by the last Cholesky
 *     factors: the same equilibrium to 1e-8, and at least one PCG direction taken.
 *  3. A pressure surface whose rim slides (the cylinder-like case where V is not the
 *     potential): the solver switches the energy merit off and still converges to the default
 *     path's equilibrium. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static int build(const FemMesh *m, const FemMaterial *mat, const FemSolverParams *prm,
                 int fix_rim, FemSolver **out) {
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, mat, prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "clamp", FEM_XYZ));
  if (fix_rim) {
    const FemSurface *end = fem_mesh_find_surface(m, "end");
    for (int k = 0; k < end->nnodes; k++) {
      const double *X = m->xyz + 3 * end->nodes[k];
      int rim = fabs(X[1]) < 1e-12 || fabs(X[1] - 0.2) < 1e-12 || fabs(X[2]) < 1e-12 ||
                fabs(X[2] - 0.2) < 1e-12;
      if (rim) TU_CHECK(fem_solver_fix_nodes(s, 1, &end->nodes[k], FEM_XYZ));
    }
  }
  TU_CHECK(fem_solver_add_pressure_surface(s, "end"));
  TU_CHECK(fem_solver_setup(s));
  *out = s;
  return 0;
}

/* Ramp to p in two increments; u [out] 3 nnodes. */
static int ramp(FemSolver *s, int n, double p, double *u, FemSolverStats *st) {
  for (int k = 1; k <= 2; k++) {
    TU_CHECK(fem_solver_set_pressure(s, p * k / 2));
    TU_CHECK(fem_solver_solve(s));
  }
  const double *ud = fem_solver_displacements(s);
  for (int i = 0; i < n; i++) u[i] = ud[i];
  fem_solver_stats(s, st);
  return 0;
}

static double rel_diff(const double *a, const double *b, int n) {
  double num = 0, den = 0;
  for (int i = 0; i < n; i++) {
    num += (a[i] - b[i]) * (a[i] - b[i]);
    den += b[i] * b[i];
  }
  return sqrt(num / fmax(den, 1e-300));
}

int main(void) {
  int verbose = getenv("SA_TEST_VERBOSE") != NULL;
  sa_log_set_level(verbose ? SA_LOG_DEBUG : SA_LOG_WARN);
  SmeshBlock blk = {{10, 2, 2}, smesh_map_bar, NULL, {"clamp", "end", "front", "back", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 500, .rho = 1};
  int fails = 0, n = 3 * m->nnodes;
  const double p = -1.0; /* suction on the end face: it bulges outward, rim held */

  /* 1: finite difference of the potential off equilibrium */
  FemSolver *s;
  TU_CHECK(build(m, &mat, NULL, 1, &s));
  TU_CHECK(fem_solver_set_pressure(s, p / 3));
  TU_CHECK(fem_solver_solve(s));
  double e1, e2;
  TU_CHECK(fem_solver_check_potential(s, p, 2e-6, &e1));
  TU_CHECK(fem_solver_check_potential(s, p, 1e-6, &e2));
  if (verbose) printf("potential FD check: rel err %.3e (h = 2e-6), %.3e (h = 1e-6)\n", e1, e2);
  fails += tu_close("energy merit: R.v against the central difference of Pi, h = 1e-6", e2, 0.0,
                    1e-4, 0.0);
  fails += tu_close("energy merit: FD error ratio e(h)/e(2h) (O(h^2): 0.25)", e2 / e1, 0.25, 0.05,
                    0.0);
  fem_solver_destroy(&s);

  /* 2: same equilibrium with the defaults and with energy merit + modified Cholesky */
  double *u0 = malloc(sizeof(double) * n), *u1 = malloc(sizeof(double) * n);
  FemSolverStats st0, st1;
  TU_CHECK(build(m, &mat, NULL, 1, &s));
  TU_CHECK(ramp(s, n, p, u0, &st0));
  fem_solver_destroy(&s);
  FemSolverParams prm = fem_solver_params_default();
  prm.merit = FEM_MERIT_ENERGY;
  prm.indefinite = FEM_INDEFINITE_MODIFY;
  TU_CHECK(build(m, &mat, &prm, 1, &s));
  TU_CHECK(ramp(s, n, p, u1, &st1));
  fem_solver_destroy(&s);
  double d = rel_diff(u1, u0, n);
  if (st1.n_ls_energy == 0) {
    fprintf(stderr, "rim fixed: no energy backtrack (the test should exercise the line search)\n");
    fails++;
  }
  if (verbose)
    printf("rim fixed: defaults %d factorisations (%d LU), energy+modify %d (%d LU, %d modified, "
           "%d energy backtracks); |u1 - u0|/|u0| = %.3e\n", st0.n_factor, st0.n_lu, st1.n_factor,
           st1.n_lu, st1.n_modified, st1.n_ls_energy, d);
  fails += tu_close("energy + modify: displacement against the default path (relative)", d, 0.0,
                    1e-8, 0.0);

  /* 4 (before 3 reuses prm): PCG on the last factors reaches the direct path's equilibrium */
  prm.krylov_max = 20;
  TU_CHECK(build(m, &mat, &prm, 1, &s));
  TU_CHECK(ramp(s, n, p, u1, &st1));
  fem_solver_destroy(&s);
  d = rel_diff(u1, u0, n);
  if (verbose)
    printf("krylov: %d factorisations, %d PCG directions (%d PCG iterations, %d abandoned); "
           "|u1 - u0|/|u0| = %.3e\n", st1.n_factor, st1.n_krylov, st1.n_krylov_it,
           st1.n_krylov_fail, d);
  fails += tu_close("PCG on earlier factors: displacement against the direct path (relative)", d,
                    0.0, 1e-8, 0.0);
  if (st1.n_krylov == 0) {
    fprintf(stderr, "krylov: no PCG direction taken (the test should exercise it)\n");
    fails++;
  }
  /* 5: the whole ramp in one increment (energy merit, modify, PCG): the energy stall rule
   * and the step-back when even K_int is indefinite let one substep reach case 2's
   * equilibrium (unique on this stable path) */
  prm.dl_init = 1.0;
  TU_CHECK(build(m, &mat, &prm, 1, &s));
  TU_CHECK(fem_solver_set_pressure(s, p));
  TU_CHECK(fem_solver_solve(s));
  FemSolveReport rep;
  fem_solver_report(s, &rep);
  fem_solver_stats(s, &st1);
  const double *ud = fem_solver_displacements(s);
  for (int i = 0; i < n; i++) u1[i] = ud[i];
  fem_solver_destroy(&s);
  d = rel_diff(u1, u0, n); /* u0: case 2's default path */
  fails += tu_close("one increment: displacement against the two-increment default path", d, 0.0,
                    1e-8, 0.0);
  if (verbose)
    printf("one increment to p: %d substeps, %d cuts, %d Newton iterations, %d step-backs on an "
           "indefinite K_int, %d energy backtracks\n", rep.substeps, rep.cuts, rep.newton_iters,
           st1.n_indef_backtrack, st1.n_ls_energy);
  prm.krylov_max = 0;

  /* 3: rim free (V is not the potential): merit switched off, same equilibrium */
  prm.indefinite = FEM_INDEFINITE_LU;
  TU_CHECK(build(m, &mat, NULL, 0, &s));
  TU_CHECK(ramp(s, n, 0.25 * p, u0, &st0));
  fem_solver_destroy(&s);
  TU_CHECK(build(m, &mat, &prm, 0, &s));
  TU_CHECK(ramp(s, n, 0.25 * p, u1, &st1));
  fem_solver_destroy(&s);
  d = rel_diff(u1, u0, n);
  if (verbose) printf("rim free: |u1 - u0|/|u0| = %.3e, energy backtracks %d\n", d, st1.n_ls_energy);
  fails += tu_close("rim free, energy merit requested: displacement against the default path", d,
                    0.0, 1e-8, 0.0);
  if (st1.n_ls_energy != 0) {
    fprintf(stderr, "rim free: %d energy backtracks (expected 0: the merit must be off)\n",
            st1.n_ls_energy);
    fails++;
  }
  free(u0);
  free(u1);
  smesh_free(&m);
  return fails ? 1 : 0;
}
