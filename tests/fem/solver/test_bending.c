/* test_bending - the bending-angle and centre-line definitions (docs/fem.md) on rigid motions.
 *
 * A column 0.01 x 0.01 x 0.08 hanging tip down (z from -0.08 to 0, surface `tip` at z = -0.08
 * with outward normal -e_z), tet10. Rotating it rigidly about +e_y by theta (x -> the rotated
 * position) must give a bending angle of exactly theta (toward -x is positive: the tip normal
 * -e_z turns to (-sin theta, 0, -cos theta)), for theta in (-180, 180); a rotation about e_z or
 * a translation must give 0. The centre-line of a translated column is the translated axis
 * (slice points = axis points to round-off: the element centroids of each slab average to the
 * slab's axis point by the mesh's mirror symmetry about the axis). Tolerances: round-off. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem.h"
#include "smesh.h"
#include "tutil.h"

static void map_col(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  X[0] = 0.01 * (xi[0] - 0.5);
  X[1] = 0.01 * (xi[1] - 0.5);
  X[2] = -0.08 * (1 - xi[2]);
}

int main(void) {
  SmeshBlock blk = {{2, 2, 8}, map_col, NULL, {"s0", "s1", "s2", "s3", "tip", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-12, &m));
  int n = m->nnodes, fails = 0;
  double *x = malloc(sizeof(double) * 3 * n), pi = 4 * atan(1.0);
  double thetas[] = {-120, -30, 0, 15, 90, 135, 179};
  for (int k = 0; k < 7; k++) {
    double t = thetas[k] * pi / 180, c = cos(t), s = sin(t);
    for (int i = 0; i < n; i++) { /* rotation about +y: x' = c x + s z, z' = -s x + c z */
      const double *X = m->xyz + 3 * i;
      x[3 * i] = c * X[0] + s * X[2] + 0.3;
      x[3 * i + 1] = X[1] - 0.1;
      x[3 * i + 2] = -s * X[0] + c * X[2] + 0.2;
    }
    double ang;
    TU_CHECK(fem_bending_angle(m, "tip", x, &ang));
    char w[64];
    snprintf(w, sizeof w, "rotation %.0f deg about +y", thetas[k]);
    fails += tu_close(w, ang, thetas[k], 1e-9, 0);
  }
  for (int i = 0; i < n; i++) { /* rotation about z by 40 deg: no bending */
    const double *X = m->xyz + 3 * i;
    double c = cos(0.7), s = sin(0.7);
    x[3 * i] = c * X[0] - s * X[1];
    x[3 * i + 1] = s * X[0] + c * X[1];
    x[3 * i + 2] = X[2];
  }
  double ang;
  TU_CHECK(fem_bending_angle(m, "tip", x, &ang));
  fails += tu_close("rotation about z", ang, 0.0, 1e-9, 0);
  /* centre-line of a translated column */
  for (int i = 0; i < 3 * n; i++) x[i] = m->xyz[i] + (i % 3 == 0 ? 0.01 : i % 3 == 2 ? -0.02 : 0);
  double zr[8], cl[24];
  TU_CHECK(fem_centerline(m, x, -0.08, 0.0, 8, zr, cl));
  for (int k = 0; k < 8; k++) {
    fails += tu_close("centre-line x", cl[3 * k], 0.01, 1e-15, 0);
    fails += tu_close("centre-line y", cl[3 * k + 1], 0.0, 1e-15, 0);
    fails += tu_close("centre-line z", cl[3 * k + 2], zr[k] - 0.02, 1e-12, 0);
  }
  free(x);
  smesh_free(&m);
  return fails ? 1 : 0;
}
