/* test_coupling_surface - the FEM side of the FEM-DEM force exchange (fem_coupling.h).
 *
 * Mesh: the inner half of a thick cylinder (radii R = 6 mm .. 8.5 mm, angle 0..pi, length
 * L = 20 mm), tet10, inner face "inner" (tri6 faces split into four flat triangles).
 * 1. Uniform pressure p on the flat triangles (force p A_t along the triangle normal, the wall
 *    pressing on the solid) scattered to the nodes: the resultant equals the analytic
 *    p * 2 R L along -y (the projection of the half-cylinder on the x-z plane is the 2R x L
 *    rectangle, exactly also for the polygonal surface because its boundary chords end on
 *    x = +-R), to round-off; the moment of the nodal forces equals the sum of c_t x F_t (force
 *    at the centroid) to round-off: the map keeps resultant and moment.
 * 2. Transpose property (virtual work): for a random nodal displacement field dx,
 *    sum_i f_i . dx_i = sum_t F_t . dx(centroid_t) for random triangle forces F_t.
 * 3. Rigid-body motion x -> Q X + c of the FEM moves the wall vertices exactly (to round-off),
 *    keeps every triangle area, and the interval velocities equal (x - x_mark) / dt.
 * 4. A missing surface is an input error naming it.
 * 5. The part below a height (fem_coupling_surface_create_below): the lower half of the faces,
 *    whose uniform-pressure resultant is p R L (half of 1.), and none is an input error. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem_coupling.h"
#include "smesh.h"
#include "tutil.h"

#define R_IN 6e-3
#define R_OUT 8.5e-3
#define LEN 20e-3

static void map_half_shell(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  double r = R_IN + (R_OUT - R_IN) * xi[0], th = M_PI * xi[1];
  X[0] = r * cos(th);
  X[1] = r * sin(th);
  X[2] = LEN * xi[2];
}

static unsigned long rng = 12345;
static double urand(void) {
  rng = rng * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(rng >> 11) / 9007199254740992.0 - 0.5;
}

int main(void) {
  SmeshBlock b = {{2, 12, 8}, map_half_shell, NULL, {"inner", NULL, NULL, NULL, NULL, NULL}};
  FemMesh *m = NULL;
  TU_CHECK(smesh_build(1, &b, 2, 1e-12, &m));
  FemCouplingSurface *c = NULL;
  const char *names[] = {"inner"};
  TU_CHECK(fem_coupling_surface_create(m, 1, names, &c));
  int nv = fem_coupling_surface_nverts(c), nt = fem_coupling_surface_ntri(c), fail = 0;
  const int *tri = fem_coupling_surface_triangles(c), *nodes = fem_coupling_surface_nodes(c);
  double *xw = malloc(sizeof(double) * 3 * nv), *ft = malloc(sizeof(double) * 3 * nt);
  double *fn = malloc(sizeof(double) * 3 * nv), *x = malloc(sizeof(double) * 3 * m->nnodes);
  double *vw = malloc(sizeof(double) * 3 * nv);
  if (!xw || !ft || !fn || !x || !vw) return 1;
  /* 2 * 12 * 8 cells: the inner side has 12 * 8 * 2 tri6 faces -> 4 flat triangles each */
  if (nt != 12 * 8 * 2 * 4) {
    fprintf(stderr, "triangles: %d, expected %d\n", nt, 12 * 8 * 2 * 4);
    fail = 1;
  }
  fem_coupling_surface_gather(c, m->xyz, xw);

  /* 1. uniform pressure */
  const double p = 1e4;
  double Mref[3] = {0, 0, 0};
  for (int t = 0; t < nt; t++) {
    double n[3], A = fem_coupling_surface_tri_area(c, xw, t, n), cen[3] = {0, 0, 0};
    for (int j = 0; j < 3; j++)
      for (int d = 0; d < 3; d++) cen[d] += xw[3 * tri[3 * t + j] + d] / 3;
    for (int d = 0; d < 3; d++) ft[3 * t + d] = -p * A * n[d]; /* outward n: push into solid */
    Mref[0] += cen[1] * ft[3 * t + 2] - cen[2] * ft[3 * t + 1];
    Mref[1] += cen[2] * ft[3 * t + 0] - cen[0] * ft[3 * t + 2];
    Mref[2] += cen[0] * ft[3 * t + 1] - cen[1] * ft[3 * t + 0];
  }
  fem_coupling_surface_scatter(c, ft, fn);
  double F[3] = {0, 0, 0}, M[3] = {0, 0, 0};
  for (int i = 0; i < nv; i++) {
    const double *xi = xw + 3 * i, *f = fn + 3 * i;
    for (int d = 0; d < 3; d++) F[d] += f[d];
    M[0] += xi[1] * f[2] - xi[2] * f[1];
    M[1] += xi[2] * f[0] - xi[0] * f[2];
    M[2] += xi[0] * f[1] - xi[1] * f[0];
  }
  /* the inner face's outward normal (out of the solid) points to the axis: -r; the pressure
   * pushes along +r, whose y-resultant over 0..pi is +2 R L p */
  fail |= tu_close("resultant y (analytic 2 p R L)", F[1], 2 * p * R_IN * LEN, 1e-12, 1e-12);
  fail |= tu_close("resultant x", F[0], 0, 1e-12 * p * R_IN * LEN, 0);
  fail |= tu_close("resultant z", F[2], 0, 1e-12 * p * R_IN * LEN, 0);
  for (int d = 0; d < 3; d++) fail |= tu_close("moment", M[d], Mref[d], 1e-15, 1e-11);

  /* 2. transpose property */
  double *dx = malloc(sizeof(double) * 3 * nv);
  if (!dx) return 1;
  for (int i = 0; i < 3 * nv; i++) dx[i] = urand();
  for (int i = 0; i < 3 * nt; i++) ft[i] = urand();
  fem_coupling_surface_scatter(c, ft, fn);
  double w_nodes = 0, w_tri = 0;
  for (int i = 0; i < 3 * nv; i++) w_nodes += fn[i] * dx[i];
  for (int t = 0; t < nt; t++)
    for (int j = 0; j < 3; j++)
      for (int d = 0; d < 3; d++) w_tri += ft[3 * t + d] * dx[3 * tri[3 * t + j] + d] / 3;
  fail |= tu_close("virtual work", w_nodes, w_tri, 1e-13, 1e-12);

  /* 3. rigid motion */
  double th = 0.7, Q[3][3] = {{cos(th), 0, sin(th)}, {0, 1, 0}, {-sin(th), 0, cos(th)}};
  double sh[3] = {1e-3, -2e-3, 5e-3}, dt = 1e-3;
  fem_coupling_surface_mark(c, m->xyz);
  for (int i = 0; i < m->nnodes; i++)
    for (int r = 0; r < 3; r++) {
      x[3 * i + r] = sh[r];
      for (int k = 0; k < 3; k++) x[3 * i + r] += Q[r][k] * m->xyz[3 * i + k];
    }
  double *xr = malloc(sizeof(double) * 3 * nv);
  if (!xr) return 1;
  fem_coupling_surface_gather(c, x, xr);
  fem_coupling_surface_velocities(c, x, dt, vw);
  double emax = 0, vmax = 0, amax = 0;
  for (int i = 0; i < nv; i++) {
    const double *X = m->xyz + 3 * nodes[i];
    for (int r = 0; r < 3; r++) {
      double e = sh[r];
      for (int k = 0; k < 3; k++) e += Q[r][k] * X[k];
      emax = fmax(emax, fabs(xr[3 * i + r] - e));
      vmax = fmax(vmax, fabs(vw[3 * i + r] - (e - X[r]) / dt));
    }
  }
  for (int t = 0; t < nt; t++)
    amax = fmax(amax, fabs(fem_coupling_surface_tri_area(c, xr, t, NULL) -
                           fem_coupling_surface_tri_area(c, xw, t, NULL)));
  fail |= tu_close("rigid motion of the wall", emax, 0, 1e-17, 0);
  fail |= tu_close("interval velocity", vmax, 0, 1e-13, 0);
  fail |= tu_close("area change under rigid motion", amax, 0, 1e-18, 0);

  /* 5. the part below z_max ([dem] rigid_band): z_max = L/2 lies on an element layer (8 cells
   * along z), so exactly the lower half of the faces is kept, and the same uniform pressure
   * on them has the resultant 2 p R (L/2) along y */
  {
    FemCouplingSurface *h = NULL;
    TU_CHECK(fem_coupling_surface_create_below(m, 1, names, 0.5 * LEN + 1e-9, &h));
    int hv = fem_coupling_surface_nverts(h), ht = fem_coupling_surface_ntri(h);
    const int *htri = fem_coupling_surface_triangles(h);
    double *hx = malloc(sizeof(double) * 3 * hv), *hf = malloc(sizeof(double) * 3 * ht);
    double *hn = malloc(sizeof(double) * 3 * hv);
    if (!hx || !hf || !hn) return 1;
    fem_coupling_surface_gather(h, m->xyz, hx);
    double zmax = -INFINITY, Fy = 0;
    for (int t = 0; t < ht; t++) {
      double n[3], A = fem_coupling_surface_tri_area(h, hx, t, n);
      for (int d = 0; d < 3; d++) hf[3 * t + d] = -p * A * n[d];
      for (int j = 0; j < 3; j++) zmax = fmax(zmax, hx[3 * htri[3 * t + j] + 2]);
    }
    fem_coupling_surface_scatter(h, hf, hn);
    for (int i = 0; i < hv; i++) Fy += hn[3 * i + 1];
    if (ht != 12 * 4 * 2 * 4 || zmax > 0.5 * LEN + 1e-12) {
      fprintf(stderr, "below L/2: %d triangles (expected %d), highest vertex z %g\n", ht,
              12 * 4 * 2 * 4, zmax);
      fail = 1;
    }
    fail |= tu_close("lower half: resultant y (analytic p R L)", Fy, p * R_IN * LEN, 1e-12, 1e-12);
    FemCouplingSurface *none = NULL;
    if (fem_coupling_surface_create_below(m, 1, names, -1e-3, &none) != SA_ERR_INPUT || none) {
      fprintf(stderr, "a surface with no face below z_max was not an input error\n");
      fail = 1;
    }
    sa_error_clear();
    free(hx), free(hf), free(hn);
    fem_coupling_surface_destroy(&h);
  }

  /* 4. missing surface */
  FemCouplingSurface *bad = NULL;
  const char *nope[] = {"no_such_wall"};
  if (fem_coupling_surface_create(m, 1, nope, &bad) != SA_ERR_INPUT || bad) {
    fprintf(stderr, "a missing surface was not an input error\n");
    fail = 1;
  }
  sa_error_clear();
  free(xw), free(ft), free(fn), free(x), free(vw), free(dx), free(xr);
  fem_coupling_surface_destroy(&c);
  smesh_free(&m);
  return fail;
}
