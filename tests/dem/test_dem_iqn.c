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
 *   still ends within n + 2 evaluations.
 * - The trust region (dem_iqn_limit_step, [coupling] max_trial_change): a long update is
 *   shortened along its direction so that its farthest node (xyz triples) moves exactly the
 *   limit, a short one is left bit for bit; with every iterate so limited, the method still
 *   reaches the fixed point (it takes more evaluations: the limit makes it walk there). */
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

  /* trust region: geometry of one limited update */
  double xa[N], xb[N], xc[N];
  for (int i = 0; i < N; i++) xa[i] = urand(), xb[i] = xa[i] + 2 * urand();
  double big = 0;
  for (int v = 0; v < N; v += 3)
    big = fmax(big, sqrt(pow(xb[v] - xa[v], 2) + pow(xb[v + 1] - xa[v + 1], 2) +
                         pow(xb[v + 2] - xa[v + 2], 2)));
  memcpy(xc, xb, sizeof xc);
  double L = 0.25 * big, f = dem_iqn_limit_step(xa, xc, N, L), far = 0, par = 0;
  for (int v = 0; v < N; v += 3)
    far = fmax(far, sqrt(pow(xc[v] - xa[v], 2) + pow(xc[v + 1] - xa[v + 1], 2) +
                         pow(xc[v + 2] - xa[v + 2], 2)));
  for (int i = 0; i < N; i++) par = fmax(par, fabs((xc[i] - xa[i]) - 0.25 * (xb[i] - xa[i])));
  memcpy(xc, xb, sizeof xc);
  double f2 = dem_iqn_limit_step(xa, xc, N, 1.01 * big), f0 = dem_iqn_limit_step(xa, xc, N, 0);
  int same = !memcmp(xc, xb, sizeof xc);
  printf("trust region: factor %.17g (0.25), farthest node %.3g of the limit, off the direction "
         "by %.3g; unlimited: factors %g %g, unchanged %d\n", f, far / L, par, f2, f0, same);
  if (fabs(f - 0.25) > 1e-14 || fabs(far / L - 1) > 1e-14 || par > 1e-14 * big || f2 != 1 ||
      f0 != 1 || !same)
    fails++;
  /* every iterate limited to a fifth of the solution's largest node: still converges */
  double sol = 0;
  for (int v = 0; v < N; v += 3)
    sol = fmax(sol, sqrt(x1[v] * x1[v] + x1[v + 1] * x1[v + 1] + x1[v + 2] * x1[v + 2]));
  if (dem_iqn_create(N, 2 * N, 0, &q)) return sa_error_print(), 1;
  dem_iqn_new_step(q);
  double xl[N] = {0}, xtl[N], xnl[N];
  int kl = 0, limited = 0;
  for (kl = 1; kl <= 60; kl++) {
    apply(A, b1, xl, xtl);
    if (err(xtl, x1) < 1e-8 && err(xl, x1) < 1e-8) break;
    dem_iqn_update(q, xl, xtl, xnl);
    limited += dem_iqn_limit_step(xl, xnl, N, 0.2 * sol) < 1;
    memcpy(xl, xnl, sizeof xl);
  }
  printf("trust region 0.2 of the solution: %d evaluations (limit 60), %d updates shortened\n",
         kl, limited);
  if (kl > 60 || limited < 4) fails++;
  dem_iqn_destroy(&q);
  printf("%s\n", fails ? "FAIL" : "PASS");
  return fails != 0;
}
