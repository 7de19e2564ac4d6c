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
#include "dem_checks.h"
#include "dem_test_util.h"

#define NTH 48
#define R 6e-3
#define ZFLOOR (-80e-3)

/* The wall: t_tube from the floor to z = -5 mm (20 rows), its top row then moved to z_top(j)
 * (zig-zag: -5 / -7 mm by turns; flat: 0), closed below by a fan floor on the same vertices. */
static int build(int zigzag, double **xyz, int **tri, int *nv) {
  const int nz = 20;
  int nt;
  t_tube(0, 0, R, ZFLOOR, -5e-3, NTH, nz, xyz, tri, nv, &nt);
  *xyz = realloc(*xyz, sizeof(double) * 3 * (size_t)(*nv + 1));
  *tri = realloc(*tri, sizeof(int) * 3 * (size_t)(nt + NTH));
  if (!*xyz || !*tri) exit(2);
  for (int j = 0; j < NTH; j++) (*xyz)[3 * (nz * NTH + j) + 2] = zigzag ? (j % 2 ? -7e-3 : -5e-3) : 0;
  double *c = *xyz + 3 * (*nv)++;
  c[0] = 0, c[1] = 0, c[2] = ZFLOOR;
  for (int j = 0; j < NTH; j++) {
    int *q = *tri + 3 * nt++;
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
