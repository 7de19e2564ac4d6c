/* test_fem_locking.c - neither volumetric locking nor the softness of a pure mean-dilatation
 * element: small-deflection tip-loaded cantilever, length L = 10, square section 1 x 1 (ONE
 * element through the thickness, the hardest case), clamped at x = 0, shear force P = 1e-6 mu in
 * -z spread over the tip face, 10 x 1 x 1 cubes split into 6 tet10 each; the linear problem
 * K u = f with K = fem_element_tl's tangent at the reference (dense Cholesky).
 * Reference: Timoshenko beam, delta = P L^3 / (3 E I) + P L / (k G A), E = 2 mu (1 + nu),
 * I = 1/12, A = 1, k = 10 (1 + nu) / (12 + 11 nu). The beam theory ignores the clamp's restraint
 * of the cross-section, which makes the 3D solution stiffer by about 1 % (nu = 0.3) and 2.3 %
 * (nu = 0.4995) at L/h = 10 (refined meshes, 4 elements through the thickness, agree with each
 * other to 0.1 %), so each deflection must be within 4 % of Timoshenko, and the ratio of the
 * near-incompressible (nu = 0.4995 and 0.49995, K/mu = 1000 and 1e4) to the compressible
 * (nu = 0.3) deflection, in which these effects largely cancel, within 1 %.
 * To show the test discriminates: on the same mesh the pure mean-dilatation element
 * (mix_alpha < 0, P2-P0) must come out > 20 % too soft (its element-level zero-energy "special
 * conformal" modes are only weakly restrained by one layer of elements), the plain displacement
 * tet10 at K/mu = 1000 (mix_alpha huge) > 8 % too stiff (locking) and tet4 > 3x too stiff. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_element.h"
#include "sa_error.h"
#include "kt_util.h"

#define NX 10
#define NY 1
#define NZ 1
#define GX (2 * NX + 1)
#define GY (2 * NY + 1)
#define GZ (2 * NZ + 1)
#define NNODE (GX * GY * GZ)

static int gid(int i, int j, int k) { return i + GX * (j + GY * k); }

/* Tip deflection (mean w over the tip face nodes) for element type t and Poisson ratio nu. */
static double cantilever(FemElemType t, double nu, double P, double mix_alpha)
{
  const double mu = 1;
  FemMaterial m = {.kind = FEM_MAT_NEOHOOKE, .c10 = mu / 2,
                   .kappa = 2 * mu * (1 + nu) / (3 * (1 - 2 * nu)), .mix_alpha = mix_alpha};
  const int nd = 3 * NNODE, nen = (int)t;
  double *K = calloc((size_t)nd * nd, sizeof *K), f[3 * NNODE] = {0}, X[3 * NNODE];
  int fixed[3 * NNODE] = {0}, used[NNODE] = {0};
  for (int k = 0; k < GZ; k++)
    for (int j = 0; j < GY; j++)
      for (int i = 0; i < GX; i++) {
        double *x = X + 3 * gid(i, j, k);
        x[0] = 0.5 * i, x[1] = 0.5 * j, x[2] = 0.5 * k;
      }
  /* Kuhn split of a cube into 6 tets along the diagonal 000-111: paths through the corners. */
  static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  static FemElemOut out;
  for (int ci = 0; ci < NX; ci++)
    for (int cj = 0; cj < NY; cj++)
      for (int ck = 0; ck < NZ; ck++)
        for (int p = 0; p < 6; p++) {
          int c[4][3], conn[10];
          c[0][0] = 2 * ci, c[0][1] = 2 * cj, c[0][2] = 2 * ck;
          for (int s = 1; s < 4; s++) {
            memcpy(c[s], c[s - 1], sizeof c[s]);
            c[s][perm[p][s - 1]] += 2;
          }
          double A[9];
          for (int r = 0; r < 3; r++)
            for (int d = 0; d < 3; d++) A[3 * r + d] = c[r + 1][d] - c[0][d];
          if (kt_det3(A) < 0) { /* keep positive volume */
            int tmp[3];
            memcpy(tmp, c[1], sizeof tmp), memcpy(c[1], c[2], sizeof tmp), memcpy(c[2], tmp, sizeof tmp);
          }
          for (int a = 0; a < 4; a++) conn[a] = gid(c[a][0], c[a][1], c[a][2]);
          for (int e = 0; e < 6; e++) {
            const int *u = c[kt_tet_edge[e][0]], *v = c[kt_tet_edge[e][1]];
            conn[4 + e] = gid((u[0] + v[0]) / 2, (u[1] + v[1]) / 2, (u[2] + v[2]) / 2);
          }
          double Xe[30];
          for (int a = 0; a < nen; a++) {
            memcpy(Xe + 3 * a, X + 3 * conn[a], 3 * sizeof(double));
            used[conn[a]] = 1;
          }
          if (fem_element_tl(t, Xe, Xe, &m, NULL, NULL, 1, &out)) {
            fprintf(stderr, "element failed: %s\n", sa_error_message());
            exit(1);
          }
          for (int r = 0; r < 3 * nen; r++)
            for (int s = 0; s < 3 * nen; s++)
              K[(size_t)(3 * conn[r / 3] + r % 3) * nd + 3 * conn[s / 3] + s % 3] += out.Ke[r * 3 * nen + s];
        }
  /* Clamp x = 0; tip traction -P/A in z: consistent loads of the two tri6 per tip square are
   * 0 at corners and 1/3 of each triangle's load at its mid-nodes; tet4 faces: 1/3 at corners. */
  for (int n = 0; n < NNODE; n++) {
    if (X[3 * n] == 0 || !used[n]) fixed[3 * n] = fixed[3 * n + 1] = fixed[3 * n + 2] = 1;
  }
  for (int cj = 0; cj < NY; cj++)
    for (int ck = 0; ck < NZ; ck++) {
      double q = P / (NY * NZ) / 2; /* load per triangle */
      int i = 2 * NX, j = 2 * cj, k = 2 * ck;
      if (t == FEM_TET10) {
        f[3 * gid(i, j + 1, k) + 2] -= q / 3, f[3 * gid(i, j + 1, k + 2) + 2] -= q / 3;
        f[3 * gid(i, j, k + 1) + 2] -= q / 3, f[3 * gid(i, j + 2, k + 1) + 2] -= q / 3;
        f[3 * gid(i, j + 1, k + 1) + 2] -= 2 * q / 3; /* on the diagonal: both triangles */
      } else {
        /* the Kuhn diagonal of the tip face joins (j, k) and (j+2, k+2) */
        f[3 * gid(i, j, k) + 2] -= 2 * q / 3, f[3 * gid(i, j + 2, k + 2) + 2] -= 2 * q / 3;
        f[3 * gid(i, j + 2, k) + 2] -= q / 3, f[3 * gid(i, j, k + 2) + 2] -= q / 3;
      }
    }
  /* Dense Cholesky of the free block (fixed dofs: identity rows). */
  for (int r = 0; r < nd; r++)
    if (fixed[r]) {
      for (int s = 0; s < nd; s++) K[(size_t)r * nd + s] = K[(size_t)s * nd + r] = 0;
      K[(size_t)r * nd + r] = 1, f[r] = 0;
    }
  for (int j = 0; j < nd; j++) {
    double d = K[(size_t)j * nd + j];
    for (int k = 0; k < j; k++) d -= K[(size_t)j * nd + k] * K[(size_t)j * nd + k];
    if (!(d > 0)) {
      fprintf(stderr, "stiffness not positive definite at dof %d\n", j);
      exit(1);
    }
    d = sqrt(d);
    K[(size_t)j * nd + j] = d;
    for (int i = j + 1; i < nd; i++) {
      double s = K[(size_t)i * nd + j];
      for (int k = 0; k < j; k++) s -= K[(size_t)i * nd + k] * K[(size_t)j * nd + k];
      K[(size_t)i * nd + j] = s / d;
    }
  }
  for (int i = 0; i < nd; i++) {
    for (int k = 0; k < i; k++) f[i] -= K[(size_t)i * nd + k] * f[k];
    f[i] /= K[(size_t)i * nd + i];
  }
  for (int i = nd - 1; i >= 0; i--) {
    for (int k = i + 1; k < nd; k++) f[i] -= K[(size_t)k * nd + i] * f[k];
    f[i] /= K[(size_t)i * nd + i];
  }
  double w = 0;
  int cnt = 0;
  for (int n = 0; n < NNODE; n++)
    if (used[n] && X[3 * n] == NX) w += f[3 * n + 2], cnt++;
  free(K);
  return -w / cnt;
}

static double timoshenko(double nu, double P)
{
  double mu = 1, E = 2 * mu * (1 + nu), L = NX, I = 1.0 / 12, k = 10 * (1 + nu) / (12 + 11 * nu);
  return P * L * L * L / (3 * E * I) + P * L / (k * mu);
}

int main(void)
{
  const double P = 1e-6;
  double d3 = cantilever(FEM_TET10, 0.3, P, 0), d5 = cantilever(FEM_TET10, 0.4995, P, 0);
  double r3 = timoshenko(0.3, P), r5 = timoshenko(0.4995, P);
  kt_close("tet10 cantilever nu = 0.3: tip deflection vs Timoshenko", d3, r3, 0, 0.04);
  kt_close("tet10 cantilever nu = 0.4995 (K/mu = 1000): tip deflection vs Timoshenko", d5, r5, 0, 0.04);
  kt_close("tet10 cantilever deflection ratio nu 0.4995 / 0.3", d5 / d3, r5 / r3, 0, 0.01);
  double d6 = cantilever(FEM_TET10, 0.49995, P, 0), r6 = timoshenko(0.49995, P);
  kt_close("tet10 cantilever nu = 0.49995 (K/mu = 1e4): tip deflection vs Timoshenko", d6, r6, 0, 0.04);
  kt_close("tet10 cantilever deflection ratio nu 0.49995 / 0.3", d6 / d3, r6 / r3, 0, 0.01);
  double p5 = cantilever(FEM_TET10, 0.4995, P, -1), s5 = cantilever(FEM_TET10, 0.4995, P, 1e12);
  double t5 = cantilever(FEM_TET4, 0.4995, P, 0);
  if (!(p5 > 1.2 * r5)) {
    fprintf(stderr, "pure mean dilatation not too soft (%g vs %g): the test cannot tell\n", p5, r5);
    kt_fail++;
  }
  if (!(s5 < 0.92 * r5)) {
    fprintf(stderr, "displacement tet10 at K/mu = 1000 not locking (%g vs %g)\n", s5, r5);
    kt_fail++;
  }
  if (!(t5 < r5 / 3)) {
    fprintf(stderr, "tet4 at K/mu = 1000 is not locking (%g vs %g): the test cannot tell\n", t5, r5);
    kt_fail++;
  }
  if (getenv("FEM_KERNELS_VERBOSE"))
    printf("Timoshenko nu=0.3: %.6g, nu=0.4995: %.6g\n"
           "tet10 default: nu=0.3 %.6g (%.4f), nu=0.4995 %.6g (%.4f)\n"
           "nu=0.4995: pure mean dilatation %.6g (%.4f), displacement tet10 %.6g (%.4f), "
           "tet4 %.6g (%.4f)\n",
           r3, r5, d3, d3 / r3, d5, d5 / r5, p5, p5 / r5, s5, s5 / r5, t5, t5 / r5);
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
