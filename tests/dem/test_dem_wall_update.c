/* The one-pass update of a deforming wall mesh (dem_shim_mesh_set_nodes) against LIGGGHTS' own
 * routines (updateCenterRbound, recalcLocalSurfProperties, decideRebuild), bit for bit.
 *
 * Reference: LIGGGHTS itself. The wall moves every DEM step, and LIGGGHTS' recalculation
 * (a heap allocation per triangle in TriMesh::calcArea, norms taken twice, four passes over
 * the elements) was the exchange's largest cost; softact does the same arithmetic in one pass.
 * The two must agree in every bit of every value the contact code reads (centres, bounding
 * radii, unit edge vectors and lengths, normals, edge normals, areas, the obtuse-angle index
 * and the rebuild request), so a run is identical with either.
 * Scene: a tube of 4000 triangles (radius 8 mm, 40 mm high) around 300 grains; the tube is
 * moved (a bulge, a random jitter, a tilt) before LIGGGHTS' set-up, then between runs by less
 * and by more than half the skin (a rebuild must be requested), and last with one triangle
 * made collinear (LIGGGHTS' fallback normals). DEM_TEST_VERBOSE=1 prints the update times. */
#include "dem_test_util.h"

enum { NT = 40, NZ = 50, NV = NT * (NZ + 1), NTRI = 2 * NT * NZ };
static const double R = 8e-3, H = 40e-3;

/* Tube vertices moved by a bulge of amplitude a, a jitter of amplitude j (seeded) and a shear
 * s (x += s z). */
static void tube(double a, double j, double s, unsigned seed, double *xyz) {
  srand(seed);
  for (int k = 0; k <= NZ; k++)
    for (int i = 0; i < NT; i++) {
      double th = 2 * M_PI * i / NT, z = -H / 2 + H * k / NZ;
      double r = R * (1 + a * cos(M_PI * z / H));
      double *p = xyz + 3 * (k * NT + i);
      p[0] = r * cos(th) + s * z;
      p[1] = r * sin(th);
      p[2] = z;
      for (int c = 0; c < 3; c++) p[c] += j * (2.0 * rand() / RAND_MAX - 1);
    }
}

static void tube_triangles(int *tri) {
  int n = 0;
  for (int k = 0; k < NZ; k++)
    for (int i = 0; i < NT; i++) {
      int a = k * NT + i, b = k * NT + (i + 1) % NT, c = a + NT, d = b + NT;
      tri[n++] = a, tri[n++] = b, tri[n++] = d;
      tri[n++] = a, tri[n++] = d, tri[n++] = c;
    }
}

static double median(double *x, int n) {
  for (int i = 1; i < n; i++)
    for (int k = i; k > 0 && x[k] < x[k - 1]; k--) {
      double t = x[k];
      x[k] = x[k - 1], x[k - 1] = t;
    }
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

/* Update through both paths, require bitwise agreement; returns the two times. */
static void check(DemBridge *b, int id, const double *xyz, const double *v, const char *what,
                  double *t_lean, double *t_ref) {
  long differ = -1;
  T_CHECK(dem_bridge_mesh_update_check(b, id, xyz, v, &differ, t_lean, t_ref));
  if (differ != 0) printf("%s: %ld surface values differ from LIGGGHTS' update\n", what, differ);
  t_true("one-pass wall update equals LIGGGHTS' bit for bit", differ == 0);
}

int main(void) {
  DemParams p;
  t_params(&p);
  p.gravity[2] = 0;
  static double xyz[3 * NV], v[3 * NV];
  static int tri[3 * NTRI];
  tube_triangles(tri);
  tube(0, 0, 0, 1, xyz);
  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));
  T_CHECK(dem_bridge_setup(b, &p));
  int id, ins;
  T_CHECK(dem_bridge_add_mesh(b, "tube", NV, xyz, NTRI, tri, DEM_WALL_SILICONE, &id));
  T_CHECK(dem_bridge_insert_cylinder(b, 0, 0, 0.8 * R, -0.4 * H, 0.4 * H, 300, &ins));
  t_true("grains inserted", ins > 100);
  for (int k = 0; k < 3 * NV; k++) v[k] = 0.01 * sin(k);
  double tl, tr;
  tube(0.02, 1e-5, 0.05, 2, xyz); /* before the set-up: no rebuild test */
  check(b, id, xyz, v, "before set-up", &tl, &tr);
  T_CHECK(dem_bridge_run(b, 20));
  const double skin = p.skin;
  double lean[20], ref[20];
  for (int it = 0; it < 20; it++) { /* small moves: 1e-3 of the skin, no rebuild */
    tube(0.02 + 1e-3 * skin / R * it, 1e-5, 0.05, 2, xyz);
    check(b, id, xyz, v, "small move", &lean[it], &ref[it]);
    T_CHECK(dem_bridge_run(b, 1));
  }
  double t_lean = median(lean, 20), t_ref = median(ref, 20);
  tube(0.02 + 2 * skin / R, 1e-5, 0.05, 2, xyz); /* a node moves by 2 skins: rebuild */
  check(b, id, xyz, NULL, "large move", &tl, &tr);
  T_CHECK(dem_bridge_run(b, 5));
  /* triangle 0 (vertices 0, 1, NT + 1) made collinear: the fallback normals */
  double *a = xyz, *c = xyz + 3 * (NT + 1), *m = xyz + 3;
  for (int k = 0; k < 3; k++) m[k] = 0.5 * (a[k] + c[k]);
  check(b, id, xyz, v, "collinear triangle", &tl, &tr);
  if (t_verbose())
    printf("%d triangles: one-pass update %.1f us (%.1f ns per triangle), LIGGGHTS' %.1f us "
           "(%.1f ns), ratio %.2f (medians of 20)\n",
           NTRI, 1e6 * t_lean, 1e9 * t_lean / NTRI, 1e6 * t_ref, 1e9 * t_ref / NTRI,
           t_ref / t_lean);
  dem_bridge_destroy(&b);
  if (t_failures) printf("%d failure(s)\n", t_failures);
  return t_failures != 0;
}
