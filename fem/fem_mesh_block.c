/* fem_mesh_block.c - structured tetrahedral meshes without Gmsh (fem_mesh_blocks, fem_mesh.h):
 * mapped hexahedral blocks, each cell split into 6 tetrahedra (Kuhn split along the cell's main
 * diagonal: conforming between cells, and between blocks whose shared index directions agree),
 * tet4 or tet10 with mid-nodes placed by the mapping; coincident nodes of different blocks are
 * merged; named block sides become surfaces (outward faces); a map that collapses a side to
 * a line (r = 0 of a polar block) gives wedge cells, whose flat tets are dropped. Used by the
 * verification scenes (triaxial, footing), the swept actuator (fem_mesh_swept.c) and the
 * solver tests (tests/fem/solver/smesh.h). */
#include "fem_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

typedef struct {
  double x[3];
  int id;
} NodeKey;

static double g_tol;

static int cmp_key(const void *a, const void *b) {
  const NodeKey *p = a, *q = b;
  for (int k = 0; k < 3; k++) {
    double d = p->x[k] - q->x[k];
    if (d < -g_tol) return -1;
    if (d > g_tol) return 1;
  }
  return 0;
}

static int cmp_int(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* Kuhn split: 6 tets, vertex i of tet = sum of the first i unit steps of permutation. */
static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

typedef struct {
  char name[64];
  int nfaces, cap;
  int *faces, *elem;
} SurfAcc;

/* After a collapsed side: the edge from the axis to a grid point is a radial line in one cell
 * and a diagonal of the parameter square in its neighbour, and the map puts the two mid-nodes
 * at different points. Give every edge (pair of corners) one mid-node, on the straight line
 * where two disagreed (the radial line), and drop the nodes no element uses any more. */
typedef struct {
  int a, b, mid;
} EdgeRec;

static int cmp_edge(const void *p, const void *q) {
  const EdgeRec *x = p, *y = q;
  if (x->a != y->a) return x->a < y->a ? -1 : 1;
  if (x->b != y->b) return x->b < y->b ? -1 : 1;
  return (x->mid > y->mid) - (x->mid < y->mid);
}

static int unify_mid_nodes(FemMesh *m) {
  static const int ed[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  long n = 6L * m->nelem;
  EdgeRec *r;
  int *canon, *newid;
  SA_CALLOC(r, n > 0 ? n : 1);
  SA_CALLOC(canon, m->nnodes);
  SA_CALLOC(newid, m->nnodes);
  for (int i = 0; i < m->nnodes; i++) canon[i] = i;
  for (long e = 0; e < m->nelem; e++)
    for (int q = 0; q < 6; q++) {
      int a = m->conn[10 * e + ed[q][0]], b = m->conn[10 * e + ed[q][1]];
      EdgeRec *x = r + 6 * e + q;
      x->a = a < b ? a : b, x->b = a < b ? b : a, x->mid = m->conn[10 * e + 4 + q];
    }
  qsort(r, (size_t)n, sizeof *r, cmp_edge);
  for (long i = 0; i < n;) {
    long j = i;
    while (j < n && r[j].a == r[i].a && r[j].b == r[i].b) j++;
    if (r[j - 1].mid != r[i].mid) {
      for (long k = i; k < j; k++) canon[r[k].mid] = r[i].mid;
      for (int c = 0; c < 3; c++)
        m->xyz[3 * (long)r[i].mid + c] =
            0.5 * (m->xyz[3 * (long)r[i].a + c] + m->xyz[3 * (long)r[i].b + c]);
    }
    i = j;
  }
  free(r);
  for (long i = 0; i < 10L * m->nelem; i++) m->conn[i] = canon[m->conn[i]];
  for (int s = 0; s < m->nsurfaces; s++)
    for (long i = 0; i < 6L * m->surfaces[s].nfaces; i++)
      m->surfaces[s].faces[i] = canon[m->surfaces[s].faces[i]];
  /* compact */
  for (int i = 0; i < m->nnodes; i++) newid[i] = -1;
  for (long i = 0; i < 10L * m->nelem; i++) newid[m->conn[i]] = 0;
  int nn = 0;
  for (int i = 0; i < m->nnodes; i++)
    if (newid[i] == 0) {
      newid[i] = nn;
      memmove(m->xyz + 3 * (long)nn, m->xyz + 3 * (long)i, 3 * sizeof(double));
      nn++;
    }
  m->nnodes = nn;
  for (long i = 0; i < 10L * m->nelem; i++) m->conn[i] = newid[m->conn[i]];
  for (int s = 0; s < m->nsurfaces; s++) {
    FemSurface *S = &m->surfaces[s];
    for (long i = 0; i < 6L * S->nfaces; i++) S->faces[i] = newid[S->faces[i]];
    int *tmp = realloc(S->nodes, sizeof(int) * (6 * (size_t)S->nfaces + 1));
    SA_REQUIRE(tmp, SA_ERR_MEMORY, "surface nodes");
    memcpy(tmp, S->faces, sizeof(int) * 6 * (size_t)S->nfaces);
    qsort(tmp, 6 * (size_t)S->nfaces, sizeof(int), cmp_int);
    int k = 0;
    for (long i = 0; i < 6L * S->nfaces; i++)
      if (i == 0 || tmp[i] != tmp[i - 1]) tmp[k++] = tmp[i];
    S->nodes = tmp, S->nnodes = k;
  }
  free(canon);
  free(newid);
  return 0;
}

int fem_mesh_blocks(int nblocks, const FemMeshBlock *blocks, int order, double merge_tol,
                FemMesh **out) {
  *out = NULL;
  SA_REQUIRE(order == 1 || order == 2, SA_ERR_INPUT, "order %d", order);
  int nen = order == 1 ? 4 : 10, nfn = order == 1 ? 3 : 6;
  /* count */
  long nn = 0, ne = 0;
  for (int b = 0; b < nblocks; b++) {
    const int *n = blocks[b].n;
    nn += (long)(order * n[0] + 1) * (order * n[1] + 1) * (order * n[2] + 1);
    ne += 6L * n[0] * n[1] * n[2];
  }
  double *xyz;
  int *conn, *used;
  SA_CALLOC(xyz, 3 * nn);
  SA_CALLOC(conn, nen * ne);
  SA_CALLOC(used, nn);
  SurfAcc surf[32];
  int nsurf = 0;
  long node0 = 0, e = 0, ndropped = 0;
  for (int b = 0; b < nblocks; b++) {
    const FemMeshBlock *B = &blocks[b];
    int F[3] = {order * B->n[0] + 1, order * B->n[1] + 1, order * B->n[2] + 1};
#define NID(i, j, k) (node0 + ((long)(k) * F[1] + (j)) * F[0] + (i))
    for (int k = 0; k < F[2]; k++)
      for (int j = 0; j < F[1]; j++)
        for (int i = 0; i < F[0]; i++) {
          double xi[3] = {(double)i / (F[0] - 1), (double)j / (F[1] - 1), (double)k / (F[2] - 1)};
          B->map(xi, B->ctx, xyz + 3 * NID(i, j, k));
        }
    for (int ck = 0; ck < B->n[2]; ck++)
      for (int cj = 0; cj < B->n[1]; cj++)
        for (int ci = 0; ci < B->n[0]; ci++)
          for (int t = 0; t < 6; t++) {
            int v[4][3];
            v[0][0] = order * ci, v[0][1] = order * cj, v[0][2] = order * ck;
            for (int s = 1; s < 4; s++) {
              memcpy(v[s], v[s - 1], sizeof v[s]);
              v[s][perms[t][s - 1]] += order;
            }
            /* orientation */
            long c[4];
            for (int s = 0; s < 4; s++) c[s] = NID(v[s][0], v[s][1], v[s][2]);
            double a[3], bb[3], d[3];
            for (int q = 0; q < 3; q++) {
              a[q] = xyz[3 * c[1] + q] - xyz[3 * c[0] + q];
              bb[q] = xyz[3 * c[2] + q] - xyz[3 * c[0] + q];
              d[q] = xyz[3 * c[3] + q] - xyz[3 * c[0] + q];
            }
            double vol = a[0] * (bb[1] * d[2] - bb[2] * d[1]) - a[1] * (bb[0] * d[2] - bb[2] * d[0]) +
                         a[2] * (bb[0] * d[1] - bb[1] * d[0]);
            /* a map that collapses a side (the axis of a polar block) leaves cells with
             * coincident corners: their flat tets are dropped, the rest form wedges */
            double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]),
                   lb = sqrt(bb[0] * bb[0] + bb[1] * bb[1] + bb[2] * bb[2]),
                   ld = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (fabs(vol) <= 1e-9 * la * lb * ld) {
              ndropped++;
              continue;
            }
            if (vol < 0) {
              int tmp[3];
              memcpy(tmp, v[1], sizeof tmp);
              memcpy(v[1], v[2], sizeof tmp);
              memcpy(v[2], tmp, sizeof tmp);
            }
            int *ce = conn + e * nen;
            for (int s = 0; s < 4; s++) ce[s] = (int)NID(v[s][0], v[s][1], v[s][2]);
            if (order == 2) {
              static const int ed[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
              for (int q = 0; q < 6; q++) {
                int *p0 = v[ed[q][0]], *p1 = v[ed[q][1]];
                ce[4 + q] = (int)NID((p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2, (p0[2] + p1[2]) / 2);
              }
            }
            for (int s = 0; s < nen; s++) used[ce[s]] = 1;
            /* boundary faces: opposite corner o, face corners the others */
            for (int o = 0; o < 4; o++) {
              int fc[3], m = 0;
              for (int s = 0; s < 4; s++)
                if (s != o) fc[m++] = s;
              for (int side = 0; side < 6; side++) {
                if (!B->side[side]) continue;
                int ax = side / 2, val = (side % 2) ? F[ax] - 1 : 0, on = 1;
                for (int q = 0; q < 3; q++) on &= v[fc[q]][ax] == val;
                if (!on) continue;
                /* outward: (b-a)x(c-a).(d-a) < 0 */
                const double *pa = xyz + 3 * (long)ce[fc[0]], *pb = xyz + 3 * (long)ce[fc[1]],
                             *pc = xyz + 3 * (long)ce[fc[2]], *pd = xyz + 3 * (long)ce[o];
                double u[3], w[3], r[3];
                for (int q = 0; q < 3; q++) {
                  u[q] = pb[q] - pa[q];
                  w[q] = pc[q] - pa[q];
                  r[q] = pd[q] - pa[q];
                }
                double tp = (u[1] * w[2] - u[2] * w[1]) * r[0] + (u[2] * w[0] - u[0] * w[2]) * r[1] +
                            (u[0] * w[1] - u[1] * w[0]) * r[2];
                if (tp > 0) {
                  int tmp = fc[1];
                  fc[1] = fc[2];
                  fc[2] = tmp;
                }
                int fn[6];
                for (int q = 0; q < 3; q++) fn[q] = ce[fc[q]];
                if (order == 2) {
                  for (int q = 0; q < 3; q++) {
                    int *p0 = v[fc[q]], *p1 = v[fc[(q + 1) % 3]];
                    fn[3 + q] = (int)NID((p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2,
                                         (p0[2] + p1[2]) / 2);
                  }
                }
                int si = -1;
                for (int q = 0; q < nsurf; q++)
                  if (!strcmp(surf[q].name, B->side[side])) si = q;
                if (si < 0) {
                  si = nsurf++;
                  memset(&surf[si], 0, sizeof surf[si]);
                  snprintf(surf[si].name, sizeof surf[si].name, "%s", B->side[side]);
                }
                SurfAcc *S = &surf[si];
                if (S->nfaces == S->cap) {
                  S->cap = S->cap ? 2 * S->cap : 64;
                  S->faces = realloc(S->faces, (size_t)S->cap * nfn * sizeof(int));
                  S->elem = realloc(S->elem, (size_t)S->cap * sizeof(int));
                }
                memcpy(S->faces + (size_t)S->nfaces * nfn, fn, nfn * sizeof(int));
                S->elem[S->nfaces++] = (int)e;
              }
            }
            e++;
          }
    node0 += (long)F[0] * F[1] * F[2];
#undef NID
  }
  /* merge coincident nodes, drop unused ones */
  NodeKey *keys;
  SA_CALLOC(keys, nn);
  long nk = 0;
  for (long i = 0; i < nn; i++)
    if (used[i]) {
      memcpy(keys[nk].x, xyz + 3 * i, 3 * sizeof(double));
      keys[nk++].id = (int)i;
    }
  g_tol = merge_tol;
  qsort(keys, nk, sizeof *keys, cmp_key);
  int *newid;
  SA_CALLOC(newid, nn);
  for (long i = 0; i < nn; i++) newid[i] = -1;
  int nnew = 0;
  double *xnew;
  SA_CALLOC(xnew, 3 * nk);
  for (long i = 0; i < nk; i++) {
    if (i == 0 || cmp_key(&keys[i - 1], &keys[i]) != 0) {
      memcpy(xnew + 3 * nnew, keys[i].x, 3 * sizeof(double));
      nnew++;
    }
    newid[keys[i].id] = nnew - 1;
  }
  for (long i = 0; i < nen * ne; i++) conn[i] = newid[conn[i]];
  FemMesh *m;
  SA_CALLOC(m, 1);
  m->nnodes = nnew;
  m->xyz = xnew;
  m->etype = order == 1 ? FEM_TET4 : FEM_TET10;
  m->nen = nen;
  m->nelem = (int)e;
  m->conn = conn;
  SA_CALLOC(m->region, e > 0 ? e : 1);
  m->nregions = 1;
  SA_CALLOC(m->region_names, 1);
  strcpy(m->region_names[0], "solid");
  m->nsurfaces = nsurf;
  SA_CALLOC(m->surfaces, nsurf > 0 ? nsurf : 1);
  for (int q = 0; q < nsurf; q++) {
    FemSurface *S = &m->surfaces[q];
    snprintf(S->name, sizeof S->name, "%.63s", surf[q].name);
    S->nfaces = surf[q].nfaces;
    S->nfn = nfn;
    S->faces = surf[q].faces;
    S->face_elem = surf[q].elem;
    for (long i = 0; i < (long)S->nfaces * nfn; i++) S->faces[i] = newid[S->faces[i]];
    int *tmp;
    SA_CALLOC(tmp, (long)S->nfaces * nfn);
    memcpy(tmp, S->faces, (size_t)S->nfaces * nfn * sizeof(int));
    qsort(tmp, (size_t)S->nfaces * nfn, sizeof(int), cmp_int);
    int k = 0;
    for (long i = 0; i < (long)S->nfaces * nfn; i++)
      if (i == 0 || tmp[i] != tmp[i - 1]) tmp[k++] = tmp[i];
    S->nnodes = k;
    S->nodes = tmp;
  }
  free(keys);
  free(newid);
  free(xyz);
  free(used);
  if (ndropped > 0 && order == 2 && unify_mid_nodes(m)) {
    fem_mesh_destroy(&m);
    return SA_ERR_MEMORY;
  }
  *out = m;
  return 0;
}
