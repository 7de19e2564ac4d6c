/* fem_kernel_tensor.h - private: small 3x3 tensor helpers (row-major) for the element kernels. */
#ifndef FEM_KERNEL_TENSOR_H
#define FEM_KERNEL_TENSOR_H

#include <math.h>

static inline double fem_kt_det(const double A[9])
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* Cofactor matrix cof(A) = det(A) A^-T; returns det A. */
static inline double fem_kt_cof(const double A[9], double C[9])
{
  C[0] = A[4] * A[8] - A[5] * A[7];
  C[1] = A[5] * A[6] - A[3] * A[8];
  C[2] = A[3] * A[7] - A[4] * A[6];
  C[3] = A[2] * A[7] - A[1] * A[8];
  C[4] = A[0] * A[8] - A[2] * A[6];
  C[5] = A[1] * A[6] - A[0] * A[7];
  C[6] = A[1] * A[5] - A[2] * A[4];
  C[7] = A[2] * A[3] - A[0] * A[5];
  C[8] = A[0] * A[4] - A[1] * A[3];
  return A[0] * C[0] + A[1] * C[1] + A[2] * C[2];
}

/* Inverse Ainv [out]; returns det A (Ainv untouched when det == 0). */
static inline double fem_kt_inv(const double A[9], double Ainv[9])
{
  double C[9];
  double d = fem_kt_cof(A, C);
  if (d == 0) return 0;
  double s = 1 / d;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) Ainv[3 * i + j] = s * C[3 * j + i];
  return d;
}

/* Eigenvalues [out] (descending) of a symmetric 3x3 S by cyclic Jacobi rotations. */
static inline void fem_kt_sym_eig(const double S[9], double ev[3])
{
  double a[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) a[i][j] = 0.5 * (S[3 * i + j] + S[3 * j + i]);
  for (int sweep = 0; sweep < 50; sweep++) {
    double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-30 * diag || off == 0) break;
    for (int p = 0; p < 2; p++)
      for (int q = p + 1; q < 3; q++) {
        if (a[p][q] == 0) continue;
        double th = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        double t = (th >= 0 ? 1 : -1) / (fabs(th) + sqrt(th * th + 1));
        double c = 1 / sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; k++) { /* A <- A R */
          double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; k++) { /* A <- R^T A */
          double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
      }
  }
  ev[0] = a[0][0], ev[1] = a[1][1], ev[2] = a[2][2];
  for (int i = 0; i < 2; i++)
    for (int j = i + 1; j < 3; j++)
      if (ev[j] > ev[i]) {
        double t = ev[i];
        ev[i] = ev[j], ev[j] = t;
      }
}

#endif
