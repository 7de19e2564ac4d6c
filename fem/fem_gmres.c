/* fem_gmres.c - restarted GMRES(m) with right preconditioning (Saad and Schultz 1986; Saad,
 * "Iterative methods for sparse linear systems", 2nd ed., algorithm 9.5), for Newton directions
 * of an unsymmetric tangent (frictional contact, non-associated plasticity) preconditioned by
 * the factors of an earlier tangent, where PCG does not apply.
 *
 * Right preconditioning solves K M^-1 y = b, x = M^-1 y: the residual GMRES minimises is the
 * true one, |b - K x|, so the stop |b - K x| <= rtol |b| is the same test as PCG's. Givens
 * rotations keep that residual norm at every iteration without forming x. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem_gmres.h"
#include "sa_error.h"

int fem_gmres_alloc(FemGmres *g, int n, int m) {
  memset(g, 0, sizeof *g);
  g->n = n;
  g->m = m;
  g->abandon = 1;
  SA_CALLOC(g->V, (size_t)n * (m + 1));
  SA_CALLOC(g->H, (size_t)(m + 1) * m);
  SA_CALLOC(g->cs, m);
  SA_CALLOC(g->sn, m);
  SA_CALLOC(g->gv, m + 1);
  SA_CALLOC(g->y, m);
  SA_CALLOC(g->w, n);
  SA_CALLOC(g->z, n);
  return 0;
}

void fem_gmres_free(FemGmres *g) {
  void *p[] = {g->V, g->H, g->cs, g->sn, g->gv, g->y, g->w, g->z};
  for (size_t i = 0; i < sizeof p / sizeof *p; i++) free(p[i]);
  memset(g, 0, sizeof *g);
}

static double dot(const double *a, const double *b, int n) {
  double s = 0.0;
  for (int i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

/* q = K p (K: full compressed-column pattern). */
static void matvec(int n, const int *cp, const int *ri, const double *K, const double *p,
                   double *q) {
  memset(q, 0, (size_t)n * sizeof *q);
  for (int j = 0; j < n; j++) {
    double pj = p[j];
    for (int k = cp[j]; k < cp[j + 1]; k++) q[ri[k]] += K[k] * pj;
  }
}

/* x += M^-1 (V y) over the first k basis vectors. */
static int update(FemGmres *g, int k, double *x, FemPrecond pc, void *ctx) {
  const int n = g->n, m = g->m;
  for (int i = k - 1; i >= 0; i--) { /* back substitution, H upper triangular after Givens */
    double s = g->gv[i];
    for (int j = i + 1; j < k; j++) s -= g->H[j * (m + 1) + i] * g->y[j];
    g->y[i] = s / g->H[i * (m + 1) + i];
  }
  memset(g->w, 0, (size_t)n * sizeof *g->w);
  for (int j = 0; j < k; j++) {
    const double *v = g->V + (size_t)j * n;
    for (int i = 0; i < n; i++) g->w[i] += g->y[j] * v[i];
  }
  SA_CHECK(pc(ctx, g->w, g->z));
  for (int i = 0; i < n; i++) x[i] += g->z[i];
  return 0;
}

int fem_gmres_solve(FemGmres *g, const int *cp, const int *ri, const double *K, const double *b,
                    double *x, int maxit, double rtol, FemPrecond pc, void *ctx, int *its) {
  const int n = g->n, m = g->m;
  memset(x, 0, (size_t)n * sizeof *x);
  *its = 0;
  double bn = sqrt(dot(b, b, n));
  if (bn == 0.0) return 0;
  double rel = 1.0;
  while (*its < maxit) {
    /* r = b - K x into V[0] */
    double *v0 = g->V;
    if (*its == 0) {
      memcpy(v0, b, (size_t)n * sizeof *v0);
    } else {
      matvec(n, cp, ri, K, x, g->w);
      for (int i = 0; i < n; i++) v0[i] = b[i] - g->w[i];
    }
    double beta = sqrt(dot(v0, v0, n));
    rel = beta / bn;
    if (rel <= rtol) return 0;
    for (int i = 0; i < n; i++) v0[i] /= beta;
    memset(g->gv, 0, (size_t)(m + 1) * sizeof *g->gv);
    g->gv[0] = beta;
    int k = 0;
    while (k < m && *its < maxit) {
      double *h = g->H + (size_t)k * (m + 1); /* column k */
      double *vk = g->V + (size_t)k * n, *vn = g->V + (size_t)(k + 1) * n;
      SA_CHECK(pc(ctx, vk, g->z));
      matvec(n, cp, ri, K, g->z, vn);
      for (int j = 0; j <= k; j++) { /* modified Gram-Schmidt */
        const double *vj = g->V + (size_t)j * n;
        h[j] = dot(vn, vj, n);
        for (int i = 0; i < n; i++) vn[i] -= h[j] * vj[i];
      }
      h[k + 1] = sqrt(dot(vn, vn, n));
      if (h[k + 1] > 0.0)
        for (int i = 0; i < n; i++) vn[i] /= h[k + 1];
      for (int j = 0; j < k; j++) { /* earlier rotations */
        double t = g->cs[j] * h[j] + g->sn[j] * h[j + 1];
        h[j + 1] = -g->sn[j] * h[j] + g->cs[j] * h[j + 1];
        h[j] = t;
      }
      double d = hypot(h[k], h[k + 1]);
      if (!(d > 0.0) || !isfinite(d)) return 1; /* breakdown with a singular K M^-1 */
      g->cs[k] = h[k] / d;
      g->sn[k] = h[k + 1] / d;
      h[k] = d;
      h[k + 1] = 0.0;
      g->gv[k + 1] = -g->sn[k] * g->gv[k];
      g->gv[k] = g->cs[k] * g->gv[k];
      k++;
      (*its)++;
      rel = fabs(g->gv[k]) / bn;
      if (rel <= rtol) break;
      /* abandon when the mean reduction per iteration so far, continued to maxit, would miss
       * rtol by 10x (the same test as PCG's in fem_newton.c: a failed attempt costs maxit
       * products and factor solves) */
      if (g->abandon && *its >= 3 && *its < maxit && rel * pow(rel, (double)(maxit - *its) / *its) > 10.0 * rtol) {
        SA_CHECK(update(g, k, x, pc, ctx));
        return 1;
      }
    }
    SA_CHECK(update(g, k, x, pc, ctx));
    if (rel <= rtol) return 0;
  }
  return 1;
}
