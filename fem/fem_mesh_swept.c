/* fem_mesh_swept.c - the reference actuator as a swept (r, theta, z) tensor-grid mesh
 * (fem_mesh_actuator_swept, fem_mesh.h).
 *
 * Why: with isotropic tetrahedra the 0.5 mm rings and band force 0.5 mm elements all around the
 * 53 mm ring circumference, and the bending angle converges only at order ~1.1 in the ring size
 * (the bonded ring corners), so a mesh within 1 % of the converged angle needs over 1.6 M dofs
 * (docs/fem_time_to_accuracy.md). The actuator is an r-theta-z body: a grid whose lines pass
 * through every interface gives elements that are thin across the rings and band and long
 * along them, as CalculiX's ring-aligned C3D20R model (bench/fem/ccx/ccx_hex.c) does.
 *
 * Four blocks of fem_mesh_blocks, all with the index directions (r outward, theta
 * counter-clockwise, z up), so the Kuhn split conforms across every block face and the seam
 * theta = 0 = 2 pi (merged nodes):
 *   wall     r in [R_cav, R_out], z in [-L_cav, -L_fix]  sides: cavity_wall | outer
 *   top      r in [R_cav, R_out], z in [-L_fix, 0]       sides: cavity_wall | fixed_end, top
 *                                                         fixed_end
 *   cap ring r in [R_cav, R_out], z in [-L_tot, -L_cav]  sides: outer, bottom tip
 *   cap core r in [0, R_cav],     z in [-L_tot, -L_cav]  sides: bottom tip, top cavity_wall
 * (L_tot = L_cav + t_cap).
 * The core's axis cells are wedges (their flat Kuhn tets dropped). Mid-nodes lie on the map, so
 * tet10 edges follow the circles exactly. Regions are set from each element's centroid: the grid
 * lines include every interface, so every cell lies in one material. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_mesh.h"
#include "sa_error.h"

#define MAXC 4096 /* cells per axis */

typedef struct {
  int n;         /* cells */
  double c[MAXC + 1]; /* cell boundaries, increasing */
} Axis;

static int push(Axis *a, double x) {
  SA_REQUIRE(a->n < MAXC, SA_ERR_INPUT, "swept actuator mesh: more than %d cells along one axis "
             "(element sizes too small: raise [mesh] h, h_radial, h_band or h_ring, or raise grade)",
             MAXC);
  a->c[++a->n] = x;
  return 0;
}

/* [x0, x1] in equal cells no larger than size (the axis ends at x0 already). */
static int add_uniform(Axis *a, double x0, double x1, double size) {
  int n = (int)ceil((x1 - x0) / size - 1e-9);
  if (n < 1) n = 1;
  for (int i = 1; i <= n; i++) SA_CHECK(push(a, i == n ? x1 : x0 + (x1 - x0) * i / n));
  return 0;
}

/* [x0, x1] with cells growing geometrically by g from s0 at x0 and from s1 at x1 up to hmax,
 * equal cells no larger than hmax between. */
static int add_graded(Axis *a, double x0, double x1, double s0, double s1, double hmax, double g) {
  double L = x1 - x0, left[64], right[64];
  int nl = 0, nr = 0;
  double sl = 0, sr = 0;
  for (double s = fmin(s0, hmax); nl < 64 && sl + s <= 0.5 * L + 1e-12 * L; s = fmin(s * g, hmax)) {
    left[nl++] = s, sl += s;
    if (s >= hmax) break;
  }
  for (double s = fmin(s1, hmax); nr < 64 && sr + s <= 0.5 * L + 1e-12 * L; s = fmin(s * g, hmax)) {
    right[nr++] = s, sr += s;
    if (s >= hmax) break;
  }
  double mid = L - sl - sr, last = fmax(nl ? left[nl - 1] : 0, nr ? right[nr - 1] : 0);
  int nm = mid > 1e-12 * L ? (int)ceil(mid / hmax - 1e-9) : 0;
  if (nm == 0 && mid > 1e-12 * L) nm = 1;
  if (nm == 1 && mid < 0.5 * last) nm = 0; /* a sliver cell: spread it over the others */
  double scale = nm ? 1.0 : L / (sl + sr), x = x0;
  for (int i = 0; i < nl; i++) {
    x += scale * left[i];
    SA_CHECK(push(a, x));
  }
  for (int i = 0; i < nm; i++) {
    x += mid / nm;
    SA_CHECK(push(a, x));
  }
  for (int i = nr - 1; i >= 0; i--) {
    x += scale * right[i];
    SA_CHECK(push(a, i == 0 ? x1 : x));
  }
  return 0;
}

/* The part [lo, hi] of axis a (both grid lines of a) as its own axis. */
static int sub_axis(const Axis *a, double lo, double hi, Axis *out) {
  int i0 = -1, i1 = -1;
  for (int i = 0; i <= a->n; i++) {
    if (fabs(a->c[i] - lo) <= 1e-12) i0 = i;
    if (fabs(a->c[i] - hi) <= 1e-12) i1 = i;
  }
  SA_REQUIRE(i0 >= 0 && i1 > i0, SA_ERR_INTERNAL, "swept mesh: %g..%g not on the grid", lo, hi);
  out->n = i1 - i0;
  memcpy(out->c, a->c + i0, sizeof(double) * (size_t)(out->n + 1));
  return 0;
}

static double axis_at(const Axis *a, double xi) {
  double s = xi * a->n;
  int i = (int)floor(s);
  if (i >= a->n) i = a->n - 1;
  if (i < 0) i = 0;
  return a->c[i] + (s - i) * (a->c[i + 1] - a->c[i]);
}

typedef struct {
  const Axis *r, *th, *z;
} Polar;

static void polar_map(const double xi[3], const void *ctx, double X[3]) {
  const Polar *p = ctx;
  double r = axis_at(p->r, xi[0]), t = axis_at(p->th, xi[1]);
  X[0] = r * cos(t), X[1] = r * sin(t), X[2] = axis_at(p->z, xi[2]);
}

FemSweptActuator fem_swept_actuator_default(double h, double h_radial, double h_band,
                                            double h_ring, int rings) {
  FemSweptActuator p = {6e-3, 8.5e-3, 80e-3, 4e-3, 5e-3, 7e-3, 7.5e-3, 10e-3, rings, 16,
                        0.5e-3, 0.5e-3, 5e-3, -2.5e-3, h, h_radial, h_band, h_ring, 1.5};
  return p;
}

int fem_mesh_actuator_swept(const FemSweptActuator *p, int order, FemMesh **out) {
  *out = NULL;
  double r_ring = p->R_out - p->ring_d;
  SA_REQUIRE(p->R_cav > 0 && p->R_cav < p->band_r_in && p->band_r_in < p->band_r_out &&
                 p->band_r_out < (p->rings ? r_ring : p->R_out) && r_ring < p->R_out,
             SA_ERR_INPUT, "swept actuator mesh: radii must increase: cavity %g < band %g..%g "
             "< rings %g < outer %g m", p->R_cav, p->band_r_in, p->band_r_out, r_ring, p->R_out);
  SA_REQUIRE(p->h > 0 && p->h_radial > 0 && p->h_band > 0 && p->h_ring > 0 && p->grade >= 1,
             SA_ERR_INPUT, "swept actuator mesh: sizes must be > 0 and grade >= 1");
  SA_REQUIRE(p->L_fix > 0 && p->L_fix < p->L_cav && p->t_cap > 0, SA_ERR_INPUT,
             "swept actuator mesh: the clamp line must lie inside the cavity's length");
  double a = 0.5 * p->band_w / (0.5 * (p->band_r_in + p->band_r_out));
  SA_REQUIRE(a > 0 && a < M_PI, SA_ERR_INPUT, "swept actuator mesh: band width %g m", p->band_w);

  Axis *ax = calloc(7, sizeof(Axis));
  SA_REQUIRE(ax, SA_ERR_MEMORY, "swept mesh axes");
  Axis *rA = ax, *rB = ax + 1, *th = ax + 2, *z = ax + 3, *zs = ax + 4, *zw = ax + 5, *zt = ax + 6;
  int rc = 0;
#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((rc = (x)) != 0) goto done;                                                                \
  } while (0)
  /* r: the wall's layers through the band and ring radii; the core in cells of h */
  rA->c[0] = p->R_cav;
  TRY(add_uniform(rA, p->R_cav, p->band_r_in, p->h_radial));
  TRY(add_uniform(rA, p->band_r_in, p->band_r_out, p->h_band));
  /* the ring corners (a stiff ring bonded to the silicone: a stress singularity that sets the
   * angle's convergence, docs/fem_time_to_accuracy.md) get cells of h_ring, graded away */
  double s_ring = fmin(p->h_ring, p->ring_h);
  if (p->rings) {
    TRY(add_graded(rA, p->band_r_out, r_ring, p->h_radial, s_ring, p->h_radial, p->grade));
    TRY(add_graded(rA, r_ring, p->R_out, s_ring, s_ring, fmax(s_ring, 0.5 * p->ring_d), p->grade));
  } else {
    TRY(add_uniform(rA, p->band_r_out, p->R_out, p->h_radial));
  }
  rB->c[0] = 0;
  TRY(add_uniform(rB, 0, p->R_cav, p->h));
  /* theta: the band's edges at pi -+ a, arcs of h at the wall's mid radius */
  double rm = 0.5 * (p->R_cav + p->R_out);
  th->c[0] = 0;
  TRY(add_uniform(th, 0, M_PI - a, p->h / rm));
  TRY(add_uniform(th, M_PI - a, M_PI + a, p->h / rm));
  TRY(add_uniform(th, M_PI + a, 2 * M_PI, p->h / rm));
  /* z, bottom up: the cap, then the wall through every ring face and the clamp line; graded
   * from the small cells at a ring face (or a corner: floor, clamp line, top) up to h */
  double zb = -p->L_cav - p->t_cap, s_edge = fmin(p->h, p->h_radial);
  z->c[0] = zb;
  TRY(add_uniform(z, zb, -p->L_cav, fmin(p->h, 0.5 * p->t_cap)));
  double zprev = -p->L_cav, sprev = s_edge;
  int nbreak = 0;
  double zk[2 * 64 + 2], sk[2 * 64 + 2];
  int is_ring[2 * 64 + 2];
  SA_REQUIRE(!p->rings || p->ring_n <= 64, SA_ERR_INPUT, "swept actuator mesh: at most 64 rings");
  /* breakpoints above the floor: ring faces (bottom ring first) and the clamp line */
  if (p->rings)
    for (int k = p->ring_n - 1; k >= 0; k--) {
      double zc = p->ring_z0 - k * p->ring_pitch;
      zk[nbreak] = zc - 0.5 * p->ring_h, sk[nbreak] = s_ring, is_ring[nbreak++] = 0;
      zk[nbreak] = zc + 0.5 * p->ring_h, sk[nbreak] = s_ring, is_ring[nbreak++] = 1;
    }
  zk[nbreak] = -p->L_fix, sk[nbreak] = s_edge, is_ring[nbreak++] = 0;
  zk[nbreak] = 0, sk[nbreak] = s_edge, is_ring[nbreak++] = 0;
  /* sort by z (the clamp line falls between two rings); a ring's inside is uniform */
  for (int i = 1; i < nbreak; i++)
    for (int j = i; j > 0 && zk[j] < zk[j - 1]; j--) {
      double t = zk[j]; zk[j] = zk[j - 1]; zk[j - 1] = t;
      t = sk[j]; sk[j] = sk[j - 1]; sk[j - 1] = t;
      int q = is_ring[j]; is_ring[j] = is_ring[j - 1]; is_ring[j - 1] = q;
    }
  for (int i = 0; i < nbreak; i++) {
    SA_REQUIRE(zk[i] > zprev + 1e-9 && zk[i] <= 1e-12, SA_ERR_INPUT, "swept actuator mesh: "
               "rings, clamp line and cavity overlap at z = %g m", zk[i]);
    if (is_ring[i]) /* inside a ring: graded from both faces */
      TRY(add_graded(z, zprev, zk[i], s_ring, s_ring, fmax(s_ring, 0.5 * p->ring_h), p->grade));
    else TRY(add_graded(z, zprev, zk[i], sprev, sk[i], p->h, p->grade));
    zprev = zk[i], sprev = sk[i];
  }
  /* the blocks */
  TRY(sub_axis(z, zb, -p->L_cav, zs));
  TRY(sub_axis(z, -p->L_cav, -p->L_fix, zw));
  TRY(sub_axis(z, -p->L_fix, 0, zt));
  {
    Polar pw = {rA, th, zw}, pt = {rA, th, zt}, pc = {rA, th, zs}, pk = {rB, th, zs};
    FemMeshBlock bl[4] = {
        {{rA->n, th->n, zw->n}, polar_map, &pw, {"cavity_wall", "outer", NULL, NULL, NULL, NULL}},
        {{rA->n, th->n, zt->n}, polar_map, &pt,
         {"cavity_wall", "fixed_end", NULL, NULL, NULL, "fixed_end"}},
        {{rA->n, th->n, zs->n}, polar_map, &pc, {NULL, "outer", NULL, NULL, "tip", NULL}},
        {{rB->n, th->n, zs->n}, polar_map, &pk, {NULL, NULL, NULL, NULL, "tip", "cavity_wall"}}};
    rc = fem_mesh_blocks(4, bl, order, 1e-9 * p->R_out, out);
  }
  if (rc) goto done;
  /* regions from the centroids */
  {
    FemMesh *m = *out;
    char(*names)[64] = realloc(m->region_names, 3 * sizeof *names);
    if (!names) {
      rc = SA_ERROR(SA_ERR_MEMORY, "region names");
      goto done;
    }
    m->region_names = names;
    strcpy(names[0], "silicone");
    strcpy(names[1], "strain_limit");
    strcpy(names[2], "reinforcement");
    m->nregions = p->rings ? 3 : 2;
    for (int e = 0; e < m->nelem; e++) {
      /* the centroid in (r, theta, z), not in x, y, z: a chord's midpoint lies inside the
       * circle, so a band cell's Cartesian centroid can fall below the band's inner radius */
      double r = 0, t = 0, c[3] = {0, 0, 0}, t0 = 0;
      for (int k = 0; k < 4; k++) {
        const double *x = m->xyz + 3 * (size_t)m->conn[(size_t)e * m->nen + k];
        double rk = hypot(x[0], x[1]), tk = atan2(x[1], x[0]);
        if (k == 0) t0 = tk;
        if (rk > 0) tk = t0 + remainder(tk - t0, 2 * M_PI); /* no jump across the seam */
        else tk = t0; /* a corner on the axis has no angle */
        r += 0.25 * rk, t += 0.25 * tk, c[2] += 0.25 * x[2];
      }
      if (t < 0) t += 2 * M_PI;
      if (t >= 2 * M_PI) t -= 2 * M_PI;
      int reg = 0;
      if (r > p->band_r_in && r < p->band_r_out && fabs(t - M_PI) < a && c[2] > -p->L_cav)
        reg = 1;
      if (p->rings && r > r_ring && c[2] > -p->L_cav) {
        double k = round((p->ring_z0 - c[2]) / p->ring_pitch);
        if (k >= 0 && k < p->ring_n &&
            fabs(c[2] - (p->ring_z0 - k * p->ring_pitch)) < 0.5 * p->ring_h)
          reg = 2;
      }
      m->region[e] = reg;
    }
    snprintf(m->source, sizeof m->source, "swept actuator mesh (h %g, radial %g, band %g, "
             "ring %g mm, grade %g)", 1e3 * p->h, 1e3 * p->h_radial, 1e3 * p->h_band,
             1e3 * p->h_ring, p->grade);
  }
done:
#undef TRY
  free(ax);
  if (rc && *out) fem_mesh_destroy(out);
  return rc;
}
