/* ccx_hex.c - structured 20-node hexahedral meshes written as CalculiX C3D20R decks.
 *
 * actuator mode: the reference actuator of /work/shared/ACTUATOR.md (same parameters as
 *   meshes/actuator.geo), half model y >= 0 with the symmetry plane y = 0 (u_y = 0): the design
 *   is symmetric about the bending plane x-z. The wall is a tensor grid in (r, theta, z) whose
 *   grid lines include every material interface (band radii 7.0/7.5 mm and angle pi - a,
 *   ring radius 8.0 mm and ring faces, the clamp line z = -L_fix), so each element lies in one
 *   material. The tip cap (z = -L_cav - t_cap .. -L_cav) is an O-grid: a half square of
 *   half-width s at the centre, a transition ring blending the square's boundary into the
 *   circle r = R_cav, and the wall's annulus below the cavity floor.
 * box mode: a block [0,Lx] x [0,Ly] x [0,Lz] with rollers on x = 0, y = 0, z = 0 and pressure on
 *   z = Lz, for checking node and face orders against a uniaxial-stress solution (ccx_post).
 *
 * Every element is built independently from a mapping of its parent cube (nodes at the 27
 * lattice points minus face and body centres) and coincident nodes are merged afterwards
 * (spatial hash, tolerance 1e-10 m), so blocks need no shared numbering.
 *
 * usage: ccx_hex actuator --h H --out BASE [--hr HR (radial size, default H)] [--rings 0|1] [--kappa-ratio R] [--pressure P]
 *                [--c10 ..] [--c20 ..] [--c30 ..] [--inc0 F] [--incmin F] [--incmax F]
 *                [--etype C3D20R|C3D20] [--time-points T1,T2,... (print times, as ccx_export)]
 *        ccx_hex box --lx L --ly L --lz L --nx N --ny N --nz N --out BASE [material, step] */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ccx_inp.h"
#include "sa_error.h"

#define TOL 1e-9 /* geometric tolerance for classifying nodes [m]: far below any feature */

/* ---------------------------------------------------------------- node merging (hash grid) */
typedef struct {
  int n, cap;
  double *xyz;
  int *next;
  int64_t *keys; /* open-addressing table of cell keys */
  int *head;
  size_t tsize;
  double cell;
} Merge;

static int64_t cell_key(int64_t i, int64_t j, int64_t k)
{
  return (i & 0x1fffff) | ((j & 0x1fffff) << 21) | ((k & 0x1fffff) << 42);
}

static size_t slot(const Merge *mg, int64_t key)
{
  uint64_t h = (uint64_t)key * 0x9E3779B97F4A7C15ull;
  size_t s = (size_t)(h >> 20) & (mg->tsize - 1);
  while (mg->head[s] >= 0 && mg->keys[s] != key) s = (s + 1) & (mg->tsize - 1);
  return s;
}

static int merge_init(Merge *mg, int cap)
{
  memset(mg, 0, sizeof *mg);
  mg->cap = cap;
  mg->cell = 1e-6;
  SA_CALLOC(mg->xyz, 3 * (size_t)cap);
  SA_CALLOC(mg->next, cap);
  mg->tsize = 1;
  while (mg->tsize < 4 * (size_t)cap) mg->tsize <<= 1;
  SA_CALLOC(mg->keys, mg->tsize);
  SA_CALLOC(mg->head, mg->tsize);
  for (size_t s = 0; s < mg->tsize; ++s) mg->head[s] = -1;
  return 0;
}

static void merge_free(Merge *mg)
{
  free(mg->xyz);
  free(mg->next);
  free(mg->keys);
  free(mg->head);
}

/* Index of the node at p (new or existing within 1e-10 m). */
static int merge_add(Merge *mg, const double p[3])
{
  int64_t c[3];
  for (int q = 0; q < 3; ++q) c[q] = (int64_t)floor(p[q] / mg->cell);
  for (int di = -1; di <= 1; ++di)
    for (int dj = -1; dj <= 1; ++dj)
      for (int dk = -1; dk <= 1; ++dk) {
        size_t s = slot(mg, cell_key(c[0] + di, c[1] + dj, c[2] + dk));
        for (int v = mg->head[s]; v >= 0; v = mg->next[v]) {
          double *x = mg->xyz + 3 * (size_t)v;
          if (fabs(x[0] - p[0]) < 1e-10 && fabs(x[1] - p[1]) < 1e-10 && fabs(x[2] - p[2]) < 1e-10)
            return v;
        }
      }
  int v = mg->n++;
  memcpy(mg->xyz + 3 * (size_t)v, p, 3 * sizeof(double));
  size_t s = slot(mg, cell_key(c[0], c[1], c[2]));
  mg->keys[s] = cell_key(c[0], c[1], c[2]);
  mg->next[v] = mg->head[s];
  mg->head[s] = v;
  return v;
}

/* ------------------------------------------------------------------- element construction */
/* Parent-cube positions of the 20 C3D20 nodes (ccx_inp.h). */
static const int kHex[20][3] = {
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1},
    {-1, 1, 1},   {0, -1, -1}, {1, 0, -1}, {0, 1, -1},  {-1, 0, -1}, {0, -1, 1}, {1, 0, 1},
    {0, 1, 1},    {-1, 0, 1},  {-1, -1, 0}, {1, -1, 0}, {1, 1, 0},   {-1, 1, 0}};
/* Corner quadruples of faces F1..F6 and the 8-node faces (outward order) from ccx's ifaceq. */
static const int kFaceC[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
static const int kFace8[6][8] = {{3, 2, 1, 0, 10, 9, 8, 11},   {4, 5, 6, 7, 12, 13, 14, 15},
                                 {0, 1, 5, 4, 8, 17, 12, 16},  {1, 2, 6, 5, 9, 18, 13, 17},
                                 {2, 3, 7, 6, 10, 19, 14, 18}, {3, 0, 4, 7, 11, 16, 15, 19}};

/* A 2-D map of a block: (u, v) in block lattice units -> (x, y). */
typedef void (*Map2)(const void *ctx, double u, double v, double xy[2]);

typedef struct {
  CcxModel *m;
  Merge mg;
  int cap_elem;
} Builder;

static int add_hex(Builder *b, Map2 map, const void *ctx, int i, int j, double z0, double z1,
                   int region)
{
  SA_REQUIRE(b->m->nelem < b->cap_elem, SA_ERR_INTERNAL, "element capacity exceeded");
  int e = b->m->nelem++;
  int *c = b->m->conn + 20 * (size_t)e;
  for (int k = 0; k < 20; ++k) {
    double p[3];
    map(ctx, i + 0.5 * (kHex[k][0] + 1), j + 0.5 * (kHex[k][1] + 1), p);
    p[2] = z0 + 0.5 * (kHex[k][2] + 1) * (z1 - z0);
    c[k] = merge_add(&b->mg, p);
  }
  b->m->region[e] = region;
  return 0;
}

/* Piecewise-uniform 1-D grid through breakpoints: knots t = 0..n map to coordinates. */
typedef struct {
  int n;
  double x[4096];
} Grid1;

static int grid_build(Grid1 *g, int nb, const double *bp, double h)
{
  g->n = 0;
  g->x[0] = bp[0];
  for (int s = 0; s + 1 < nb; ++s) {
    double len = bp[s + 1] - bp[s];
    if (len <= TOL) continue;
    int k = (int)ceil(len / h - 1e-9);
    if (k < 1) k = 1;
    SA_REQUIRE(g->n + k < 4096, SA_ERR_INPUT, "grid too fine");
    for (int q = 1; q <= k; ++q) g->x[g->n + q] = bp[s] + len * q / k;
    g->n += k;
  }
  return 0;
}

/* Coordinate at lattice parameter t in [0, n] (linear within a cell). */
static double grid_at(const Grid1 *g, double t)
{
  int i = (int)floor(t);
  if (i >= g->n) i = g->n - 1;
  if (i < 0) i = 0;
  return g->x[i] + (t - i) * (g->x[i + 1] - g->x[i]);
}

/* ------------------------------------------------------------------------ actuator blocks */
typedef struct {
  double R_cav, R_out, L_cav, t_cap, L_fix, band_r_in, band_r_out, band_w;
  int rings, ring_n;
  double ring_d, ring_h, ring_pitch, ring_z0;
  double a, s; /* band half-angle, square half-width */
  int m;       /* square: m elements along x, m/2 along y; 2m angular elements on the half circle */
  Grid1 r, th, z, zc, tr;
} Act;

static void map_annulus(const void *ctx, double u, double v, double xy[2])
{
  const Act *A = ctx;
  double r = grid_at(&A->r, u), t = grid_at(&A->th, v);
  xy[0] = r * cos(t);
  xy[1] = r * sin(t);
}

/* Square boundary walked counter-clockwise from (s, 0) to (-s, 0): v in [0, 2m]. */
static void square_boundary(const Act *A, double v, double xy[2])
{
  double h = 2.0 * A->s / A->m, half = 0.5 * A->m;
  if (v <= half) xy[0] = A->s, xy[1] = v * h;
  else if (v <= half + A->m) xy[0] = A->s - (v - half) * h, xy[1] = A->s;
  else xy[0] = -A->s, xy[1] = A->s - (v - half - A->m) * h;
}

static void map_transition(const void *ctx, double u, double v, double xy[2])
{
  const Act *A = ctx;
  double sq[2], t = grid_at(&A->th, v), w = grid_at(&A->tr, u);
  square_boundary(A, v, sq);
  xy[0] = (1 - w) * sq[0] + w * A->R_cav * cos(t);
  xy[1] = (1 - w) * sq[1] + w * A->R_cav * sin(t);
}

static void map_square(const void *ctx, double u, double v, double xy[2])
{
  const Act *A = ctx;
  double h = 2.0 * A->s / A->m;
  xy[0] = -A->s + u * h;
  xy[1] = v * h;
}

static int classify(const Act *A, const double c[3])
{
  double r = hypot(c[0], c[1]), th = atan2(c[1], c[0]);
  if (c[2] > -A->L_cav && r > A->band_r_in && r < A->band_r_out && th > M_PI - A->a) return 1;
  if (A->rings && r > A->R_out - A->ring_d)
    for (int k = 0; k < A->ring_n; ++k) {
      double zc = A->ring_z0 - k * A->ring_pitch;
      if (fabs(c[2] - zc) < 0.5 * A->ring_h) return 2;
    }
  return 0;
}

static int sort_unique(double *v, int n)
{
  for (int i = 1; i < n; ++i)
    for (int j = i; j > 0 && v[j] < v[j - 1]; --j) {
      double t = v[j];
      v[j] = v[j - 1];
      v[j - 1] = t;
    }
  int k = 0;
  for (int i = 0; i < n; ++i)
    if (!k || v[i] - v[k - 1] > TOL) v[k++] = v[i];
  return k;
}

static int build_actuator(Act *A, double h, double hr, CcxModel *m)
{
  A->a = 0.5 * A->band_w / (0.5 * (A->band_r_in + A->band_r_out));
  /* radial grid */
  double rb[6] = {A->R_cav, A->band_r_in, A->band_r_out, A->R_out - A->ring_d, A->R_out};
  int nrb = sort_unique(rb, 5);
  SA_CHECK(grid_build(&A->r, nrb, rb, hr));
  /* angular grid: [0, pi - a] and [pi - a, pi] at the band's mid radius, 2m cells, m even */
  double rm = 0.5 * (A->band_r_in + A->band_r_out);
  int n2 = (int)ceil(A->a * rm / h - 1e-9), n1 = (int)ceil((M_PI - A->a) * rm / h - 1e-9);
  if (n2 < 2) n2 = 2;
  while ((n1 + n2) % 4) n1++;
  A->m = (n1 + n2) / 2;
  A->th.n = n1 + n2;
  for (int q = 0; q <= n1; ++q) A->th.x[q] = (M_PI - A->a) * q / n1;
  for (int q = 1; q <= n2; ++q) A->th.x[n1 + q] = M_PI - A->a + A->a * q / n2;
  /* square and transition ring: square cells 2s/m close to the arc cells at R_cav */
  A->s = 0.5 * A->R_cav;
  double tb[2] = {0.0, 1.0};
  double lt = A->R_cav - 1.2 * A->s;
  SA_CHECK(grid_build(&A->tr, 2, tb, h / lt));
  /* axial grids: tube (breakpoints at the cavity floor, ring faces, clamp line, top) and cap */
  double zb[64];
  int nzb = 0;
  zb[nzb++] = -A->L_cav;
  zb[nzb++] = -A->L_fix;
  zb[nzb++] = 0.0;
  if (A->rings)
    for (int k = 0; k < A->ring_n && nzb + 2 < 64; ++k) {
      double zc = A->ring_z0 - k * A->ring_pitch;
      if (zc + 0.5 * A->ring_h < 0 && zc - 0.5 * A->ring_h > -A->L_cav) {
        zb[nzb++] = zc - 0.5 * A->ring_h;
        zb[nzb++] = zc + 0.5 * A->ring_h;
      }
    }
  nzb = sort_unique(zb, nzb);
  SA_CHECK(grid_build(&A->z, nzb, zb, h));
  double cb[2] = {-A->L_cav - A->t_cap, -A->L_cav};
  SA_CHECK(grid_build(&A->zc, 2, cb, h));

  int nr = A->r.n, nt = A->th.n, ntr = A->tr.n, mm = A->m;
  int n2d_tube = nr * nt, n2d_cap = n2d_tube + ntr * nt + mm * (mm / 2);
  int cap_elem = n2d_tube * A->z.n + n2d_cap * A->zc.n;
  Builder b = {.m = m, .cap_elem = cap_elem};
  SA_CHECK(merge_init(&b.mg, 20 * cap_elem));
  m->etype = m->etype ? m->etype : "C3D20R";
  m->nen = 20;
  SA_CALLOC(m->conn, 20 * (size_t)cap_elem);
  SA_CALLOC(m->region, cap_elem);
  /* region index: classify() returns 0 silicone, 1 band, 2 ring */
  for (int iz = 0; iz < A->zc.n; ++iz) {
    double z0 = A->zc.x[iz], z1 = A->zc.x[iz + 1];
    for (int i = 0; i < mm; ++i)
      for (int j = 0; j < mm / 2; ++j) SA_CHECK(add_hex(&b, map_square, A, i, j, z0, z1, 0));
    for (int i = 0; i < ntr; ++i)
      for (int j = 0; j < nt; ++j) SA_CHECK(add_hex(&b, map_transition, A, i, j, z0, z1, 0));
    for (int i = 0; i < nr; ++i)
      for (int j = 0; j < nt; ++j) SA_CHECK(add_hex(&b, map_annulus, A, i, j, z0, z1, 0));
  }
  for (int iz = 0; iz < A->z.n; ++iz)
    for (int i = 0; i < nr; ++i)
      for (int j = 0; j < nt; ++j)
        SA_CHECK(add_hex(&b, map_annulus, A, i, j, A->z.x[iz], A->z.x[iz + 1], 0));
  m->nnodes = b.mg.n;
  SA_CALLOC(m->xyz, 3 * (size_t)m->nnodes);
  memcpy(m->xyz, b.mg.xyz, 3 * (size_t)m->nnodes * sizeof(double));
  merge_free(&b.mg);
  return 0;
}

/* Orientation, regions, BCs, load faces, tip of the actuator model. */
static int finish_actuator(const Act *A, CcxModel *m)
{
  m->nregions = 2 + (A->rings ? 1 : 0);
  snprintf(m->regions[0].name, 64, "silicone");
  snprintf(m->regions[1].name, 64, "strain_limit");
  m->regions[1].stiff = 1, m->regions[1].E = 1000e6, m->regions[1].nu = 0.3;
  if (A->rings) {
    snprintf(m->regions[2].name, 64, "reinforcement");
    m->regions[2].stiff = 1, m->regions[2].E = 2000e6, m->regions[2].nu = 0.3;
  }
  double L_tot = A->L_cav + A->t_cap;
  int *list;
  SA_CALLOC(list, m->nnodes);
  SA_CALLOC(m->load_elem, 2 * (size_t)m->nelem);
  SA_CALLOC(m->load_face, 2 * (size_t)m->nelem);
  SA_CALLOC(m->tip_tri, 3 * 6 * (size_t)m->nelem);
  for (int e = 0; e < m->nelem; ++e) {
    const int *c = m->conn + 20 * (size_t)e;
    const double *X[8];
    double cen[3] = {0, 0, 0};
    for (int k = 0; k < 8; ++k) {
      X[k] = m->xyz + 3 * (size_t)c[k];
      for (int q = 0; q < 3; ++q) cen[q] += 0.125 * X[k][q];
    }
    SA_REQUIRE(ccx_tet_volume(X[0], X[1], X[3], X[4]) > 0, SA_ERR_INTERNAL,
               "hex %d is not right-handed", e);
    m->region[e] = classify(A, cen);
    for (int f = 0; f < 6; ++f) {
      int cav = 1, floor_ = 1, tip = 1;
      for (int k = 0; k < 4; ++k) {
        const double *x = X[kFaceC[f][k]];
        double r = hypot(x[0], x[1]);
        cav &= fabs(r - A->R_cav) < TOL && x[2] > -A->L_cav - TOL;
        floor_ &= fabs(x[2] + A->L_cav) < TOL && r < A->R_cav + TOL;
        tip &= fabs(x[2] + L_tot) < TOL;
      }
      if (cav || floor_) {
        m->load_elem[m->nload] = e;
        m->load_face[m->nload++] = f + 1;
      }
      if (tip) {
        static const int sub[6][3] = {{0, 4, 7}, {4, 1, 5}, {5, 2, 6}, {6, 3, 7}, {4, 5, 6}, {4, 6, 7}};
        for (int t = 0; t < 6; ++t, m->ntip_tri++)
          for (int k = 0; k < 3; ++k) m->tip_tri[3 * m->ntip_tri + k] = c[kFace8[f][sub[t][k]]];
      }
    }
  }
  int n = 0;
  for (int v = 0; v < m->nnodes; ++v) {
    const double *x = m->xyz + 3 * (size_t)v;
    if ((fabs(hypot(x[0], x[1]) - A->R_out) < TOL && x[2] > -A->L_fix - TOL) || fabs(x[2]) < TOL)
      list[n++] = v;
  }
  SA_CHECK(ccx_model_add_bc(m, "FIX", 1, 3, n, list));
  n = 0;
  for (int v = 0; v < m->nnodes; ++v)
    if (fabs(m->xyz[3 * (size_t)v + 1]) < TOL) list[n++] = v;
  SA_CHECK(ccx_model_add_bc(m, "SYM", 2, 2, n, list));
  n = 0;
  for (int v = 0; v < m->nnodes; ++v)
    if (fabs(m->xyz[3 * (size_t)v + 2] + L_tot) < TOL) list[n++] = v;
  m->ntip_nodes = n;
  SA_CALLOC(m->tip_nodes, n);
  memcpy(m->tip_nodes, list, (size_t)n * sizeof(int));
  free(list);
  return 0;
}

/* ----------------------------------------------------------------------------------- box */
typedef struct {
  double dx, dy;
} Box;

static void map_box(const void *ctx, double u, double v, double xy[2])
{
  const Box *B = ctx;
  xy[0] = u * B->dx;
  xy[1] = v * B->dy;
}

static int build_box(double L[3], int N[3], CcxModel *m)
{
  Box B = {L[0] / N[0], L[1] / N[1]};
  int cap_elem = N[0] * N[1] * N[2];
  Builder b = {.m = m, .cap_elem = cap_elem};
  SA_CHECK(merge_init(&b.mg, 20 * cap_elem));
  m->etype = m->etype ? m->etype : "C3D20R";
  m->nen = 20;
  SA_CALLOC(m->conn, 20 * (size_t)cap_elem);
  SA_CALLOC(m->region, cap_elem);
  for (int k = 0; k < N[2]; ++k)
    for (int i = 0; i < N[0]; ++i)
      for (int j = 0; j < N[1]; ++j)
        SA_CHECK(add_hex(&b, map_box, &B, i, j, L[2] * k / N[2], L[2] * (k + 1) / N[2], 0));
  m->nnodes = b.mg.n;
  SA_CALLOC(m->xyz, 3 * (size_t)m->nnodes);
  memcpy(m->xyz, b.mg.xyz, 3 * (size_t)m->nnodes * sizeof(double));
  merge_free(&b.mg);
  m->nregions = 1;
  snprintf(m->regions[0].name, 64, "silicone");
  int *list;
  SA_CALLOC(list, m->nnodes);
  for (int d = 0; d < 3; ++d) {
    int n = 0;
    for (int v = 0; v < m->nnodes; ++v)
      if (fabs(m->xyz[3 * (size_t)v + d]) < TOL) list[n++] = v;
    char name[16];
    snprintf(name, sizeof name, "ROLLER%d", d);
    SA_CHECK(ccx_model_add_bc(m, name, d + 1, d + 1, n, list));
  }
  int n = 0;
  for (int v = 0; v < m->nnodes; ++v)
    if (fabs(m->xyz[3 * (size_t)v + 2] - L[2]) < TOL) list[n++] = v;
  m->ntip_nodes = n;
  SA_CALLOC(m->tip_nodes, n);
  memcpy(m->tip_nodes, list, (size_t)n * sizeof(int));
  free(list);
  SA_CALLOC(m->load_elem, m->nelem);
  SA_CALLOC(m->load_face, m->nelem);
  SA_CALLOC(m->tip_tri, 3 * 6 * (size_t)m->nelem);
  for (int e = 0; e < m->nelem; ++e) {
    const int *c = m->conn + 20 * (size_t)e;
    for (int f = 0; f < 6; ++f) {
      int top = 1;
      for (int k = 0; k < 4; ++k) top &= fabs(m->xyz[3 * (size_t)c[kFaceC[f][k]] + 2] - L[2]) < TOL;
      if (!top) continue;
      m->load_elem[m->nload] = e;
      m->load_face[m->nload++] = f + 1;
      static const int sub[6][3] = {{0, 4, 7}, {4, 1, 5}, {5, 2, 6}, {6, 3, 7}, {4, 5, 6}, {4, 6, 7}};
      for (int t = 0; t < 6; ++t, m->ntip_tri++)
        for (int q = 0; q < 3; ++q) m->tip_tri[3 * m->ntip_tri + q] = c[kFace8[f][sub[t][q]]];
    }
  }
  return 0;
}

/* ---------------------------------------------------------------------------------- main */
static int run(int argc, char **argv)
{
  SA_REQUIRE(argc >= 2, SA_ERR_INPUT, "usage: ccx_hex actuator|box [options] (see ccx_hex.c)");
  int box = !strcmp(argv[1], "box");
  SA_REQUIRE(box || !strcmp(argv[1], "actuator"), SA_ERR_INPUT, "mode must be actuator or box");
  Act A = {.R_cav = 6e-3, .R_out = 8.5e-3, .L_cav = 80e-3, .t_cap = 4e-3, .L_fix = 5e-3,
           .band_r_in = 7e-3, .band_r_out = 7.5e-3, .band_w = 10e-3, .rings = 1, .ring_n = 16,
           .ring_d = 0.5e-3, .ring_h = 0.5e-3, .ring_pitch = 5e-3, .ring_z0 = -2.5e-3};
  double h = 0, hr = 0, L[3] = {1, 1, 1}, kratio = 500, kappa = 0;
  int N[3] = {2, 2, 2};
  const char *out = NULL;
  CcxModel m;
  memset(&m, 0, sizeof m);
  m.c10 = 0.11e6, m.c20 = 0.02e6, m.pressure = 10e3;
  m.inc0 = 0.02, m.incmin = 1e-5, m.incmax = 0.05;
  for (int i = 2; i < argc; ++i) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
#define OPT(name) (!strcmp(a, name) && v && ++i)
    if (OPT("--h")) h = atof(v);
    else if (OPT("--hr")) hr = atof(v);
    else if (OPT("--out")) out = v;
    else if (OPT("--rings")) A.rings = atoi(v);
    else if (OPT("--kappa-ratio")) kratio = atof(v);
    else if (OPT("--kappa")) kappa = atof(v);
    else if (OPT("--c10")) m.c10 = atof(v);
    else if (OPT("--c20")) m.c20 = atof(v);
    else if (OPT("--c30")) m.c30 = atof(v);
    else if (OPT("--pressure")) m.pressure = atof(v);
    else if (OPT("--inc0")) m.inc0 = atof(v);
    else if (OPT("--incmin")) m.incmin = atof(v);
    else if (OPT("--incmax")) m.incmax = atof(v);
    else if (OPT("--etype")) m.etype = v;
    else if (OPT("--lx")) L[0] = atof(v);
    else if (OPT("--ly")) L[1] = atof(v);
    else if (OPT("--lz")) L[2] = atof(v);
    else if (OPT("--nx")) N[0] = atoi(v);
    else if (OPT("--ny")) N[1] = atoi(v);
    else if (OPT("--nz")) N[2] = atoi(v);
    else if (!strcmp(a, "--print-all")) m.print_all = 1;
    else if (OPT("--time-points")) SA_CHECK(ccx_model_set_time_points(&m, v));
    else return SA_ERROR(SA_ERR_INPUT, "unknown or incomplete option %s", a);
#undef OPT
  }
  SA_REQUIRE(out, SA_ERR_INPUT, "need --out");
  m.kappa = kappa > 0 ? kappa : kratio * 2.0 * m.c10;
  if (box) {
    SA_CHECK(build_box(L, N, &m));
  } else {
    SA_REQUIRE(h > 0, SA_ERR_INPUT, "need --h");
    SA_CHECK(build_actuator(&A, h, hr > 0 ? hr : h, &m));
    SA_CHECK(finish_actuator(&A, &m));
  }
  SA_CHECK(ccx_model_write(&m, out));
  int nreg[CCX_MAX_REGIONS] = {0};
  for (int e = 0; e < m.nelem; ++e) nreg[m.region[e]]++;
  printf("ccx_hex: %s.inp: %d nodes (%d dof), %d %s (", out, m.nnodes, 3 * m.nnodes, m.nelem,
         m.etype);
  for (int r = 0; r < m.nregions; ++r) printf("%s%s %d", r ? ", " : "", m.regions[r].name, nreg[r]);
  printf("), %d pressure faces, %d tip triangles, kappa %.6g Pa\n", m.nload, m.ntip_tri, m.kappa);
  ccx_model_free(&m);
  return 0;
}

int main(int argc, char **argv)
{
  int rc = run(argc, argv);
  if (rc) sa_error_print();
  return sa_error_exit_status(rc);
}
