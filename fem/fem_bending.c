/* fem_bending.c - bending angle and deformed centre-line of the actuator (docs/fem.md).
 *
 * Bending angle: n = sum over the faces of surface `tip` of the face's vector area
 * (int n da, the deformed outward normal weighted by area; tri6 faces split into their four
 * corner/mid-node sub-triangles), n0 the same sum in the reference configuration. Both are
 * projected on the x-z plane and the angle is the signed rotation from n0 to n about +y:
 *   theta = atan2((n0 x n) . e_y, n0 . n)   [deg, in (-180, 180]]
 * A rotation about +y turns the reference tip normal -e_z toward -e_x, the strain-limiting
 * side, so bending toward the strain-limiting layer is positive.
 *
 * Centre-line: slice the reference length into nslices equal slabs; a slab's centre point is
 * the reference-volume-weighted mean of the deformed images of the reference centroids of the
 * elements whose reference centroid lies in the slab. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_error.h"

static void tri_area_vec(const double *a, const double *b, const double *c, double *n) {
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
  n[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
  n[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
}

static void surface_vector_area(const FemSurface *s, const double *x, double n[3]) {
  n[0] = n[1] = n[2] = 0.0;
  for (int f = 0; f < s->nfaces; f++) {
    const int *c = s->faces + (size_t)f * s->nfn;
    if (s->nfn == 3) {
      tri_area_vec(x + 3 * c[0], x + 3 * c[1], x + 3 * c[2], n);
    } else { /* corners 0,1,2, mid-nodes 3 (01), 4 (12), 5 (20) */
      const double *p[6];
      for (int a = 0; a < 6; a++) p[a] = x + 3 * c[a];
      tri_area_vec(p[0], p[3], p[5], n);
      tri_area_vec(p[3], p[1], p[4], n);
      tri_area_vec(p[5], p[4], p[2], n);
      tri_area_vec(p[3], p[4], p[5], n);
    }
  }
}

int fem_bending_angle(const FemMesh *m, const char *tip, const double *x, double *deg) {
  const FemSurface *s = fem_mesh_find_surface(m, tip);
  SA_REQUIRE(s, SA_ERR_INPUT, "mesh has no surface '%s' for the bending angle", tip);
  double n0[3], n[3];
  surface_vector_area(s, m->xyz, n0);
  surface_vector_area(s, x, n);
  double cr = n0[2] * n[0] - n0[0] * n[2];
  double dt = n0[0] * n[0] + n0[2] * n[2];
  SA_REQUIRE(fabs(cr) + fabs(dt) > 0.0, SA_ERR_NUMERICAL,
             "surface '%s' has no normal component in the x-z plane", tip);
  *deg = atan2(cr, dt) * (45.0 / atan(1.0));
  return 0;
}

int fem_centerline(const FemMesh *m, const double *x, double zmin, double zmax, int nslices,
                   double *z_ref, double *c) {
  SA_REQUIRE(nslices > 0 && zmax > zmin, SA_ERR_INPUT, "bad centre-line slicing");
  double *w;
  SA_CALLOC(w, nslices);
  memset(c, 0, 3 * (size_t)nslices * sizeof *c);
  double h = (zmax - zmin) / nslices;
  int nen = m->nen;
  for (int e = 0; e < m->nelem; e++) {
    const int *cn = m->conn + (size_t)e * nen;
    const double *X0 = m->xyz + 3 * cn[0], *X1 = m->xyz + 3 * cn[1], *X2 = m->xyz + 3 * cn[2],
                 *X3 = m->xyz + 3 * cn[3];
    double zc = 0.25 * (X0[2] + X1[2] + X2[2] + X3[2]);
    int k = (int)floor((zc - zmin) / h);
    if (k < 0 || k >= nslices) continue;
    double a[3], b[3], d[3];
    for (int i = 0; i < 3; i++) {
      a[i] = X1[i] - X0[i];
      b[i] = X2[i] - X0[i];
      d[i] = X3[i] - X0[i];
    }
    double vol = fabs(a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                      a[2] * (b[0] * d[1] - b[1] * d[0])) / 6.0;
    double xc[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
      if (nen == 10) { /* x at the reference centroid: N_corner = -1/8, N_mid = 1/4 */
        for (int q = 0; q < 4; q++) xc[i] -= 0.125 * x[3 * cn[q] + i];
        for (int q = 4; q < 10; q++) xc[i] += 0.25 * x[3 * cn[q] + i];
      } else {
        for (int q = 0; q < 4; q++) xc[i] += 0.25 * x[3 * cn[q] + i];
      }
    }
    w[k] += vol;
    for (int i = 0; i < 3; i++) c[3 * k + i] += vol * xc[i];
  }
  for (int k = 0; k < nslices; k++) {
    z_ref[k] = zmin + (k + 0.5) * h;
    for (int i = 0; i < 3; i++) c[3 * k + i] = w[k] > 0 ? c[3 * k + i] / w[k] : NAN;
  }
  free(w);
  return 0;
}
