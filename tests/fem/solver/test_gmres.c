/* test_gmres - restarted right-preconditioned GMRES (fem_gmres.h) on matrices with known
 * answers, and the unrefined factor solve it uses as its preconditioner.
 *
 * Matrix: 2-D convection-diffusion on an m x m grid (five-point Laplacian plus a centred
 * first-order convection term c: unsymmetric, nonsingular). The exact solution x* is chosen
 * and b = A x* built by a matrix-vector product, so the reference is independent of the
 * solvers. Checks:
 *  1. finite termination: unpreconditioned, one cycle as long as the order n, GMRES reaches x*
 *     (exact arithmetic: at most n iterations; here |x - x*| <= 1e-8 |x*|);
 *  2. preconditioned by the exact LU factors of A, one iteration, to round-off;
 *  3. preconditioned by the LU factors of another matrix (convection 30 % weaker, diffusion
 *     10 % stronger), the way Newton uses an earlier tangent's factors: the returned x meets
 *     |b - A x| <= rtol |b| (computed here, not taken from GMRES) for rtol 1e-3 and 1e-10, in
 *     fewer iterations than without a preconditioner, and with restarts (m = 5) as well;
 *  4. an iteration limit too small returns "not converged" (1);
 *  5. fem_linsolve_solve_factors is a fixed operator: after the values array handed to the LU
 *     is overwritten, it returns the same vector, bit for bit (the refined solve need not: it
 *     refines against the values now held, which is no linear preconditioner). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_gmres.h"
#include "fem_linsolve.h"
#include "grid_matrix.h"
#include "sa_error.h"

#define M 12
#define N (M * M)

static int colptr[N + 1], rowind[5 * N];

static void build(double diag, double conv, double *val) {
  grid_matrix(M, diag, conv, colptr, rowind, val);
}

static void matvec(const double *val, const double *x, double *y) {
  memset(y, 0, N * sizeof *y);
  for (int j = 0; j < N; j++)
    for (int k = colptr[j]; k < colptr[j + 1]; k++) y[rowind[k]] += val[k] * x[j];
}

static double nrm(const double *a) {
  double s = 0;
  for (int i = 0; i < N; i++) s += a[i] * a[i];
  return sqrt(s);
}

static int identity(void *ctx, const double *r, double *z) {
  (void)ctx;
  memcpy(z, r, N * sizeof *z);
  return 0;
}

static int factors(void *ctx, const double *r, double *z) {
  return fem_linsolve_solve_factors(ctx, r, z);
}

static double A[5 * N], P[5 * N], xs[N], b[N], x[N], w[N];

/* |b - A x| / |b| of the x returned */
static double relres(void) {
  matvec(A, x, w);
  for (int i = 0; i < N; i++) w[i] = b[i] - w[i];
  return nrm(w) / nrm(b);
}

static int check(const char *what, int ok) {
  if (!ok) fprintf(stderr, "FAIL: %s\n", what);
  return !ok;
}

int main(void) {
  int fail = 0, its, rc;
  build(4.0, 0.4, A);
  for (int i = 0; i < N; i++) xs[i] = sin(0.3 * i) + 0.1 * i;
  matvec(A, xs, b);
  FemGmres g;
  if (fem_gmres_alloc(&g, N, N)) return sa_error_print(), 1;

  /* 1. finite termination without a preconditioner (not abandoned for slowness: unpreconditioned
   * GMRES speeds up late) */
  g.abandon = 0;
  rc = fem_gmres_solve(&g, colptr, rowind, A, b, x, N, 1e-13, identity, NULL, &its);
  double err = 0;
  for (int i = 0; i < N; i++) err = fmax(err, fabs(x[i] - xs[i]));
  int its_plain = 0;
  fem_gmres_solve(&g, colptr, rowind, A, b, x, N, 1e-10, identity, NULL, &its_plain);
  printf("1. no preconditioner: %d iterations to 1e-13, |x - x*|_inf %.2e; %d to 1e-10\n", its,
         err, its_plain);
  fail |= check("1. converges within n iterations", rc == 0 && its <= N);
  fail |= check("1. |x - x*| <= 1e-8 |x*|", err <= 1e-8 * nrm(xs));

  /* 2. exact factors: one iteration */
  FemLinSolver *lin;
  if (fem_linsolve_create(N, colptr, rowind, 1, &lin) || fem_linsolve_factorize(lin, A, 0))
    return sa_error_print(), 1;
  rc = fem_gmres_solve(&g, colptr, rowind, A, b, x, 50, 1e-12, factors, lin, &its);
  printf("2. exact LU: %d iteration(s), |b - A x|/|b| %.2e\n", its, relres());
  fail |= check("2. one iteration with the exact factors", rc == 0 && its == 1);
  fail |= check("2. residual <= 1e-12", relres() <= 1e-12);

  /* 3. factors of another matrix */
  build(4.4, 0.28, P);
  if (fem_linsolve_factorize(lin, P, 0)) return sa_error_print(), 1;
  for (int m = 0; m < 2; m++) {
    FemGmres gm;
    if (fem_gmres_alloc(&gm, N, m ? 5 : 40)) return sa_error_print(), 1;
    double tols[2] = {1e-3, 1e-10};
    for (int t = 0; t < 2; t++) {
      rc = fem_gmres_solve(&gm, colptr, rowind, A, b, x, 100, tols[t], factors, lin, &its);
      double rr = relres();
      printf("3. earlier factors, restart %d, rtol %.0e: %d iterations, |b - A x|/|b| %.2e "
             "(unpreconditioned to 1e-10: %d)\n", gm.m, tols[t], its, rr, its_plain);
      char what[120];
      snprintf(what, sizeof what, "3. restart %d rtol %.0e: converged, true residual <= rtol",
               gm.m, tols[t]);
      fail |= check(what, rc == 0 && rr <= tols[t]);
      if (t == 1) fail |= check("3. fewer iterations than unpreconditioned", its < its_plain);
    }
    fem_gmres_free(&gm);
  }

  g.abandon = 1;
  /* 4. iteration limit */
  rc = fem_gmres_solve(&g, colptr, rowind, A, b, x, 2, 1e-12, identity, NULL, &its);
  fail |= check("4. limit of 2 iterations: not converged", rc == 1 && its <= 2);

  /* 5. the unrefined solve is a fixed operator */
  double z0[N], z1[N];
  fem_linsolve_solve_factors(lin, b, z0);
  double saveP[5 * N];
  memcpy(saveP, P, sizeof P);
  memcpy(P, A, sizeof P); /* the values the LU was handed now hold another matrix */
  fem_linsolve_solve_factors(lin, b, z1);
  fail |= check("5. solve_factors unchanged when the values change", !memcmp(z0, z1, sizeof z0));
  memcpy(P, saveP, sizeof P);

  fem_gmres_free(&g);
  fem_linsolve_destroy(&lin);
  if (!fail) printf("test_gmres: all checks passed\n");
  return fail;
}
