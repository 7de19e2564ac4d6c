/* test_linsolve - the CHOLMOD / UMFPACK wrapper on small matrices with known answers.
 *
 * Matrix: 2-D five-point Laplacian on an m x m grid (SPD), optionally shifted by -s I
 * (indefinite for s above the smallest eigenvalue 4 - 4 cos(pi/(m+1)) ... = 2(2 - 2cos(h)))
 * and with a first-order convection term c (unsymmetric). The exact solution x* is chosen and
 * b = A x* built by a matrix-vector product, so the reference is independent of the solvers.
 * Checks: CHOLMOD used for the SPD case; fallback to UMFPACK flagged for the indefinite case;
 * UMFPACK for the unsymmetric case; CHOLMOD again for an SPD matrix after an indefinite one on
 * the same handle (the per-iteration policy of fem_solver); |x - x*|_inf <= 1e-10 (condition number of these matrices
 * is < 1e4, so double precision direct solvers give ~1e-12); asymmetry measure 0 / c-scaled. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem_linsolve.h"
#include "grid_matrix.h"
#include "sa_error.h"

#define M 12
#define N (M * M)

static int colptr[N + 1], rowind[5 * N];
static double val[5 * N];

static void build(double shift, double conv) {
  grid_matrix(M, 4.0 - shift, conv, colptr, rowind, val);
}

static void matvec(const double *x, double *y) {
  for (int i = 0; i < N; i++) y[i] = 0;
  for (int j = 0; j < N; j++)
    for (int k = colptr[j]; k < colptr[j + 1]; k++) y[rowind[k]] += val[k] * x[j];
}

static int run(const char *name, double shift, double conv, int sym, FemLinKind want_kind,
               int want_not_pd) {
  build(shift, conv);
  FemLinSolver *s;
  if (fem_linsolve_create(N, colptr, rowind, 1, &s)) {
    sa_error_print();
    return 1;
  }
  double xs[N], b[N], x[N];
  for (int i = 0; i < N; i++) xs[i] = sin(0.3 * i) + 0.1 * i;
  matvec(xs, b);
  int fails = 0;
  for (int rep = 0; rep < 3; rep++) { /* repeated factorisations reuse the analysis */
    if (fem_linsolve_factorize(s, val, sym) || fem_linsolve_solve(s, b, x)) {
      sa_error_print();
      fem_linsolve_destroy(&s);
      return 1;
    }
  }
  double err = 0;
  for (int i = 0; i < N; i++) err = fmax(err, fabs(x[i] - xs[i]));
  FemLinInfo info;
  fem_linsolve_info(s, &info);
  if (err > 1e-10) {
    fprintf(stderr, "%s: |x - x*| = %g > 1e-10\n", name, err);
    fails++;
  }
  if (info.kind != want_kind || info.not_pd != want_not_pd) {
    fprintf(stderr, "%s: solver kind %d not_pd %d, expected %d %d\n", name, info.kind,
            info.not_pd, want_kind, want_not_pd);
    fails++;
  }
  double asym = fem_linsolve_asymmetry(s, val);
  /* exact: symmetric -> 0; convection -> max |2 conv| / max |a_ij| = 2 conv / (4 - shift) */
  double want_asym = conv == 0.0 ? 0.0 : 2 * conv / fmax(fabs(4.0 - shift), 1.0 + conv);
  if (fabs(asym - want_asym) > 1e-14) {
    fprintf(stderr, "%s: asymmetry %g, expected %g\n", name, asym, want_asym);
    fails++;
  }
  if (info.nnz_l < N) {
    fprintf(stderr, "%s: nnz(L) = %g < n\n", name, info.nnz_l);
    fails++;
  }
  fem_linsolve_destroy(&s);
  return fails;
}

/* Policy: CHOLMOD is tried at every symmetric factorisation, so after an indefinite matrix
 * (UMFPACK fallback) an SPD one on the same handle is factorised by CHOLMOD again (its symbolic
 * factor must have survived the failed attempt), and back to UMFPACK again; every solve exact. */
static int alternate(void) {
  static double v_spd[5 * N], v_ind[5 * N];
  build(0.5, 0.0);
  for (int k = 0; k < colptr[N]; k++) v_ind[k] = val[k];
  build(0.0, 0.0);
  for (int k = 0; k < colptr[N]; k++) v_spd[k] = val[k];
  FemLinSolver *s;
  if (fem_linsolve_create(N, colptr, rowind, 1, &s)) {
    sa_error_print();
    return 1;
  }
  int fails = 0;
  const double *seq[4] = {v_ind, v_spd, v_ind, v_spd};
  FemLinKind want[4] = {FEM_LIN_UMFPACK, FEM_LIN_CHOLMOD, FEM_LIN_UMFPACK, FEM_LIN_CHOLMOD};
  for (int r = 0; r < 4; r++) {
    double xs[N], b[N], x[N], err = 0;
    for (int k = 0; k < colptr[N]; k++) val[k] = seq[r][k];
    for (int i = 0; i < N; i++) xs[i] = cos(0.2 * i + r);
    matvec(xs, b);
    if (fem_linsolve_factorize(s, seq[r], 1) || fem_linsolve_solve(s, b, x)) {
      sa_error_print();
      fem_linsolve_destroy(&s);
      return 1;
    }
    for (int i = 0; i < N; i++) err = fmax(err, fabs(x[i] - xs[i]));
    FemLinInfo info;
    fem_linsolve_info(s, &info);
    if (info.kind != want[r] || err > 1e-10) {
      fprintf(stderr, "alternate %d: kind %d (expected %d), |x - x*| = %g\n", r, info.kind,
              want[r], err);
      fails++;
    }
    if (r == 3 && (info.n_chol != 2 || info.n_umf != 2)) {
      fprintf(stderr, "alternate: %d Cholesky, %d LU (expected 2, 2)\n", info.n_chol,
              info.n_umf);
      fails++;
    }
  }
  fem_linsolve_destroy(&s);
  return fails;
}

int main(void) {
  int fails = 0;
  fails += run("spd", 0.0, 0.0, 1, FEM_LIN_CHOLMOD, 0);
  /* smallest eigenvalue of the Laplacian: 4 - 4 cos(pi/(M+1)) ~ 0.116; shift 0.5 makes
   * several eigenvalues negative; 0.5 is not an eigenvalue (nonsingular) */
  fails += run("indefinite", 0.5, 0.0, 1, FEM_LIN_UMFPACK, 1);
  fails += run("unsymmetric", 0.0, 0.3, 0, FEM_LIN_UMFPACK, 0);
  fails += alternate();
  return fails ? 1 : 0;
}
