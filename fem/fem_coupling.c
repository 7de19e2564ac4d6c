/* fem_coupling.c - coupling surface: FEM boundary nodes <-> flat wall triangles (fem_coupling.h
 * states the geometry and force maps). */
#include "fem_coupling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

struct FemCouplingSurface {
  const FemMesh *m;
  int nverts, ntri;
  int *nodes; /* nverts global node numbers */
  int *tri;   /* 3 * ntri local vertex indices */
  double *x_mark; /* 3 * nverts */
};

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* Face f of S lies below z_max when every one of its nodes does (reference coordinates). */
static int face_below(const FemMesh *m, const FemSurface *S, int f, double z_max) {
  const int *fn = S->faces + (size_t)S->nfn * f;
  for (int j = 0; j < S->nfn; j++)
    if (m->xyz[3 * fn[j] + 2] >= z_max) return 0;
  return 1;
}

int fem_coupling_surface_create(const FemMesh *m, int nsurf, const char *const *surfaces,
                                FemCouplingSurface **out) {
  return fem_coupling_surface_create_below(m, nsurf, surfaces, INFINITY, out);
}

int fem_coupling_surface_create_below(const FemMesh *m, int nsurf, const char *const *surfaces,
                                      double z_max, FemCouplingSurface **out) {
  *out = NULL;
  SA_REQUIRE(nsurf > 0, SA_ERR_INPUT, "coupling surface: no surface named");
  int nfaces = 0, nn = 0;
  for (int s = 0; s < nsurf; s++) {
    const FemSurface *S = fem_mesh_find_surface(m, surfaces[s]);
    SA_REQUIRE(S && S->nfaces > 0, SA_ERR_INPUT,
               "coupling surface: mesh %s has no surface '%s' (or it is empty)",
               m->source[0] ? m->source : "(built)", surfaces[s]);
    SA_REQUIRE(S->nfn == 3 || S->nfn == 6, SA_ERR_INPUT, "surface '%s': %d nodes per face",
               surfaces[s], S->nfn);
    for (int f = 0; f < S->nfaces; f++)
      if (face_below(m, S, f, z_max)) nfaces += S->nfn == 6 ? 4 : 1, nn += S->nfn;
  }
  SA_REQUIRE(nfaces > 0, SA_ERR_INPUT, "coupling surface: no face of '%s' lies below z = %g m",
             surfaces[0], z_max);
  FemCouplingSurface *c;
  SA_CALLOC(c, 1);
  c->m = m;
  int *all = malloc(sizeof(int) * (size_t)nn);
  int *g2l = malloc(sizeof(int) * (size_t)m->nnodes);
  c->tri = malloc(sizeof(int) * 3 * (size_t)nfaces);
  if (!all || !g2l || !c->tri) {
    free(all);
    free(g2l);
    fem_coupling_surface_destroy(&c);
    return SA_ERROR(SA_ERR_MEMORY, "coupling surface");
  }
  int k = 0;
  for (int s = 0; s < nsurf; s++) {
    const FemSurface *S = fem_mesh_find_surface(m, surfaces[s]);
    for (int f = 0; f < S->nfaces; f++)
      if (face_below(m, S, f, z_max))
        for (int j = 0; j < S->nfn; j++) all[k++] = S->faces[(size_t)S->nfn * f + j];
  }
  qsort(all, (size_t)nn, sizeof(int), cmp_int);
  int nu = 0;
  for (int i = 0; i < nn; i++)
    if (!nu || all[i] != all[nu - 1]) all[nu++] = all[i];
  c->nverts = nu;
  c->nodes = realloc(all, sizeof(int) * (size_t)nu);
  c->x_mark = calloc(3 * (size_t)nu, sizeof(double));
  if (!c->nodes || !c->x_mark) {
    if (!c->nodes) free(all);
    free(g2l);
    fem_coupling_surface_destroy(&c);
    return SA_ERROR(SA_ERR_MEMORY, "coupling surface");
  }
  for (int i = 0; i < nu; i++) g2l[c->nodes[i]] = i;
  static const int split6[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
  int t = 0;
  for (int s = 0; s < nsurf; s++) {
    const FemSurface *S = fem_mesh_find_surface(m, surfaces[s]);
    for (int f = 0; f < S->nfaces; f++) {
      if (!face_below(m, S, f, z_max)) continue;
      const int *fn = S->faces + (size_t)S->nfn * f;
      if (S->nfn == 3) {
        for (int j = 0; j < 3; j++) c->tri[3 * t + j] = g2l[fn[j]];
        t++;
      } else {
        for (int q = 0; q < 4; q++, t++)
          for (int j = 0; j < 3; j++) c->tri[3 * t + j] = g2l[fn[split6[q][j]]];
      }
    }
  }
  c->ntri = t;
  free(g2l);
  for (int i = 0; i < nu; i++)
    for (int d = 0; d < 3; d++) c->x_mark[3 * i + d] = m->xyz[3 * c->nodes[i] + d];
  *out = c;
  return 0;
}

int fem_coupling_surface_nverts(const FemCouplingSurface *c) { return c->nverts; }
int fem_coupling_surface_ntri(const FemCouplingSurface *c) { return c->ntri; }
const int *fem_coupling_surface_triangles(const FemCouplingSurface *c) { return c->tri; }
const int *fem_coupling_surface_nodes(const FemCouplingSurface *c) { return c->nodes; }

void fem_coupling_surface_gather(const FemCouplingSurface *c, const double *x_fem, double *xw) {
  for (int i = 0; i < c->nverts; i++)
    for (int d = 0; d < 3; d++) xw[3 * i + d] = x_fem[3 * c->nodes[i] + d];
}

void fem_coupling_surface_mark(FemCouplingSurface *c, const double *x_fem) {
  fem_coupling_surface_gather(c, x_fem, c->x_mark);
}

void fem_coupling_surface_velocities(const FemCouplingSurface *c, const double *x_fem, double dt,
                                     double *vw) {
  for (int i = 0; i < c->nverts; i++)
    for (int d = 0; d < 3; d++)
      vw[3 * i + d] = dt > 0 ? (x_fem[3 * c->nodes[i] + d] - c->x_mark[3 * i + d]) / dt : 0.0;
}

void fem_coupling_surface_scatter(const FemCouplingSurface *c, const double *f_tri,
                                  double *f_node) {
  memset(f_node, 0, sizeof(double) * 3 * (size_t)c->nverts);
  for (int t = 0; t < c->ntri; t++)
    for (int j = 0; j < 3; j++)
      for (int d = 0; d < 3; d++) f_node[3 * c->tri[3 * t + j] + d] += f_tri[3 * t + d] / 3.0;
}

double fem_coupling_surface_tri_area(const FemCouplingSurface *c, const double *xw, int t,
                                     double n[3]) {
  const double *a = xw + 3 * c->tri[3 * t], *b = xw + 3 * c->tri[3 * t + 1],
               *d = xw + 3 * c->tri[3 * t + 2];
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  double cr[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  double len = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
  if (n)
    for (int i = 0; i < 3; i++) n[i] = len > 0 ? cr[i] / len : 0.0;
  return 0.5 * len;
}

void fem_coupling_surface_destroy(FemCouplingSurface **c) {
  if (!c || !*c) return;
  free((*c)->nodes);
  free((*c)->tri);
  free((*c)->x_mark);
  free(*c);
  *c = NULL;
}
