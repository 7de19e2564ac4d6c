/* dem_checks.c - is every grain inside the bore (dem_checks.h). */
#include "dem_checks.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

/* The closed surface: the wall's ntri triangles, then for each of its nedge open edges a -> b
 * three closing triangles: the edge drawn straight up to the plane z = z_cap (vertices a', b':
 * nverts + 2k, nverts + 2k + 1) and the cap's fan to its centre (vertex nverts + 2 nedge). The
 * open edge need not be flat (with [dem] rigid_band it zig-zags along the band's lower edge): a
 * fan straight from it would cut off the bore between its highest and lowest vertices. */
struct DemBore {
  int nverts, ntri, nedge;
  int *edge;   /* 2 * nedge: the open edges a -> b as the wall's triangles run them */
  int *tri;    /* 3 * (ntri + 3 nedge) */
  double r_barrel;
  double *xyz; /* 3 * (nverts + 2 nedge + 1) work copy with the closing vertices */
};

/* Triangle (a, b, c) solid angle seen from p (van Oosterom & Strackee). */
static double solid_angle(const double *a, const double *b, const double *c, const double p[3]) {
  double r1[3], r2[3], r3[3];
  for (int i = 0; i < 3; i++) r1[i] = a[i] - p[i], r2[i] = b[i] - p[i], r3[i] = c[i] - p[i];
  double l1 = sqrt(r1[0] * r1[0] + r1[1] * r1[1] + r1[2] * r1[2]);
  double l2 = sqrt(r2[0] * r2[0] + r2[1] * r2[1] + r2[2] * r2[2]);
  double l3 = sqrt(r3[0] * r3[0] + r3[1] * r3[1] + r3[2] * r3[2]);
  double det = r1[0] * (r2[1] * r3[2] - r2[2] * r3[1]) - r1[1] * (r2[0] * r3[2] - r2[2] * r3[0]) +
               r1[2] * (r2[0] * r3[1] - r2[1] * r3[0]);
  double d12 = r1[0] * r2[0] + r1[1] * r2[1] + r1[2] * r2[2];
  double d13 = r1[0] * r3[0] + r1[1] * r3[1] + r1[2] * r3[2];
  double d23 = r2[0] * r3[0] + r2[1] * r3[1] + r2[2] * r3[2];
  double den = l1 * l2 * l3 + d12 * l3 + d13 * l2 + d23 * l1;
  return 2 * atan2(det, den);
}

double dem_winding_number(const double *xyz, const int *tri, int ntri, const double p[3]) {
  double w = 0;
  for (int t = 0; t < ntri; t++)
    w += solid_angle(xyz + 3 * tri[3 * t], xyz + 3 * tri[3 * t + 1], xyz + 3 * tri[3 * t + 2], p);
  return w / (4 * M_PI);
}

static int cmp_edge(const void *a, const void *b) {
  const int *x = a, *y = b;
  if (x[0] != y[0]) return (x[0] > y[0]) - (x[0] < y[0]);
  return (x[1] > y[1]) - (x[1] < y[1]);
}

int dem_bore_create(int nverts, const int *tri, int ntri, double r_barrel, DemBore **out) {
  *out = NULL;
  /* open edges: directed edges whose reverse does not occur */
  int ne = 3 * ntri;
  int *e = malloc(sizeof(int) * 3 * (size_t)ne); /* (min, max, directed a->b as sign) */
  SA_REQUIRE(e, SA_ERR_MEMORY, "bore edges");
  for (int t = 0; t < ntri; t++)
    for (int j = 0; j < 3; j++) {
      int a = tri[3 * t + j], b = tri[3 * t + (j + 1) % 3];
      int *r = e + 3 * (3 * t + j);
      r[0] = a < b ? a : b, r[1] = a < b ? b : a, r[2] = a < b ? 1 : -1;
    }
  qsort(e, (size_t)ne, 3 * sizeof(int), cmp_edge);
  int ncap = 0;
  for (int i = 0; i < ne;) {
    int k = i;
    while (k < ne && e[3 * k] == e[3 * i] && e[3 * k + 1] == e[3 * i + 1]) k++;
    if (k - i == 1) e[3 * ncap] = e[3 * i], e[3 * ncap + 1] = e[3 * i + 1],
                    e[3 * ncap + 2] = e[3 * i + 2], ncap++;
    i = k;
  }
  DemBore *b;
  SA_CALLOC(b, 1);
  b->nverts = nverts, b->ntri = ntri, b->nedge = ncap, b->r_barrel = r_barrel;
  b->edge = malloc(sizeof(int) * 2 * (size_t)(ncap > 0 ? ncap : 1));
  b->tri = malloc(sizeof(int) * 3 * (size_t)(ntri + 3 * ncap));
  b->xyz = malloc(sizeof(double) * 3 * (size_t)(nverts + 2 * ncap + 1));
  if (!b->edge || !b->tri || !b->xyz) {
    free(e);
    dem_bore_destroy(&b);
    return SA_ERROR(SA_ERR_MEMORY, "bore");
  }
  memcpy(b->tri, tri, sizeof(int) * 3 * (size_t)ntri);
  int centre = nverts + 2 * ncap;
  for (int k = 0; k < ncap; k++) {
    /* the wall runs the open edge a -> b; the closing surface runs it b -> a, then up, across
     * the cap and down, so the closed surface is consistently oriented */
    int a = e[3 * k + 2] > 0 ? e[3 * k] : e[3 * k + 1], bb = e[3 * k + 2] > 0 ? e[3 * k + 1] : e[3 * k];
    int a_up = nverts + 2 * k, b_up = a_up + 1;
    b->edge[2 * k] = a, b->edge[2 * k + 1] = bb;
    int *c = b->tri + 3 * (ntri + 3 * k);
    c[0] = bb, c[1] = a, c[2] = a_up;
    c[3] = bb, c[4] = a_up, c[5] = b_up;
    c[6] = b_up, c[7] = a_up, c[8] = centre;
  }
  free(e);
  *out = b;
  return 0;
}

int dem_bore_count_outside(const DemBore *b, const double *xw, int n, const double *x, double tol,
                           int *first) {
  DemBore *w = (DemBore *)b; /* work copy of the vertices; not shared between threads */
  memcpy(w->xyz, xw, sizeof(double) * 3 * (size_t)b->nverts);
  /* the cap: the plane through the open edge's highest vertex (and no lower than z = 0, the
   * barrel's), centred on the edge's vertices */
  double c[3] = {0, 0, 0};
  for (int k = 0; k < b->nedge; k++) {
    const double *a = xw + 3 * b->edge[2 * k];
    c[0] += a[0] / b->nedge, c[1] += a[1] / b->nedge, c[2] = fmax(c[2], a[2]);
  }
  for (int k = 0; k < b->nedge; k++)
    for (int j = 0; j < 2; j++) {
      double *up = w->xyz + 3 * (b->nverts + 2 * k + j);
      memcpy(up, xw + 3 * b->edge[2 * k + j], sizeof(double) * 2);
      up[2] = c[2];
    }
  memcpy(w->xyz + 3 * (b->nverts + 2 * b->nedge), c, sizeof c);
  int bad = 0;
  if (first) *first = -1;
  for (int i = 0; i < n; i++) {
    const double *p = x + 3 * i;
    int out;
    if (p[2] >= c[2]) {
      out = hypot(p[0], p[1]) > b->r_barrel + tol;
    } else {
      double wn = dem_winding_number(w->xyz, b->tri, b->ntri + 3 * b->nedge, p);
      out = fabs(wn) < 0.5;
    }
    if (out) {
      if (!bad && first) *first = i;
      bad++;
    }
  }
  return bad;
}

void dem_bore_destroy(DemBore **b) {
  if (!b || !*b) return;
  free((*b)->edge);
  free((*b)->tri);
  free((*b)->xyz);
  free(*b);
  *b = NULL;
}

double dem_momentum_residual(const double F_walls[3], double W, const double dp[3], double T) {
  double r[3] = {F_walls[0] + dp[0] / T, F_walls[1] + dp[1] / T, F_walls[2] + W + dp[2] / T};
  return sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}
