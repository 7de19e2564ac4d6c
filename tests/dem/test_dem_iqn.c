/* IQN-ILS (dem_coupling/dem_iqn.c) on linear fixed points x = A x + b, against the solution of
 * (I - A) x = b by Gaussian elimination with partial pivoting (independent of the method).
 *
 * - Unknowns n = 12, A random with spectral radius ~3 (plain substitution x <- A x + b
 *   diverges): IQN-ILS is GMRES in disguise on a linear map, so the residual vanishes after at
 *   most n + 1 evaluations of the map (checked: |x - x*| < 1e-8 |x*| within n + 2).
 * - Reuse: the next step with another b and the columns kept converges in one update (the
 *   model already spans the space), i.e. the second evaluation is the answer.
 * - Without reuse (reuse_steps = 0) the next step needs the full count again.
 * - With an initial relaxation w the update without columns is x + w (H(x) - x), and the solve
 *   still ends within n + 2 evaluations. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem_iqn.h"
#include "sa_error.h"

#define N 12

static unsigned long long rng = 88172645463325252ULL;
static double urand(void) { /* xorshift64, uniform in (-1, 1) */
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return 2.0 * (double)(rng >> 11) / 9007199254740992.0 - 1.0;
}

static void apply(const double *A, const double *b, const double *x, double *y) {
  for (int i = 0; i < N; i++) {
    y[i] = b[i];
    for (int j = 0; j < N; j++) y[i] += A[i * N + j] * x[j];
  }
}

/* (I - A) x = b by elimination with partial pivoting */
static void direct(const double *A, const double *b, double *x) {
  double M[N][N + 1];
  for (int i = 0; i < N; i++) {
    for (int j = 0; j < N; j++) M[i][j] = (i == j) - A[i * N + j];
    M[i][N] = b[i];
  }
  for (int k = 0; k < N; k++) {
    int p = k;
    for (int i = k + 1; i < N; i++) if (fabs(M[i][k]) > fabs(M[p][k])) p = i;
    for (int j = 0; j <= N; j++) { double t = M[k][j]; M[k][j] = M[p][j]; M[p][j] = t; }
    for (int i = k + 1; i < N; i++) {
      double f = M[i][k] / M[k][k];
      for (int j = k; j <= N; j++) M[i][j] -= f * M[k][j];
    }
  }
  for (int i = N - 1; i >= 0; i--) {
    double s = M[i][N];
    for (int j = i + 1; j < N; j++) s -= M[i][j] * x[j];
    x[i] = s / M[i][i];
  }
}

static double err(const double *x, const double *xs) {
  double e = 0, s = 0;
  for (int i = 0; i < N; i++) e += (x[i] - xs[i]) * (x[i] - xs[i]), s += xs[i] * xs[i];
  return sqrt(e / s);
}

/* Iterate one step from x = 0; returns the evaluations of the map until |x - x*| < 1e-8. */
static int solve_step(DemIqn *q, const double *A, const double *b, const double *xs) {
  double x[N] = {0}, xt[N], xn[N];
  dem_iqn_new_step(q);
  for (int k = 1; k <= 40; k++) {
    apply(A, b, x, xt);
    if (err(xt, xs) < 1e-8 && err(x, xs) < 1e-8) return k;
    dem_iqn_update(q, x, xt, xn);
    memcpy(x, xn, sizeof x);
  }
  return 99;
}

int main(void) {
  double A[N * N], b1[N], b2[N], x1[N], x2[N];
  for (int i = 0; i < N * N; i++) A[i] = 3.0 * urand() / sqrt((double)N) * 1.7;
  for (int i = 0; i < N; i++) b1[i] = urand(), b2[i] = urand();
  direct(A, b1, x1);
  direct(A, b2, x2);
  int fails = 0;
  /* plain substitution diverges on this A (the reason for the method) */
  double x[N] = {0}, y[N];
  for (int k = 0; k < 30; k++) apply(A, b1, x, y), memcpy(x, y, sizeof x);
  if (!(err(x, x1) > 1)) printf("substitution converged: A is not a hard case\n"), fails++;

  DemIqn *q = NULL;
  if (dem_iqn_create(N, 2 * N, 4, &q)) return sa_error_print(), 1;
  int k1 = solve_step(q, A, b1, x1), k2 = solve_step(q, A, b2, x2);
  printf("reuse: step 1 %d evaluations (limit %d), step 2 %d (limit 2)\n", k1, N + 2, k2);
  if (k1 > N + 2) fails++;
  if (k2 > 2) fails++;
  dem_iqn_destroy(&q);

  if (dem_iqn_create(N, 2 * N, 0, &q)) return sa_error_print(), 1;
  k1 = solve_step(q, A, b1, x1), k2 = solve_step(q, A, b2, x2);
  printf("no reuse: step 1 %d, step 2 %d evaluations (limit %d each)\n", k1, k2, N + 2);
  if (k1 > N + 2 || k2 > N + 2 || k2 < 3) fails++;
  dem_iqn_destroy(&q);

  /* initial relaxation w = 0.3: the update without columns is exactly x + w (A x + b - x), and
   * the method still solves the linear fixed point within n + 2 evaluations */
  if (dem_iqn_create(N, 2 * N, 0, &q)) return sa_error_print(), 1;
  dem_iqn_set_initial_relaxation(q, 0.3);
  dem_iqn_new_step(q);
  double x0[N], xt0[N], xn0[N], dmax = 0;
  for (int i = 0; i < N; i++) x0[i] = urand();
  apply(A, b1, x0, xt0);
  dem_iqn_update(q, x0, xt0, xn0);
  for (int i = 0; i < N; i++) dmax = fmax(dmax, fabs(xn0[i] - (x0[i] + 0.3 * (xt0[i] - x0[i]))));
  dem_iqn_clear(q);
  k1 = solve_step(q, A, b1, x1);
  printf("initial relaxation 0.3: first update off by %.3g, %d evaluations (limit %d)\n", dmax,
         k1, N + 2);
  if (dmax > 1e-15 || k1 > N + 2) fails++;
  dem_iqn_destroy(&q);
  printf("%s\n", fails ? "FAIL" : "PASS");
  return fails != 0;
}
