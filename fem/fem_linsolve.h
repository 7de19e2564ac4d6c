/* fem_linsolve.h - sparse direct solvers behind one handle (private to fem/).
 *
 * The matrix is handed over as a FULL compressed-column pattern (both triangles, structurally
 * symmetric, row indices sorted within each column), fixed for the life of the handle. The
 * values array is supplied at every factorisation and may change freely.
 *
 *  - Symmetric values: CHOLMOD supernodal LL' with a METIS nested-dissection ordering. The
 *    symbolic analysis (ordering, elimination tree, supernodes) is done ONCE, in
 *    fem_linsolve_create; every factorisation reuses it. CHOLMOD reads the lower triangle only.
 *  - Fallback (stated in the log by the caller via FemLinInfo): when CHOLMOD reports the matrix
 *    is not positive definite, or the caller says it is unsymmetric, UMFPACK LU on the full
 *    matrix (64-bit interface umfpack_dl_*: the int one runs out of its addressable work memory
 *    above ~2 GB). Its symbolic analysis is done on first use and then reused as well. Every
 *    factorise call with symmetric = 1 tries CHOLMOD first, whatever the previous call used.
 *
 * No allocation happens in fem_linsolve_solve after the first call (CHOLMOD solve2 workspaces
 * and UMFPACK wsolve workspaces are kept). UMFPACK's numeric factorisation does allocate (the
 * LU factors); that path is the fallback, not the coupling loop. */
#ifndef FEM_LINSOLVE_H
#define FEM_LINSOLVE_H

typedef struct FemLinSolver FemLinSolver;

typedef enum { FEM_LIN_CHOLMOD = 0, FEM_LIN_UMFPACK = 1 } FemLinKind;

typedef struct {
  FemLinKind kind;      /* solver of the last successful factorisation */
  int not_pd;           /* last CHOLMOD attempt found the matrix not positive definite */
  int unsym;            /* last factorisation was asked for as unsymmetric */
  long n, nnz_a;        /* order and entries of the full matrix */
  double nnz_l;         /* entries in the Cholesky factor L (after analysis) */
  double flops_chol;    /* flop count of one Cholesky factorisation */
  double nnz_lu;        /* entries in L + U of the last UMFPACK factorisation (0 if none) */
  double t_analyze;     /* seconds spent in CHOLMOD symbolic analysis */
  int n_chol, n_umf;    /* factorisations done by each solver */
} FemLinInfo;

/* n [in] order; colptr [in] n+1, rowind [in] colptr[n]: full structurally symmetric pattern
 * with sorted rows [borrowed: must outlive the handle]. nthreads: BLAS threads (>= 1).
 * Performs the CHOLMOD symbolic analysis. */
int fem_linsolve_create(int n, const int *colptr, const int *rowind, int nthreads,
                        FemLinSolver **out);
/* Factorise the matrix with values [borrowed until the next factorise; must stay unchanged
 * while solving]. symmetric = 1: try CHOLMOD first, fall back to UMFPACK when not positive
 * definite; symmetric = 2: CHOLMOD only, SA_ERR_NOT_SPD (> 0, no error pushed, info.not_pd
 * set) when not positive definite; symmetric = 0: UMFPACK directly. Returns SA_ERR_NOT_SPD (> 0) when even UMFPACK
 * finds the matrix singular. */
int fem_linsolve_factorize(FemLinSolver *s, const double *values, int symmetric);
/* Solve A x = b with the last factor. b [in] n, x [out] n (may not alias b). After an LU,
 * UMFPACK refines the solution against the values given to factorise (up to 2 steps). */
int fem_linsolve_solve(FemLinSolver *s, const double *b, double *x);
/* The same with the factors alone, no refinement: a fixed linear operator whatever the values
 * array now holds, as a Krylov preconditioner needs (and 1/3 of the refined solve's cost). */
int fem_linsolve_solve_factors(FemLinSolver *s, const double *b, double *x);
/* max |a_ij - a_ji| / max |a_ij| over the pattern (0 for a symmetric matrix). */
double fem_linsolve_asymmetry(const FemLinSolver *s, const double *values);
/* The slot of the transposed entry of each slot [borrowed], colptr[n] entries. */
const int *fem_linsolve_transpose_map(const FemLinSolver *s);
void fem_linsolve_info(const FemLinSolver *s, FemLinInfo *info);
void fem_linsolve_destroy(FemLinSolver **s);

#endif
