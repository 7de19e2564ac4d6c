/* fem_gmres.h - restarted, right-preconditioned GMRES on a compressed-column matrix (private to
 * fem/): Newton directions of an unsymmetric tangent from the factors of an earlier one. */
#ifndef FEM_GMRES_H
#define FEM_GMRES_H

/* z = M^-1 r (the preconditioner: a solve with held factors). Returns 0 or < 0 on error. */
typedef int (*FemPrecond)(void *ctx, const double *r, double *z);

typedef struct {
  int n, m;        /* order; Krylov vectors per cycle (restart length) */
  int abandon;     /* 1 (set by fem_gmres_alloc): give up early when the mean reduction per
                    * iteration so far, continued to maxit, would miss rtol by 10x */
  double *V;       /* (m + 1) x n Arnoldi basis */
  double *H;       /* (m + 1) x m Hessenberg, column-major */
  double *cs, *sn; /* m Givens rotations */
  double *gv, *y;  /* m + 1 rotated right-hand side, m coefficients */
  double *w, *z;   /* n work */
} FemGmres;

/* Workspace for order n and restart length m; no allocation in fem_gmres_solve after it. */
int fem_gmres_alloc(FemGmres *g, int n, int m);
void fem_gmres_free(FemGmres *g);
/* Solve K x = b (K: values over the full pattern cp/ri of order g->n) from x = 0 to
 * |b - K x| <= rtol |b| within maxit iterations (restarted every g->m). Returns 0 converged,
 * 1 not (limit, abandoned as too slow, or breakdown; x then holds the last iterate), < 0 when
 * the preconditioner failed. its [out]: iterations (products with K). */
int fem_gmres_solve(FemGmres *g, const int *cp, const int *ri, const double *K, const double *b,
                    double *x, int maxit, double rtol, FemPrecond pc, void *ctx, int *its);

#endif
