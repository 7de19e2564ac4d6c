/* dem_checks.c - is every grain inside the bore (dem_checks.h). */
#include "dem_checks.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

struct DemBore {
  int nverts, ntri, ncap; /* ntri wall triangles, then ncap cap triangles */
  int *tri;               /* 3 * (ntri + ncap); cap triangles use vertex nverts (the centre) */
  double r_barrel;
  double *xyz;            /* 3 * (nverts + 1) work copy with the cap centre */
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
  b->nverts = nverts, b->ntri = ntri, b->ncap = ncap, b->r_barrel = r_barrel;
  b->tri = malloc(sizeof(int) * 3 * (size_t)(ntri + ncap));
  b->xyz = malloc(sizeof(double) * 3 * (size_t)(nverts + 1));
  if (!b->tri || !b->xyz) {
    free(e);
    dem_bore_destroy(&b);
    return SA_ERROR(SA_ERR_MEMORY, "bore");
  }
  memcpy(b->tri, tri, sizeof(int) * 3 * (size_t)ntri);
  for (int k = 0; k < ncap; k++) {
    /* the wall has the open edge as a->b; the cap uses b->a so the closed surface is
     * consistently oriented */
    int a = e[3 * k + 2] > 0 ? e[3 * k] : e[3 * k + 1], bb = e[3 * k + 2] > 0 ? e[3 * k + 1] : e[3 * k];
    int *c = b->tri + 3 * (ntri + k);
    c[0] = bb, c[1] = a, c[2] = nverts;
  }
  free(e);
  *out = b;
  return 0;
}

int dem_bore_count_outside(const DemBore *b, const double *xw, int n, const double *x, double tol,
                           int *first) {
  DemBore *w = (DemBore *)b; /* work copy of the vertices; not shared between threads */
  memcpy(w->xyz, xw, sizeof(double) * 3 * (size_t)b->nverts);
  /* cap centre: mean of the open-edge vertices */
  double c[3] = {0, 0, 0};
  for (int k = 0; k < b->ncap; k++)
    for (int d = 0; d < 3; d++) c[d] += xw[3 * b->tri[3 * (b->ntri + k)] + d] / b->ncap;
  memcpy(w->xyz + 3 * b->nverts, c, sizeof c);
  int bad = 0;
  if (first) *first = -1;
  for (int i = 0; i < n; i++) {
    const double *p = x + 3 * i;
    int out;
    if (p[2] >= c[2]) {
      out = hypot(p[0], p[1]) > b->r_barrel + tol;
    } else {
      double wn = dem_winding_number(w->xyz, b->tri, b->ntri + b->ncap, p);
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
  free((*b)->tri);
  free((*b)->xyz);
  free(*b);
  *b = NULL;
}

double dem_momentum_residual(const double F_walls[3], double W, const double dp[3], double T) {
  double r[3] = {F_walls[0] + dp[0] / T, F_walls[1] + dp[1] / T, F_walls[2] + W + dp[2] / T};
  return sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}
