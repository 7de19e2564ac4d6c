/* The run check "is every grain inside the bore" (dem_bore_count_outside, dem_checks.h) on a
 * faceted cylinder whose open top edge zig-zags between z = -5 and -7 mm, as the lower edge of
 * [dem] rigid_band does on the scene's mesh, and on the same cylinder with a flat edge at z = 0.
 *
 * Reference: the geometry itself. A point is inside the bore when it lies inside the inscribed
 * polygon of the facets (radius R cos(pi/n)) above the floor, whatever its height below the
 * barrel's top: the band and the barrel continue the cavity upwards. Points are kept 0.1 mm or
 * more from every facet, so the answer is unambiguous. A fan closing the zig-zag edge directly
 * (the check before stop 43) judged the points between the fan and the edge's highest vertex
 * outside: a grain 0.14 mm below the band stopped a run as "tunnelled". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dem_checks.h"

#define NTH 48
#define R 6e-3
#define ZFLOOR (-80e-3)

/* Cylinder wall of NTH facets around and nz rows from the floor up to the top edge (vertex j of
 * the top row at z_top(j)), plus a fan floor; triangles consistently oriented. */
static int build(int zigzag, double **xyz, int **tri, int *nv) {
  const int nz = 20;
  *nv = NTH * (nz + 1) + 1;
  int nt = 2 * NTH * nz + NTH;
  *xyz = malloc(sizeof(double) * 3 * (size_t)*nv);
  *tri = malloc(sizeof(int) * 3 * (size_t)nt);
  if (!*xyz || !*tri) exit(2);
  for (int k = 0; k <= nz; k++)
    for (int j = 0; j < NTH; j++) {
      double th = 2 * M_PI * j / NTH, *p = *xyz + 3 * (k * NTH + j);
      double ztop = zigzag ? (j % 2 ? -7e-3 : -5e-3) : 0;
      double zk = k < nz ? ZFLOOR + (-9e-3 - ZFLOOR) * k / (nz - 1) : ztop;
      p[0] = R * cos(th), p[1] = R * sin(th), p[2] = zk;
    }
  double *c = *xyz + 3 * (*nv - 1);
  c[0] = 0, c[1] = 0, c[2] = ZFLOOR;
  int t = 0;
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < NTH; j++) {
      int a = k * NTH + j, b = k * NTH + (j + 1) % NTH, a1 = a + NTH, b1 = b + NTH;
      int *q = *tri + 3 * t;
      q[0] = a, q[1] = b, q[2] = b1, q[3] = a, q[4] = b1, q[5] = a1;
      t += 2;
    }
  for (int j = 0; j < NTH; j++) {
    int *q = *tri + 3 * t++;
    q[0] = (j + 1) % NTH, q[1] = j, q[2] = *nv - 1;
  }
  return nt;
}

int main(void) {
  const double r_in = R * cos(M_PI / NTH);
  const double radii[] = {0, 3e-3, 4.98e-3, 5.8e-3, 6.3e-3, 8e-3};
  const double heights[] = {-79e-3, -40e-3, -8e-3, -6.5e-3, -6e-3, -5.14e-3, -3e-3, 10e-3};
  int fails = 0, checked = 0;
  for (int zigzag = 0; zigzag <= 1; zigzag++) {
    double *xyz;
    int *tri, nv, nt = build(zigzag, &xyz, &tri, &nv);
    DemBore *b = NULL;
    if (dem_bore_create(nv, tri, nt, R, &b)) return 2;
    for (size_t ir = 0; ir < sizeof radii / sizeof *radii; ir++)
      for (size_t iz = 0; iz < sizeof heights / sizeof *heights; iz++)
        for (int ith = 0; ith < 2 * NTH; ith++) { /* at the vertices and between them */
          double th = M_PI * ith / NTH, p[3] = {radii[ir] * cos(th), radii[ir] * sin(th), heights[iz]};
          int expect_out = radii[ir] > r_in;
          int out = dem_bore_count_outside(b, xyz, 1, p, 0, NULL);
          checked++;
          if (out != expect_out && fails++ < 10)
            fprintf(stderr, "%s edge: point r = %.2f mm, theta = %.1f deg, z = %.2f mm judged %s\n",
                    zigzag ? "zig-zag" : "flat", radii[ir] * 1e3, th * 180 / M_PI, p[2] * 1e3,
                    out ? "outside" : "inside");
        }
    dem_bore_destroy(&b);
    free(xyz);
    free(tri);
  }
  if (fails) fprintf(stderr, "%d of %d points misjudged\n", fails, checked);
  return fails != 0;
}
