/* cutil.h - helpers of the contact tests: several structured bodies in one mesh sharing no
 * node (smesh merges coincident nodes, which would glue touching bodies), boxes and a
 * cylinder map, tributary-area loads. */
#ifndef CUTIL_H
#define CUTIL_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "fem_contact.h"
#include "fem_mesh.h"
#include "smesh.h"

typedef struct {
  double lo[3], hi[3];
} CuBox;

static inline void cu_map_box(const double xi[3], const void *ctx, double X[3]) {
  const CuBox *b = ctx;
  for (int i = 0; i < 3; i++) X[i] = b->lo[i] + xi[i] * (b->hi[i] - b->lo[i]);
}

/* Cylinder of radius R (ctx[0]) and height ctx[1] from z = ctx[2], square-to-disc map
 * x = u sqrt(1 - v^2/2), y = v sqrt(1 - u^2/2) (u, v in [-1, 1]): boundary nodes lie on the
 * circle exactly. */
static inline void cu_map_cyl(const double xi[3], const void *ctx, double X[3]) {
  const double *c = ctx;
  double u = 2 * xi[0] - 1, v = 2 * xi[1] - 1;
  X[0] = c[0] * u * sqrt(1 - 0.5 * v * v);
  X[1] = c[0] * v * sqrt(1 - 0.5 * u * u);
  X[2] = c[2] + c[1] * xi[2];
}

/* Concatenate meshes [in] (built by smesh_build) into one [out, free with smesh_free]: node and
 * element numbers offset, region k named names[k], surfaces kept with their names. */
static inline int cu_concat(int nm, FemMesh *const *ms, const char *const *names, FemMesh **out) {
  FemMesh *m = calloc(1, sizeof *m);
  if (!m) return -1;
  int nn = 0, ne = 0, ns = 0;
  for (int k = 0; k < nm; k++) {
    nn += ms[k]->nnodes;
    ne += ms[k]->nelem;
    ns += ms[k]->nsurfaces;
  }
  m->etype = ms[0]->etype;
  m->nen = ms[0]->nen;
  m->nnodes = nn;
  m->nelem = ne;
  m->xyz = malloc(sizeof(double) * 3 * nn);
  m->conn = malloc(sizeof(int) * (size_t)m->nen * ne);
  m->region = malloc(sizeof(int) * ne);
  m->nregions = nm;
  m->region_names = calloc(nm, sizeof *m->region_names);
  m->nsurfaces = ns;
  m->surfaces = calloc(ns, sizeof *m->surfaces);
  int no = 0, eo = 0, so = 0;
  for (int k = 0; k < nm; k++) {
    const FemMesh *a = ms[k];
    memcpy(m->xyz + 3 * no, a->xyz, sizeof(double) * 3 * a->nnodes);
    for (int i = 0; i < a->nen * a->nelem; i++) m->conn[(size_t)m->nen * eo + i] = a->conn[i] + no;
    for (int e = 0; e < a->nelem; e++) m->region[eo + e] = k;
    snprintf(m->region_names[k], 64, "%s", names[k]);
    for (int q = 0; q < a->nsurfaces; q++) {
      const FemSurface *S = &a->surfaces[q];
      FemSurface *T = &m->surfaces[so++];
      *T = *S;
      T->faces = malloc(sizeof(int) * S->nfaces * S->nfn);
      T->face_elem = malloc(sizeof(int) * S->nfaces);
      T->nodes = malloc(sizeof(int) * S->nnodes);
      for (int i = 0; i < S->nfaces * S->nfn; i++) T->faces[i] = S->faces[i] + no;
      for (int i = 0; i < S->nfaces; i++) T->face_elem[i] = S->face_elem[i] + eo;
      for (int i = 0; i < S->nnodes; i++) T->nodes[i] = S->nodes[i] + no;
    }
    no += a->nnodes;
    eo += a->nelem;
  }
  *out = m;
  return 0;
}

/* The contact patch test's two blocks (test_contact_patch.c, test_contact_patch_tet10.c): an
 * a x a x a block (4 x 4 x 3 cells, 3 x 3 x 2 when matching) on an a x a x a block below z = 0
 * (3 x 3 x 2 cells), elements of the given order, in one mesh [out, smesh_free] (regions upper,
 * lower; surfaces xu0 xu1 yu0 yu1 ubot top and xl0 xl1 yl0 yl1 base ltop), and a solver [out]
 * with material (E, nu) in both (composite: tet10 as the composite element,
 * FemMaterial.tet10_composite), the given rtol, rollers on x = 0 and y = 0 of each block and
 * the base held in z. */
static inline int cu_patch_setup(int order, int matching, int composite, double a, double E,
                                 double nu, double rtol, FemMesh **m, FemSolver **s) {
  FemMesh *mb[2] = {NULL, NULL};
  CuBox up = {{0, 0, 0}, {a, a, a}}, lo = {{0, 0, -a}, {a, a, 0}};
  SmeshBlock bu = {{4, 4, 3}, cu_map_box, &up, {"xu0", "xu1", "yu0", "yu1", "ubot", "top"}};
  SmeshBlock bl = {{3, 3, 2}, cu_map_box, &lo, {"xl0", "xl1", "yl0", "yl1", "base", "ltop"}};
  if (matching) memcpy(bu.n, bl.n, sizeof bu.n);
  const char *names[2] = {"upper", "lower"};
  int rc = smesh_build(1, &bu, order, 1e-12, &mb[0]) || smesh_build(1, &bl, order, 1e-12, &mb[1]) ||
           cu_concat(2, mb, names, m);
  smesh_free(&mb[0]);
  smesh_free(&mb[1]);
  if (rc) return -1;
  FemMaterial mats[2] = {fem_material_from_e_nu(E, nu, 1000), fem_material_from_e_nu(E, nu, 1000)};
  mats[0].tet10_composite = mats[1].tet10_composite = composite;
  FemSolverParams prm = fem_solver_params_default();
  prm.rtol = rtol;
  if (fem_solver_create(*m, mats, &prm, s)) return -1;
  const char *fx[2] = {"xu0", "xl0"}, *fy[2] = {"yu0", "yl0"};
  for (int k = 0; k < 2; k++)
    if (fem_solver_fix_surface(*s, fx[k], FEM_X) || fem_solver_fix_surface(*s, fy[k], FEM_Y))
      return -1;
  return fem_solver_fix_surface(*s, "base", FEM_Z);
}

/* Nodal forces of a uniform traction t [in] 3 on surface S (tri3: a third of each face's
 * area to each corner; consistent for a linear field): f [out] 3 * S->nnodes in the order of
 * S->nodes. */
static inline void cu_traction(const FemMesh *m, const FemSurface *S, const double t[3], double *f) {
  memset(f, 0, sizeof(double) * 3 * S->nnodes);
  for (int k = 0; k < S->nfaces; k++) {
    const int *c = S->faces + 3 * k;
    const double *a = m->xyz + 3 * c[0], *b = m->xyz + 3 * c[1], *d = m->xyz + 3 * c[2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double area = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; i++) {
      int lo = 0, hi = S->nnodes - 1;
      while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (S->nodes[mid] < c[i]) lo = mid + 1;
        else hi = mid;
      }
      for (int j = 0; j < 3; j++) f[3 * lo + j] += area / 3 * t[j];
    }
  }
}

/* A fill column of a cu_map_cyl mesh (its sides "s0".."s3") in a rigid tube of radius R around
 * the z axis: the in-plane rigid motions removed (nodes on the axis fixed in x and y, nodes on
 * the +x radius in y) and each side in contact (parameters cp) with the tube wall, attached to
 * s. The four contacts go to wall[]; the caller destroys them. Returns 0 or the failing rc. */
static inline int cu_tube_setup(const FemMesh *m, FemSolver *s, const FemContactParams *cp,
                                double R, FemContact *wall[4]) {
  int rc = 0;
  for (int A = 0; A < m->nnodes && !rc; A++) {
    const double *X = m->xyz + 3 * A;
    if (fabs(X[0]) < 1e-9 && fabs(X[1]) < 1e-9) rc = fem_solver_fix_nodes(s, 1, &A, FEM_X | FEM_Y);
    else if (fabs(X[1]) < 1e-9 && X[0] > 0) rc = fem_solver_fix_nodes(s, 1, &A, FEM_Y);
  }
  const char *sides[4] = {"s0", "s1", "s2", "s3"};
  for (int k = 0; k < 4; k++) wall[k] = NULL;
  for (int k = 0; k < 4 && !rc; k++) {
    rc = fem_contact_create(m, sides[k], cp, &wall[k]);
    if (!rc)
      rc = fem_contact_set_cylinder(wall[k], (double[3]){0, 0, 0}, (double[3]){0, 0, 1}, R, -1, 1);
    if (!rc) rc = fem_contact_attach(wall[k], s);
  }
  return rc;
}

#endif
