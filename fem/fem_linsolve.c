/* fem_linsolve.c - CHOLMOD supernodal Cholesky (METIS ordering, analysed once) with an UMFPACK
 * LU fallback for indefinite or unsymmetric tangents. See fem_linsolve.h.
 * UMFPACK is called through its 64-bit-integer interface (umfpack_dl_*): the 32-bit one
 * (umfpack_di_*) addresses its work memory with int and is guaranteed to fail with status -1
 * (out of memory) once a factorisation needs more than ~2 GB, whatever the RAM (UMFPACK user
 * guide). Measured on the actuator: 106k dofs need 0.94 GB (nnz(L+U) 1.03e8), so the int
 * interface would hit its ceiling at roughly twice that size. The pattern is copied to
 * SuiteSparse_long arrays on first use (8 bytes per entry, 65 MB at 106k dofs). */
#include "fem_linsolve.h"

#include <cholmod.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <umfpack.h>

#include "sa_error.h"
#include "sa_output.h"
#include "sa_log.h"

void openblas_set_num_threads(int num_threads);

struct FemLinSolver {
  int n;
  const int *colptr, *rowind; /* borrowed full pattern */
  int *tmap;                  /* transpose slot of each slot */
  cholmod_common cc;
  cholmod_factor *L;
  cholmod_sparse A;           /* header over the caller's arrays (never freed by CHOLMOD) */
  cholmod_dense B;            /* header over the right-hand side */
  cholmod_dense *X, *Y, *E;   /* solve2 workspaces, allocated on first solve, then reused */
  void *usym, *unum;          /* UMFPACK symbolic (once) and numeric objects */
  double uctrl[UMFPACK_CONTROL], uinfo[UMFPACK_INFO];
  SuiteSparse_long *lp, *li;  /* 64-bit copy of the pattern (first LU) */
  SuiteSparse_long *uwi;
  double *uw;
  const double *values;       /* values of the current factor */
  FemLinInfo info;
};

static void setup_headers(FemLinSolver *s) {
  cholmod_sparse *A = &s->A;
  memset(A, 0, sizeof *A);
  A->nrow = A->ncol = (size_t)s->n;
  A->nzmax = (size_t)s->colptr[s->n];
  A->p = (void *)s->colptr;
  A->i = (void *)s->rowind;
  A->stype = -1; /* symmetric, lower triangle used; upper entries are ignored */
  A->itype = CHOLMOD_INT;
  A->xtype = CHOLMOD_REAL;
  A->dtype = CHOLMOD_DOUBLE;
  A->sorted = 1;
  A->packed = 1;
  cholmod_dense *B = &s->B;
  memset(B, 0, sizeof *B);
  B->nrow = (size_t)s->n;
  B->ncol = 1;
  B->nzmax = (size_t)s->n;
  B->d = (size_t)s->n;
  B->xtype = CHOLMOD_REAL;
  B->dtype = CHOLMOD_DOUBLE;
}

int fem_linsolve_create(int n, const int *colptr, const int *rowind, int nthreads,
                        FemLinSolver **out) {
  *out = NULL;
  SA_REQUIRE(n > 0 && colptr && rowind, SA_ERR_INPUT, "empty linear system (n = %d)", n);
  FemLinSolver *s;
  SA_CALLOC(s, 1);
  s->n = n;
  s->colptr = colptr;
  s->rowind = rowind;
  int nnz = colptr[n];
  s->tmap = malloc((size_t)nnz * sizeof *s->tmap);
  if (!s->tmap) {
    free(s);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate transpose map (%d entries)", nnz);
  }
  /* Transpose map: for slot k = (i, j) find slot of (j, i) by binary search in column i. */
  for (int j = 0; j < n; j++) {
    for (int k = colptr[j]; k < colptr[j + 1]; k++) {
      int i = rowind[k], lo = colptr[i], hi = colptr[i + 1] - 1, t = -1;
      while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (rowind[mid] < j) lo = mid + 1;
        else if (rowind[mid] > j) hi = mid - 1;
        else { t = mid; break; }
      }
      if (t < 0) {
        free(s->tmap);
        free(s);
        return SA_ERROR(SA_ERR_INTERNAL, "pattern not structurally symmetric at (%d, %d)", i, j);
      }
      s->tmap[k] = t;
    }
  }
  if (nthreads < 1) nthreads = 1;
  openblas_set_num_threads(nthreads);

  cholmod_start(&s->cc);
  s->cc.nmethods = 1;
  s->cc.method[0].ordering = CHOLMOD_METIS;
  s->cc.postorder = 1;
  s->cc.supernodal = CHOLMOD_SUPERNODAL;
  s->cc.quick_return_if_not_posdef = 1;
  s->cc.final_ll = 1;
  s->cc.print = 0;
  setup_headers(s);
  double t0 = sa_time_now();
  s->A.xtype = CHOLMOD_PATTERN; /* no values yet: analyse the pattern */
  s->L = cholmod_analyze(&s->A, &s->cc);
  s->A.xtype = CHOLMOD_REAL;
  s->info.t_analyze = sa_time_now() - t0;
  if (!s->L || s->cc.status < CHOLMOD_OK) {
    int st = s->cc.status;
    fem_linsolve_destroy(&s);
    return SA_ERROR(SA_ERR_LIBRARY, "cholmod_analyze failed (status %d)", st);
  }
  sa_timing_add("fem symbolic", s->info.t_analyze);
  s->info.n = n;
  s->info.nnz_a = nnz;
  s->info.nnz_l = s->cc.lnz;
  s->info.flops_chol = s->cc.fl;

  umfpack_dl_defaults(s->uctrl);
  s->uwi = malloc((size_t)n * sizeof *s->uwi);
  s->uw = malloc((size_t)5 * n * sizeof *s->uw);
  if (!s->uwi || !s->uw) {
    fem_linsolve_destroy(&s);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate UMFPACK workspace (n = %d)", n);
  }
  *out = s;
  return 0;
}

static int umf_factorize(FemLinSolver *s, const double *values) {
  SuiteSparse_long st;
  if (!s->lp) {
    int nnz = s->colptr[s->n];
    s->lp = malloc((size_t)(s->n + 1) * sizeof *s->lp);
    s->li = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *s->li);
    if (!s->lp || !s->li) {
      free(s->lp);
      free(s->li);
      s->lp = s->li = NULL;
      return SA_ERROR(SA_ERR_MEMORY, "cannot allocate the 64-bit pattern (%d entries)", nnz);
    }
    for (int j = 0; j <= s->n; j++) s->lp[j] = s->colptr[j];
    for (int k = 0; k < nnz; k++) s->li[k] = s->rowind[k];
  }
  if (!s->usym) {
    double t0 = sa_time_now();
    /* The tangent is structurally symmetric: UMFPACK's symmetric strategy with CHOLMOD's METIS
     * permutation as the column pre-ordering gives the Cholesky fill pattern (diagonal pivots
     * preferred). Against UMFPACK's default (AMD): nnz(L+U) 6.0e7 vs 7.3e7 and 4.4e10 vs 6.7e10
     * flops on the 73k-dof actuator, ~20 % less factorisation time (docs/fem.md). */
    s->uctrl[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_SYMMETRIC;
    SuiteSparse_long *q = malloc((size_t)s->n * sizeof *q);
    SA_REQUIRE(q, SA_ERR_MEMORY, "cannot allocate the UMFPACK column ordering (n = %d)", s->n);
    const int *perm = s->L->Perm;
    for (int k = 0; k < s->n; k++) q[k] = perm[k];
    st = umfpack_dl_qsymbolic(s->n, s->n, s->lp, s->li, values, q, &s->usym, s->uctrl, s->uinfo);
    free(q);
    sa_timing_add("fem symbolic", sa_time_now() - t0);
    SA_REQUIRE(st == UMFPACK_OK, SA_ERR_LIBRARY, "umfpack_dl_symbolic failed (status %ld)",
               (long)st);
  }
  if (s->unum) umfpack_dl_free_numeric(&s->unum);
  st = umfpack_dl_numeric(s->lp, s->li, values, s->usym, &s->unum, s->uctrl, s->uinfo);
  if (st == UMFPACK_WARNING_singular_matrix) {
    umfpack_dl_free_numeric(&s->unum);
    return SA_ERROR(SA_ERR_NOT_SPD, "UMFPACK: the tangent is singular (n = %d)", s->n);
  }
  SA_REQUIRE(st == UMFPACK_OK, SA_ERR_LIBRARY,
             "umfpack_dl_numeric failed (status %ld%s, n = %d)", (long)st,
             st == UMFPACK_ERROR_out_of_memory ? ": out of memory" : "", s->n);
  s->info.nnz_lu = s->uinfo[UMFPACK_LNZ] + s->uinfo[UMFPACK_UNZ];
  sa_log(SA_LOG_DEBUG, "fem", "UMFPACK LU (n = %d): nnz(L+U) %.4g, %.3g flops, peak memory %.0f MB",
         s->n, s->info.nnz_lu, s->uinfo[UMFPACK_FLOPS], s->uinfo[UMFPACK_PEAK_MEMORY] * s->uinfo[UMFPACK_SIZE_OF_UNIT] / 1e6);
  s->info.kind = FEM_LIN_UMFPACK;
  s->info.n_umf++;
  return 0;
}

int fem_linsolve_factorize(FemLinSolver *s, const double *values, int symmetric) {
  s->values = values;
  s->info.unsym = !symmetric;
  s->info.not_pd = 0;
  double t0 = sa_time_now();
  if (symmetric) {
    s->A.x = (void *)values;
    int ok = cholmod_factorize(&s->A, s->L, &s->cc);
    if (ok && s->cc.status == CHOLMOD_OK && s->L->minor == s->L->n) {
      s->info.kind = FEM_LIN_CHOLMOD;
      s->info.n_chol++;
      sa_timing_add("fem factorise", sa_time_now() - t0);
      return 0;
    }
    if (s->cc.status != CHOLMOD_NOT_POSDEF && s->cc.status < CHOLMOD_OK)
      return SA_ERROR(SA_ERR_LIBRARY, "cholmod_factorize failed (status %d)", s->cc.status);
    s->info.not_pd = 1;
    if (symmetric == 2) {
      sa_timing_add("fem factorise", sa_time_now() - t0);
      return SA_ERR_NOT_SPD;
    }
  }
  /* the LU after a failed Cholesky costs ~6 of them: not started once a signal came */
  if (symmetric && sa_interrupted()) {
    sa_timing_add("fem factorise", sa_time_now() - t0);
    return SA_ERROR(SA_ERR_INTERRUPTED, "interrupted before the LU factorisation");
  }
  int rc = umf_factorize(s, values);
  sa_timing_add("fem factorise", sa_time_now() - t0);
  return rc ? sa_error_push(rc, __func__, __FILE__, __LINE__) : 0;
}

static int solve(FemLinSolver *s, const double *b, double *x, int refine);

int fem_linsolve_solve(FemLinSolver *s, const double *b, double *x) {
  return solve(s, b, x, 1);
}

int fem_linsolve_solve_factors(FemLinSolver *s, const double *b, double *x) {
  return solve(s, b, x, 0);
}

/* refine: UMFPACK's iterative refinement against s->values (its default, up to 2 steps). */
static int solve(FemLinSolver *s, const double *b, double *x, int refine) {
  double t0 = sa_time_now();
  if (s->info.kind == FEM_LIN_CHOLMOD) {
    s->B.x = (void *)b;
    int ok = cholmod_solve2(CHOLMOD_A, s->L, &s->B, NULL, &s->X, NULL, &s->Y, &s->E, &s->cc);
    SA_REQUIRE(ok && s->X, SA_ERR_LIBRARY, "cholmod_solve2 failed (status %d)", s->cc.status);
    memcpy(x, s->X->x, (size_t)s->n * sizeof *x);
  } else {
    SA_REQUIRE(s->unum, SA_ERR_INTERNAL, "solve without a factorisation");
    double irstep = s->uctrl[UMFPACK_IRSTEP];
    if (!refine) s->uctrl[UMFPACK_IRSTEP] = 0;
    SuiteSparse_long st = umfpack_dl_wsolve(UMFPACK_A, s->lp, s->li, s->values, x, b, s->unum,
                                            s->uctrl, s->uinfo, s->uwi, s->uw);
    s->uctrl[UMFPACK_IRSTEP] = irstep;
    SA_REQUIRE(st == UMFPACK_OK || st == UMFPACK_WARNING_singular_matrix, SA_ERR_LIBRARY,
               "umfpack_dl_wsolve failed (status %ld)", (long)st);
  }
  sa_timing_add("fem solve", sa_time_now() - t0);
  return 0;
}

double fem_linsolve_asymmetry(const FemLinSolver *s, const double *values) {
  int nnz = s->colptr[s->n];
  double amax = 0.0, dmax = 0.0;
  for (int k = 0; k < nnz; k++) {
    double a = fabs(values[k]), d = fabs(values[k] - values[s->tmap[k]]);
    if (a > amax) amax = a;
    if (d > dmax) dmax = d;
  }
  return amax > 0.0 ? dmax / amax : 0.0;
}

const int *fem_linsolve_transpose_map(const FemLinSolver *s) { return s->tmap; }

void fem_linsolve_info(const FemLinSolver *s, FemLinInfo *info) { *info = s->info; }

void fem_linsolve_destroy(FemLinSolver **ps) {
  if (!ps || !*ps) return;
  FemLinSolver *s = *ps;
  if (s->L) cholmod_free_factor(&s->L, &s->cc);
  if (s->X) cholmod_free_dense(&s->X, &s->cc);
  if (s->Y) cholmod_free_dense(&s->Y, &s->cc);
  if (s->E) cholmod_free_dense(&s->E, &s->cc);
  cholmod_finish(&s->cc);
  if (s->unum) umfpack_dl_free_numeric(&s->unum);
  if (s->usym) umfpack_dl_free_symbolic(&s->usym);
  free(s->lp);
  free(s->li);
  free(s->uwi);
  free(s->uw);
  free(s->tmap);
  free(s);
  *ps = NULL;
}
