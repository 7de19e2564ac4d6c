/* grid_matrix.h - the test matrix of test_linsolve and test_gmres: the five-point operator on an
 * m x m grid in full compressed-column form (rows sorted), diagonal diag, off-diagonals -1 plus a
 * centred first-order convection term conv on the x neighbours (unsymmetric when conv != 0). */
#ifndef GRID_MATRIX_H
#define GRID_MATRIX_H

/* colptr [out] m^2 + 1, rowind and val [out] 5 m^2 */
static inline void grid_matrix(int m, double diag, double conv, int *colptr, int *rowind,
                               double *val) {
  int k = 0, n = m * m;
  for (int j = 0; j < n; j++) { /* column j */
    int jx = j % m, jy = j / m;
    colptr[j] = k;
    /* rows in increasing order: j-m, j-1, j, j+1, j+m */
    int rows[5], nr = 0;
    if (jy > 0) rows[nr++] = j - m;
    if (jx > 0) rows[nr++] = j - 1;
    rows[nr++] = j;
    if (jx < m - 1) rows[nr++] = j + 1;
    if (jy < m - 1) rows[nr++] = j + m;
    for (int r = 0; r < nr; r++) {
      int i = rows[r];
      rowind[k] = i;
      val[k] = i == j ? diag : -1.0 + (i == j - 1 ? conv : (i == j + 1 ? -conv : 0.0));
      k++;
    }
  }
  colptr[n] = k;
}

#endif
