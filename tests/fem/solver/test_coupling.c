/* test_coupling - the API the FEM-DEM coupling uses: external nodal forces.
 *
 * 1. Solve a cantilever block (tet10, neo-Hookean, clamped at x = 0) under a follower
 *    pressure on its top face; take the pressure's nodal forces at the converged state and give
 *    them to a second solver as dead nodal forces (no pressure surface). The second solve must
 *    reproduce the first displacement field: both are equilibria of the same forces at the
 *    same configuration, solved to rtol 1e-8, so |u_B - u_A|_inf <= 1e-6 |u_A|_inf.
 * 2. Repeated coupling calls (set_nodal_forces + solve with forces that change by 0.1 % per
 *    call) make no allocation in softact code: malloc/calloc/realloc are wrapped at link time
 *    (-Wl,--wrap) for this executable, which links libsa_fem statically, and counted. (CHOLMOD's
 *    own per-factorisation workspace inside libcholmod.so is not counted.) The time per call
 *    is printed with SA_TEST_VERBOSE=1.
 * 3. The same calls with the factor-reusing options (predictor REUSE: the first iteration of
 *    each call reuses the last factors; reuse_rate 0.3: modified Newton within a call) reach
 *    the same equilibria (|u_C - u_B|_inf <= 1e-6 |u_B|_inf after the last call: both solved to
 *    rtol 1e-8) with fewer factorisations. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static long n_alloc;
void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t m);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n) {
  n_alloc++;
  return __real_malloc(n);
}
void *__wrap_calloc(size_t n, size_t m) {
  n_alloc++;
  return __real_calloc(n, m);
}
void *__wrap_realloc(void *p, size_t n) {
  n_alloc++;
  return __real_realloc(p, n);
}

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_WARN);
  SmeshBlock blk = {{12, 3, 3}, smesh_map_bar, NULL, {"clamp", "end", "front", "back", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 50, .rho = 1};
  int n3 = 3 * m->nnodes, fails = 0;
  FemSolver *a, *b;
  TU_CHECK(fem_solver_create(m, &mat, NULL, &a));
  TU_CHECK(fem_solver_fix_surface(a, "clamp", FEM_XYZ));
  TU_CHECK(fem_solver_add_pressure_surface(a, "top"));
  TU_CHECK(fem_solver_setup(a));
  TU_CHECK(fem_solver_set_pressure(a, 1e-3));
  TU_CHECK(fem_solver_solve(a));
  double *f = malloc(sizeof(double) * n3), *f2 = malloc(sizeof(double) * n3);
  int *all = malloc(sizeof(int) * m->nnodes);
  for (int i = 0; i < m->nnodes; i++) all[i] = i;
  TU_CHECK(fem_solver_pressure_forces(a, f));

  TU_CHECK(fem_solver_create(m, &mat, NULL, &b));
  TU_CHECK(fem_solver_fix_surface(b, "clamp", FEM_XYZ));
  TU_CHECK(fem_solver_setup(b));
  TU_CHECK(fem_solver_set_nodal_forces(b, m->nnodes, all, f));
  TU_CHECK(fem_solver_solve(b));
  const double *ua = fem_solver_displacements(a), *ub = fem_solver_displacements(b);
  double dmax = 0, umax = 0;
  for (int d = 0; d < n3; d++) {
    dmax = fmax(dmax, fabs(ub[d] - ua[d]));
    umax = fmax(umax, fabs(ua[d]));
  }
  fails += tu_close("nodal forces reproduce the pressure solution: max |u_B - u_A|", dmax, 0.0,
                    1e-6 * umax, 0.0);
  if (!(umax > 0.05)) {
    fprintf(stderr, "deflection %.3g too small to test anything\n", umax);
    fails++;
  }

  /* repeated calls: warm-up one, then count */
  const int ncalls = 10;
  for (int d = 0; d < n3; d++) f2[d] = 1.001 * f[d];
  TU_CHECK(fem_solver_set_nodal_forces(b, m->nnodes, all, f2));
  TU_CHECK(fem_solver_solve(b));
  FemSolverStats sb0;
  fem_solver_stats(b, &sb0);
  long before = n_alloc;
  double t0 = sa_time_now();
  for (int k = 0; k < ncalls; k++) {
    double sc = (k % 2) ? 1.001 : 0.999;
    for (int d = 0; d < n3; d++) f2[d] = sc * f[d];
    TU_CHECK(fem_solver_set_nodal_forces(b, m->nnodes, all, f2));
    TU_CHECK(fem_solver_solve(b));
    (void)fem_solver_positions(b);
    (void)fem_solver_velocities(b);
  }
  double dt = (sa_time_now() - t0) / ncalls;
  long allocs = n_alloc - before;
  FemSolveReport rep;
  fem_solver_report(b, &rep);
  FemSolverStats st;
  fem_solver_stats(b, &st);
  if (getenv("SA_TEST_VERBOSE"))
    printf("%d free dofs: %.2f ms per set/solve call (%d Newton iterations in the last), %ld "
           "allocations in %d calls\n", st.nfree, 1e3 * dt, rep.newton_iters, allocs, ncalls);
  if (allocs != 0) {
    fprintf(stderr, "%ld allocations in softact code during %d coupling calls\n", allocs, ncalls);
    fails++;
  }

  /* 3. factor reuse across and within coupling calls */
  FemSolverParams prm = fem_solver_params_default();
  prm.predictor = FEM_PREDICT_REUSE;
  prm.reuse_rate = 0.3;
  FemSolver *c;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &c));
  TU_CHECK(fem_solver_fix_surface(c, "clamp", FEM_XYZ));
  TU_CHECK(fem_solver_setup(c));
  for (int d = 0; d < n3; d++) f2[d] = 1.001 * f[d];
  TU_CHECK(fem_solver_set_nodal_forces(c, m->nnodes, all, f));
  TU_CHECK(fem_solver_solve(c));
  TU_CHECK(fem_solver_set_nodal_forces(c, m->nnodes, all, f2));
  TU_CHECK(fem_solver_solve(c));
  FemSolverStats sc0;
  fem_solver_stats(c, &sc0);
  for (int k = 0; k < ncalls; k++) {
    double sc = (k % 2) ? 1.001 : 0.999;
    for (int d = 0; d < n3; d++) f2[d] = sc * f[d];
    TU_CHECK(fem_solver_set_nodal_forces(c, m->nnodes, all, f2));
    TU_CHECK(fem_solver_solve(c));
  }
  FemSolverStats sc1;
  fem_solver_stats(c, &sc1);
  const double *uc = fem_solver_displacements(c);
  ub = fem_solver_displacements(b);
  dmax = umax = 0;
  for (int d = 0; d < n3; d++) {
    dmax = fmax(dmax, fabs(uc[d] - ub[d]));
    umax = fmax(umax, fabs(ub[d]));
  }
  fails += tu_close("factor reuse reaches the same equilibrium: max |u_C - u_B|", dmax, 0.0,
                    1e-6 * umax, 0.0);
  int ncf = sc1.n_factor - sc0.n_factor;
  if (getenv("SA_TEST_VERBOSE"))
    printf("coupling calls with factor reuse: %d factorisations, %d reused directions\n", ncf,
           sc1.n_reuse - sc0.n_reuse);
  int nbf = st.n_factor - sb0.n_factor;
  if (getenv("SA_TEST_VERBOSE")) printf("full Newton: %d factorisations\n", nbf);
  if (!(ncf < nbf)) {
    fprintf(stderr, "factor reuse: %d factorisations in %d calls, full Newton %d\n", ncf,
            ncalls, nbf);
    fails++;
  }
  fem_solver_destroy(&c);
  fem_solver_destroy(&a);
  fem_solver_destroy(&b);
  smesh_free(&m);
  free(f);
  free(f2);
  free(all);
  return fails ? 1 : 0;
}
