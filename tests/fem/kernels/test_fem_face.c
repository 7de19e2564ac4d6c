/* test_fem_face.c - follower-pressure and face-volume kernels.
 *  1. Load stiffness Ke = -dfe/dx vs central FD of fe, face-volume gradient vs FD of the volume
 *     and Hessian vs FD of the gradient, on random tri3 and curved tri6 faces (h = 1e-6, face
 *     size 1: FD error < 1e-9 of the largest entry; rtol 1e-6).
 *  2. Closed surface: the unit cube's boundary as 12 tri6 faces (normals into the cube, i.e.
 *     out of a surrounding solid, as on a cavity wall), every node mapped by the quadratic map
 *     phi(X) = X + (a X2^2, b X1 X3, c X1^2) + offset. A tri6 represents the image of a flat
 *     triangle under a quadratic map exactly, so the enclosed volume is exactly
 *     int_cube det grad phi = int (1 - 2ab X2 X3 + 4abc X1^2 X2) = 1 - ab/2 + 2abc/3
 *     (independent of the offset from the origin); the faces integrate it exactly (degree 4).
 *  3. Pressure/volume consistency on that closed surface: the assembled pressure force equals
 *     p dV/dx, the assembled load stiffness equals -p d2V/dx2 (and is symmetric), and the net
 *     force is zero (closed surface: int n da = 0). Round-off level tolerances (1e-12). */
#include <stdio.h>
#include <string.h>

#include "fem_element.h"
#include "kt_util.h"

static void fd_face(int nfn, double curve)
{
  const int nd = 3 * nfn;
  char what[160];
  static const double c0[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  static const int edge[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (int trial = 0; trial < 5; trial++) {
    double x[18], fe[18], Ke[324], fp[18], fm[18], dv[18], d2v[324], dvp[18], dvm[18];
    for (int a = 0; a < 3; a++)
      for (int k = 0; k < 3; k++) x[3 * a + k] = c0[a][k] + kt_rand(-0.3, 0.3) + 0.5;
    for (int e = 0; nfn == 6 && e < 3; e++)
      for (int k = 0; k < 3; k++)
        x[3 * (3 + e) + k] = 0.5 * (x[3 * edge[e][0] + k] + x[3 * edge[e][1] + k]) +
                             kt_rand(-curve, curve);
    double p = kt_rand(0.5, 2), h = 1e-6;
    fem_face_pressure(nfn, x, p, fe, Ke);
    fem_face_volume(nfn, x, dv, d2v);
    double Kmax = kt_maxabs(Ke, nd * nd), dvmax = kt_maxabs(dv, nd), Hmax = kt_maxabs(d2v, nd * nd);
    for (int c = 0; c < nd; c++) {
      double xs = x[c];
      x[c] = xs + h;
      fem_face_pressure(nfn, x, p, fp, NULL);
      double vp = fem_face_volume(nfn, x, dvp, NULL);
      x[c] = xs - h;
      fem_face_pressure(nfn, x, p, fm, NULL);
      double vm = fem_face_volume(nfn, x, dvm, NULL);
      x[c] = xs;
      snprintf(what, sizeof what, "tri%d trial %d: dv[%d] vs FD", nfn, trial, c);
      kt_close(what, dv[c], (vp - vm) / (2 * h), 1e-6 * dvmax, 0);
      for (int r = 0; r < nd; r++) {
        snprintf(what, sizeof what, "tri%d trial %d: Ke[%d][%d] vs -FD of fe", nfn, trial, r, c);
        kt_close(what, Ke[r * nd + c], -(fp[r] - fm[r]) / (2 * h), 1e-6 * Kmax, 0);
        snprintf(what, sizeof what, "tri%d trial %d: d2v[%d][%d] vs FD of dv", nfn, trial, r, c);
        kt_close(what, d2v[r * nd + c], (dvp[r] - dvm[r]) / (2 * h), 1e-6 * Hmax, 0);
        snprintf(what, sizeof what, "tri%d trial %d: d2v symmetry", nfn, trial);
        kt_close(what, d2v[r * nd + c], d2v[c * nd + r], 1e-13 * Hmax, 0);
      }
    }
  }
}

/* Node (i,j,k) of the 3x3x3 grid on the unit cube. */
static int gid(int i, int j, int k) { return i + 3 * j + 9 * k; }

static void closed_cube(double a, double b, double c, const double off[3])
{
  double xn[27 * 3];
  for (int k = 0; k < 3; k++)
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) {
        double X[3] = {0.5 * i, 0.5 * j, 0.5 * k}, *x = xn + 3 * gid(i, j, k);
        x[0] = X[0] + a * X[1] * X[1] + off[0];
        x[1] = X[1] + b * X[0] * X[2] + off[1];
        x[2] = X[2] + c * X[0] * X[0] + off[2];
      }
  /* 12 tri6 faces: for each cube face (axis d, side s) split the square along a diagonal. */
  int faces[12][6], nf = 0;
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      int u = (d + 1) % 3, v = (d + 2) % 3, g[3][3];
      for (int p = 0; p < 3; p++)
        for (int q = 0; q < 3; q++) {
          int ijk[3];
          ijk[d] = 2 * s, ijk[u] = p, ijk[v] = q;
          g[p][q] = gid(ijk[0], ijk[1], ijk[2]);
        }
      /* triangles (00, 20, 22) and (00, 22, 02) in (u, v); right-hand normal along +d. */
      int t[2][6] = {{g[0][0], g[2][0], g[2][2], g[1][0], g[2][1], g[1][1]},
                     {g[0][0], g[2][2], g[0][2], g[1][1], g[1][2], g[0][1]}};
      for (int m = 0; m < 2; m++) {
        /* inward normal (into the cube): -d on side 1, +d on side 0 */
        if (s == 1) {
          int tmp = t[m][1];
          t[m][1] = t[m][2], t[m][2] = tmp;
          tmp = t[m][3];
          t[m][3] = t[m][5], t[m][5] = tmp;
        }
        memcpy(faces[nf++], t[m], sizeof t[m]);
      }
    }
  double V = 0, dV[81] = {0}, H[81 * 81], f[81] = {0}, K[81 * 81], p = 1.7;
  memset(H, 0, sizeof H);
  memset(K, 0, sizeof K);
  for (int e = 0; e < nf; e++) {
    double xe[18], dv[18], d2v[324], fe[18], Ke[324];
    for (int a = 0; a < 6; a++) memcpy(xe + 3 * a, xn + 3 * faces[e][a], 3 * sizeof(double));
    V += fem_face_volume(6, xe, dv, d2v);
    fem_face_pressure(6, xe, p, fe, Ke);
    for (int a = 0; a < 6; a++)
      for (int i = 0; i < 3; i++) {
        int r = 3 * faces[e][a] + i;
        dV[r] += dv[3 * a + i];
        f[r] += fe[3 * a + i];
        for (int b = 0; b < 6; b++)
          for (int k = 0; k < 3; k++) {
            int cc = 3 * faces[e][b] + k;
            H[r * 81 + cc] += d2v[(3 * a + i) * 18 + 3 * b + k];
            K[r * 81 + cc] += Ke[(3 * a + i) * 18 + 3 * b + k];
          }
      }
  }
  char what[160];
  double Vref = 1 - a * b / 2 + 2 * a * b * c / 3;
  snprintf(what, sizeof what, "closed tri6 cube (a=%g b=%g c=%g): volume", a, b, c);
  kt_close(what, V, Vref, 0, 1e-13);
  double fmax = kt_maxabs(f, 81), Kmax = kt_maxabs(K, 81 * 81), sum[3] = {0, 0, 0};
  for (int r = 0; r < 81; r++) {
    if (r / 3 == gid(1, 1, 1)) continue; /* the cube centre is no surface node */
    snprintf(what, sizeof what, "pressure force [%d] vs p dV/dx", r);
    kt_close(what, f[r], p * dV[r], 1e-13 * fmax, 0);
    sum[r % 3] += f[r];
    for (int cc = 0; cc < 81; cc++) {
      snprintf(what, sizeof what, "load stiffness [%d][%d] vs -p d2V/dx2", r, cc);
      kt_close(what, K[r * 81 + cc], -p * H[r * 81 + cc], 1e-13 * Kmax, 0);
      snprintf(what, sizeof what, "assembled load stiffness symmetry [%d][%d]", r, cc);
      kt_close(what, K[r * 81 + cc], K[cc * 81 + r], 1e-13 * Kmax, 0);
    }
  }
  for (int i = 0; i < 3; i++) {
    snprintf(what, sizeof what, "net pressure force on a closed surface [%d]", i);
    kt_close(what, sum[i], 0, 1e-13 * fmax, 0);
  }
}

int main(void)
{
  fd_face(3, 0);
  fd_face(6, 0.15);
  double o0[3] = {0, 0, 0}, o1[3] = {3.1, -2.2, 5.3};
  closed_cube(0, 0, 0, o0);
  closed_cube(0, 0, 0, o1);
  closed_cube(0.3, -0.4, 0.25, o0);
  closed_cube(0.3, -0.4, 0.25, o1);
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
