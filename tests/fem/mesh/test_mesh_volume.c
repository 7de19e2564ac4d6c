/* test_mesh_volume.c - mesh volumes and boundary surfaces against the analytic geometry.
 *
 * For every geometry (cook, cylinder, sphere, actuator with and without rings):
 *  - region volumes against hand-computed volumes: tet10 (curved, mid-nodes on the CAD surface)
 *    to 1e-4 relative; tet4 within the chord error bound derived below; planar geometry exact;
 *  - surface areas against the analytic areas (tet10, 1e-4);
 *  - outward orientation: (a) for each face the opposite vertex of its element lies on the inner
 *    side; (b) over the whole boundary (the union of surfaces that close the solid) the area
 *    vector int n da sums to 0 and (1/3) int x.n da equals the mesh volume (divergence theorem,
 *    exact on the mesh's own polynomial geometry, so 1e-10);
 *  - the actuator's cavity_wall, closed by the plane z = 0 through the origin, encloses the
 *    cavity volume pi R_cav^2 L_cav;
 *  - parameters reach the .geo (cylinder with A, B, t given). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_test_util.h"
#include "sa_error.h"
#include "sa_log.h"

static int generate(const char *geo, int np, const FemGeoParam *p, double h, int order,
                    FemMesh **m)
{
  char path[512];
  if (fem_mesh_generate(mt_geo(geo, path, sizeof path), np, p, h, order, m)) {
    sa_error_print();
    return 1;
  }
  if (fem_mesh_check(*m, 1e-6)) {
    sa_error_print();
    return 1;
  }
  return 0;
}

/* (a): every face's element has its remaining corner behind the face. */
static int check_face_sides(const FemMesh *m, const char *label)
{
  for (int s = 0; s < m->nsurfaces; ++s) {
    const FemSurface *S = &m->surfaces[s];
    for (int f = 0; f < S->nfaces; ++f) {
      const int *fc = S->faces + S->nfn * f, *c = m->conn + (size_t)m->nen * S->face_elem[f];
      int opp = -1, nin = 0;
      for (int a = 0; a < 4; ++a) {
        int in = (c[a] == fc[0] || c[a] == fc[1] || c[a] == fc[2]);
        nin += in;
        if (!in) opp = c[a];
      }
      if (nin != 3) {
        fprintf(stderr, "%s: surface %s face %d is not a face of its element\n", label, S->name, f);
        return 1;
      }
      const double *x0 = m->xyz + 3 * fc[0], *x1 = m->xyz + 3 * fc[1], *x2 = m->xyz + 3 * fc[2],
                   *xo = m->xyz + 3 * opp;
      double u[3], v[3], w[3];
      for (int i = 0; i < 3; ++i) u[i] = x1[i] - x0[i], v[i] = x2[i] - x0[i], w[i] = xo[i] - x0[i];
      double d = (u[1] * v[2] - u[2] * v[1]) * w[0] + (u[2] * v[0] - u[0] * v[2]) * w[1] +
                 (u[0] * v[1] - u[1] * v[0]) * w[2];
      if (d >= 0) {
        fprintf(stderr, "%s: surface %s face %d normal points into its element\n", label, S->name, f);
        return 1;
      }
    }
  }
  return 0;
}

/* (b): over the named surfaces (which close the solid). */
static int check_closed(const FemMesh *m, const char *label, int n, const char *const *names)
{
  double a[3] = {0, 0, 0}, vol = 0, area = 0;
  for (int i = 0; i < n; ++i) {
    const FemSurface *S = fem_mesh_find_surface(m, names[i]);
    if (!S) {
      fprintf(stderr, "%s: surface %s missing\n", label, names[i]);
      return 1;
    }
    double ai[3], vi;
    mt_surface_integrals(m, S, ai, &vi);
    for (int k = 0; k < 3; ++k) a[k] += ai[k];
    vol += vi;
    area += mt_surface_area(m, S);
  }
  int ok = 1;
  char l[128];
  for (int k = 0; k < 3; ++k) {
    snprintf(l, sizeof l, "%s: closed boundary area vector [%d]", label, k);
    ok &= mt_close(l, a[k], 0.0, 1e-10 * area, 0.0);
  }
  /* n points out of the solid, so -(1/3) int x.n da = -V */
  snprintf(l, sizeof l, "%s: -(1/3) int x.n da vs -(mesh volume)", label);
  ok &= mt_close(l, vol, -fem_mesh_volume(m, -1), 0.0, 1e-10);
  return !ok;
}

static int test_cook(void)
{
  int fail = 0;
  const double s = 1e-3, t = 1e-3, V = 0.5 * 48 * (44 + 16) * s * s * t;
  const char *all[] = {"clamped", "loaded", "front", "back", "free"};
  for (int order = 1; order <= 2; ++order) {
    FemMesh *m = NULL;
    if (generate("cook.geo", 0, NULL, 0.0, order, &m)) return 1;
    /* planar geometry: exact up to round-off */
    fail |= !mt_close("cook volume", fem_mesh_volume(m, -1), V, 0, 1e-12);
    fail |= !mt_close("cook loaded area", mt_surface_area(m, fem_mesh_find_surface(m, "loaded")),
                      16 * s * t, 0, 1e-12);
    fail |= !mt_close("cook front area", mt_surface_area(m, fem_mesh_find_surface(m, "front")),
                      V / t, 0, 1e-12);
    fail |= check_face_sides(m, "cook");
    fail |= check_closed(m, "cook", 5, all);
    fem_mesh_destroy(&m);
  }
  return fail;
}

static int test_cylinder(void)
{
  int fail = 0;
  /* parameters different from the defaults reach the .geo */
  const double A = 5e-3, B = 7e-3, t = 1.5e-3, h = 0.75e-3;
  const FemGeoParam p[] = {{"A", A}, {"B", B}, {"t", t}};
  const double V = 0.25 * M_PI * (B * B - A * A) * t;
  const char *all[] = {"inner", "outer", "sym_x", "sym_y", "bottom", "top"};
  for (int order = 1; order <= 2; ++order) {
    FemMesh *m = NULL;
    if (generate("cylinder.geo", 3, p, h, order, &m)) return 1;
    double v = fem_mesh_volume(m, -1);
    if (order == 2) {
      fail |= !mt_close("cylinder tet10 volume", v, V, 0, 1e-4);
      fail |= !mt_close("cylinder tet10 inner area",
                        mt_surface_area(m, fem_mesh_find_surface(m, "inner")), 0.5 * M_PI * A * t, 0,
                        1e-4);
    } else {
      /* Chords of length c <= 1.5 h cut segments of area R^2 (th - sin th)/2 ~ c^3 / (12 R)
       * off each arc, pi R / (2 c) segments per quarter circle: pi c^2 / 24 per circle, so
       * |V_mesh - V| <= 2 (pi (1.5 h)^2 / 24) t (outer deficit and inner excess). */
      double bound = 2.0 * M_PI * pow(1.5 * h, 2) / 24.0 * t;
      fail |= !mt_close("cylinder tet4 volume (chord error bound)", v, V, bound, 0);
    }
    fail |= check_face_sides(m, "cylinder");
    fail |= check_closed(m, "cylinder", 6, all);
    fem_mesh_destroy(&m);
  }
  return fail;
}

static int test_sphere(void)
{
  int fail = 0;
  const double A = 10e-3, B = 12.5e-3, h = 1.5e-3;
  const double V = M_PI / 6.0 * (B * B * B - A * A * A);
  const char *all[] = {"inner", "outer", "sym_x", "sym_y", "sym_z"};
  for (int order = 1; order <= 2; ++order) {
    FemMesh *m = NULL;
    if (generate("sphere.geo", 0, NULL, h, order, &m)) return 1;
    double v = fem_mesh_volume(m, -1);
    if (order == 2) {
      fail |= !mt_close("sphere tet10 volume", v, V, 0, 1e-4);
      fail |= !mt_close("sphere tet10 outer area",
                        mt_surface_area(m, fem_mesh_find_surface(m, "outer")), 0.5 * M_PI * B * B, 0,
                        1e-4);
    } else {
      /* A flat triangle with edges <= c = 1.5 h on a sphere of radius R lies within the sagitta
       * c^2 / (8 R) of it: |dV| <= area * c^2 / (8 R) on each of the two spherical surfaces,
       * (pi R^2 / 2) c^2 / (8 R) = pi R c^2 / 16. */
      double bound = M_PI * (A + B) * pow(1.5 * h, 2) / 16.0;
      fail |= !mt_close("sphere tet4 volume (sagitta bound)", v, V, bound, 0);
    }
    fail |= check_face_sides(m, "sphere");
    fail |= check_closed(m, "sphere", 5, all);
    fem_mesh_destroy(&m);
  }
  return fail;
}

/* Reference actuator (ACTUATOR.md), mm converted to m. */
/* Faces that bound one element only must be exactly the faces of the named surfaces: a
 * mesh with an internal crack (blocks or a seam not merged) or a face left out of every
 * surface fails. */
typedef struct {
  int v[3];
} Tri;
static int cmp_tri(const void *a, const void *b)
{
  const Tri *p = a, *q = b;
  for (int k = 0; k < 3; ++k)
    if (p->v[k] != q->v[k]) return p->v[k] < q->v[k] ? -1 : 1;
  return 0;
}
static void sort3(int *v)
{
  for (int i = 1; i < 3; ++i)
    for (int j = i; j > 0 && v[j] < v[j - 1]; --j) {
      int t = v[j];
      v[j] = v[j - 1], v[j - 1] = t;
    }
}
static int check_no_crack(const FemMesh *m, const char *label)
{
  static const int fo[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  long n = 4L * m->nelem, nb = 0, ns = 0;
  Tri *t = malloc(sizeof(Tri) * (size_t)n);
  for (int e = 0; e < m->nelem; ++e)
    for (int f = 0; f < 4; ++f) {
      Tri *q = t + 4L * e + f;
      for (int k = 0; k < 3; ++k) q->v[k] = m->conn[(size_t)m->nen * e + fo[f][k]];
      sort3(q->v);
    }
  qsort(t, (size_t)n, sizeof(Tri), cmp_tri);
  for (long i = 0; i < n;) {
    long j = i;
    while (j < n && !cmp_tri(t + i, t + j)) ++j;
    if (j - i == 1) ++nb;
    else if (j - i > 2) {
      fprintf(stderr, "%s: a face shared by %ld elements\n", label, j - i);
      free(t);
      return 1;
    }
    i = j;
  }
  int fail = 0;
  for (int s = 0; s < m->nsurfaces; ++s) {
    const FemSurface *S = &m->surfaces[s];
    ns += S->nfaces;
    for (int f = 0; f < S->nfaces && !fail; ++f) {
      Tri key;
      for (int k = 0; k < 3; ++k) key.v[k] = S->faces[S->nfn * f + k];
      sort3(key.v);
      Tri *hit = bsearch(&key, t, (size_t)n, sizeof(Tri), cmp_tri);
      /* a surface face must be a boundary face: its neighbours in the sorted list differ */
      if (!hit || (hit > t && !cmp_tri(hit - 1, hit)) || (hit < t + n - 1 && !cmp_tri(hit + 1, hit))) {
        fprintf(stderr, "%s: surface %s face %d is not a boundary face\n", label, S->name, f);
        fail = 1;
      }
    }
  }
  free(t);
  char l[128];
  snprintf(l, sizeof l, "%s: boundary faces = faces of the named surfaces", label);
  return fail | !mt_close(l, (double)nb, (double)ns, 0, 0);
}

/* The reference actuator, from actuator.geo (swept = 0) or the swept grid (fem_mesh_swept.c). */
static int test_actuator_mesh(int rings, int swept)
{
  int fail = 0;
  const double mm = 1e-3, Rc = 6 * mm, Ro = 8.5 * mm, L = 80 * mm, tc = 4 * mm, Lf = 5 * mm;
  /* band: annular sector of arc 10 mm at mid radius 7.25 mm, i.e. area a (ro^2 - ri^2) with
   * a = 5 / 7.25 -> 10 mm x 0.5 mm = 5 mm^2 exactly, over 80 mm */
  const double a = 5.0 / 7.25, Vband = a * (7.5 * 7.5 - 7.0 * 7.0) * mm * mm * L;
  /* rings: 16 annuli 8.0..8.5 mm, 0.5 mm high */
  const double Vring = rings ? 16 * M_PI * (Ro * Ro - 8.0 * 8.0 * mm * mm) * 0.5 * mm : 0.0;
  const double Vbody = M_PI * (Ro * Ro - Rc * Rc) * L + M_PI * Ro * Ro * tc;
  const double Vsil = Vbody - Vband - Vring;
  const FemGeoParam p[] = {{"rings", rings}};
  const char *label = swept ? (rings ? "swept actuator" : "swept actuator (no rings)")
                            : (rings ? "actuator" : "actuator (no rings)");
  const char *all[] = {"cavity_wall", "fixed_end", "tip", "outer"};
  /* h = 3 mm keeps the test short; the thin parts are meshed at about 0.5-1 mm anyway */
  FemMesh *m = NULL;
  if (swept) {
    /* the swept grid: h 3 mm (as the .geo test), band and rings 0.5 mm across */
    FemSweptActuator sp = fem_swept_actuator_default(3e-3, 1e-3, 0.5e-3, 0.5e-3, rings);
    if (fem_mesh_actuator_swept(&sp, 2, &m) || fem_mesh_check(m, 1e-6)) {
      sa_error_print();
      return 1;
    }
  } else if (generate("actuator.geo", 1, p, 3e-3, 2, &m)) {
    return 1;
  }
  const char *regs[] = {"silicone", "strain_limit", "reinforcement"};
  const char *surfs[] = {"cavity_wall", "fixed_end", "tip", "outer"};
  if (fem_mesh_require(m, rings ? 3 : 2, regs, 4, surfs)) {
    sa_error_print();
    fem_mesh_destroy(&m);
    return 1;
  }
  if (!rings && fem_mesh_find_region(m, "reinforcement") >= 0) {
    fprintf(stderr, "%s: has a reinforcement region\n", label);
    fail = 1;
  }
  /* curved tet10: geometric error of quadratic arcs ~ (h/R)^4, far below 1e-4 */
  fail |= !mt_close("actuator silicone volume", fem_mesh_volume(m, fem_mesh_find_region(m, "silicone")),
                    Vsil, 0, 1e-4);
  fail |= !mt_close("actuator band volume",
                    fem_mesh_volume(m, fem_mesh_find_region(m, "strain_limit")), Vband, 0, 1e-4);
  if (rings)
    fail |= !mt_close("actuator ring volume",
                      fem_mesh_volume(m, fem_mesh_find_region(m, "reinforcement")), Vring, 0, 1e-4);
  double A_cav = 2 * M_PI * Rc * L + M_PI * Rc * Rc;
  double A_fix = 2 * M_PI * Ro * Lf + M_PI * (Ro * Ro - Rc * Rc);
  double A_tip = M_PI * Ro * Ro;
  double A_out = 2 * M_PI * Ro * (L + tc - Lf);
  fail |= !mt_close("cavity_wall area", mt_surface_area(m, fem_mesh_find_surface(m, "cavity_wall")),
                    A_cav, 0, 1e-4);
  fail |= !mt_close("fixed_end area", mt_surface_area(m, fem_mesh_find_surface(m, "fixed_end")),
                    A_fix, 0, 1e-4);
  fail |= !mt_close("tip area", mt_surface_area(m, fem_mesh_find_surface(m, "tip")), A_tip, 0, 1e-4);
  fail |= !mt_close("outer area", mt_surface_area(m, fem_mesh_find_surface(m, "outer")), A_out, 0,
                    1e-4);
  /* cavity closed by the plane z = 0 (x.n = 0 there): encloses pi Rc^2 L */
  double av[3], vc;
  mt_surface_integrals(m, fem_mesh_find_surface(m, "cavity_wall"), av, &vc);
  fail |= !mt_close("cavity volume from cavity_wall", vc, M_PI * Rc * Rc * L, 0, 1e-4);
  /* fixed_end lies in z >= -L_fix, tip at z = -(L + tc) */
  const FemSurface *fx = fem_mesh_find_surface(m, "fixed_end"), *tp = fem_mesh_find_surface(m, "tip");
  for (int i = 0; i < fx->nnodes; ++i)
    if (m->xyz[3 * fx->nodes[i] + 2] < -Lf - 1e-9) {
      fprintf(stderr, "fixed_end node %d at z = %g\n", fx->nodes[i], m->xyz[3 * fx->nodes[i] + 2]);
      fail = 1;
      break;
    }
  for (int i = 0; i < tp->nnodes; ++i)
    if (fabs(m->xyz[3 * tp->nodes[i] + 2] + L + tc) > 1e-9) {
      fprintf(stderr, "tip node %d at z = %g\n", tp->nodes[i], m->xyz[3 * tp->nodes[i] + 2]);
      fail = 1;
      break;
    }
  fail |= check_face_sides(m, label);
  fail |= check_closed(m, label, 4, all);
  fail |= check_no_crack(m, label);
  fem_mesh_destroy(&m);
  return fail;
}
static int test_actuator(int rings) { return test_actuator_mesh(rings, 0); }

int main(void)
{
  sa_log_set_level(SA_LOG_WARN);
  int fail = 0;
  fail |= test_cook();
  fail |= test_cylinder();
  fail |= test_sphere();
  fail |= test_actuator(1);
  fail |= test_actuator(0);
  fail |= test_actuator_mesh(1, 1);
  fail |= test_actuator_mesh(0, 1);
  return fail;
}
