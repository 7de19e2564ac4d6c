/* kt_util.h - helpers shared by the kernel tests: a deterministic random generator, tolerance
 * comparison and small geometry builders. Header-only (static) to keep each test one program. */
#ifndef KT_UTIL_H
#define KT_UTIL_H

#include <math.h>
#include <stdio.h>

static unsigned long long kt_rng_state = 88172645463325252ULL;
/* Uniform in [lo, hi) (xorshift64). */
static inline double kt_rand(double lo, double hi)
{
  kt_rng_state ^= kt_rng_state << 13;
  kt_rng_state ^= kt_rng_state >> 7;
  kt_rng_state ^= kt_rng_state << 17;
  return lo + (hi - lo) * (double)(kt_rng_state >> 11) / 9007199254740992.0;
}

static int kt_fail = 0;
/* |a - b| <= atol + rtol |b|, else print and count a failure. */
static inline int kt_close(const char *what, double a, double b, double atol, double rtol)
{
  if (fabs(a - b) <= atol + rtol * fabs(b)) return 1;
  if (kt_fail < 40) fprintf(stderr, "%s: got %.12g, expected %.12g (diff %.3g)\n", what, a, b, a - b);
  kt_fail++;
  return 0;
}

static inline double kt_maxabs(const double *a, int n)
{
  double m = 0;
  for (int i = 0; i < n; i++)
    if (fabs(a[i]) > m) m = fabs(a[i]);
  return m;
}

static inline double kt_det3(const double A[9])
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* Random F with det F = target: I + amp * random, rescaled. */
static inline void kt_random_F(double amp, double detF, double F[9])
{
  double d;
  do {
    for (int i = 0; i < 9; i++) F[i] = (i % 4 == 0 ? 1 : 0) + kt_rand(-amp, amp);
    d = kt_det3(F);
  } while (d < 0.3);
  double s = cbrt(detF / d);
  for (int i = 0; i < 9; i++) F[i] *= s;
}

/* Rotation matrix from an axis-angle vector. */
static inline void kt_rotation(const double w[3], double R[9])
{
  double th = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  double k[3] = {w[0] / th, w[1] / th, w[2] / th}, c = cos(th), s = sin(th);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[3 * i + j] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];
  R[1] -= s * k[2], R[2] += s * k[1];
  R[3] += s * k[2], R[5] -= s * k[0];
  R[6] -= s * k[1], R[7] += s * k[0];
}

/* VTK tet10 edges. */
static const int kt_tet_edge[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};

/* Distorted tet: corners of the unit right tet perturbed by +-dist, mid-nodes at the edge
 * midpoints plus +-curve (curve = 0: straight-sided). nen = 4 or 10. */
static inline void kt_random_tet(int nen, double dist, double curve, double *X)
{
  static const double c0[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 4; a++)
    for (int k = 0; k < 3; k++) X[3 * a + k] = c0[a][k] + kt_rand(-dist, dist);
  if (nen == 4) return;
  for (int e = 0; e < 6; e++)
    for (int k = 0; k < 3; k++)
      X[3 * (4 + e) + k] = 0.5 * (X[3 * kt_tet_edge[e][0] + k] + X[3 * kt_tet_edge[e][1] + k]) +
                           kt_rand(-curve, curve);
}

#endif
