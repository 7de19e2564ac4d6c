/* test_mesh_order.c - node order of the meshes handed to the solver.
 *
 *  1. Gmsh's own reference tet10 (gmshModelMeshGetElementProperties) has the mid-node order the
 *     conversion in fem_mesh.c assumes: 4:(0,1) 5:(1,2) 6:(0,2) 7:(0,3) 8:(2,3) 9:(1,3).
 *  2. On Cook's membrane (planar faces, straight edges) every tet10 mid-node lies at the
 *     midpoint of the VTK edge it claims (01, 12, 02, 03, 13, 23) and every tri6 face mid-node at
 *     the midpoint of face edges 01, 12, 20; tet4 and tet10 elements have positive volume.
 *  3. On the cylinder slab the curved mid-nodes lie on the geometry: a mid-node of an edge whose
 *     corners are both on r = A (or r = B) has r = A (B) to round-off (Mesh.SecondOrderLinear = 0),
 *     every other mid-node is its edge midpoint (interior edges are straight). */
#include <gmshc.h>
#include <math.h>
#include <stdio.h>

#include "mesh_test_util.h"
#include "sa_error.h"
#include "sa_log.h"

static const int vtk_edge[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};

static int check_gmsh_reference(void)
{
  static const int gmsh_edge[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}};
  int ierr = 0, dim = 0, order = 0, nn = 0, nprim = 0, fail = 0;
  char *name = NULL;
  double *lc = NULL;
  size_t nlc = 0;
  gmshInitialize(0, NULL, 0, &ierr);
  gmshOptionSetNumber("General.Terminal", 0, &ierr);
  gmshModelMeshGetElementProperties(11, &name, &dim, &order, &nn, &lc, &nlc, &nprim, &ierr);
  if (ierr || nn != 10 || nlc != 30) {
    fprintf(stderr, "gmsh type 11: ierr %d, %d nodes, %zu coords\n", ierr, nn, nlc);
    fail = 1;
  }
  for (int k = 0; k < 6 && !fail; ++k)
    for (int i = 0; i < 3; ++i) {
      double mid = 0.5 * (lc[3 * gmsh_edge[k][0] + i] + lc[3 * gmsh_edge[k][1] + i]);
      if (fabs(lc[3 * (4 + k) + i] - mid) > 1e-14) {
        fprintf(stderr, "gmsh tet10 node %d is not the midpoint of edge (%d,%d)\n", 4 + k,
                gmsh_edge[k][0], gmsh_edge[k][1]);
        fail = 1;
      }
    }
  gmshFree(name);
  gmshFree(lc);
  gmshFinalize(&ierr);
  return fail;
}

static double det_corners(const FemMesh *m, int e)
{
  const int *c = m->conn + (size_t)m->nen * e;
  const double *x0 = m->xyz + 3 * c[0];
  double a[3][3];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) a[k][i] = m->xyz[3 * c[k + 1] + i] - x0[i];
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/* Distance of mid-node p from the midpoint of (a, b), relative to |b - a|. */
static double mid_off(const FemMesh *m, int a, int b, int p)
{
  double d = 0, l = 0;
  for (int i = 0; i < 3; ++i) {
    double xa = m->xyz[3 * a + i], xb = m->xyz[3 * b + i];
    d += pow(m->xyz[3 * p + i] - 0.5 * (xa + xb), 2);
    l += pow(xb - xa, 2);
  }
  return sqrt(d / l);
}

static int check_straight(const char *geo, int order)
{
  char path[512];
  FemMesh *m = NULL;
  if (fem_mesh_generate(mt_geo(geo, path, sizeof path), 0, NULL, 0.0, order, &m)) {
    sa_error_print();
    return 1;
  }
  int fail = 0;
  for (int e = 0; e < m->nelem && !fail; ++e) {
    if (det_corners(m, e) <= 0) {
      fprintf(stderr, "%s order %d: element %d has corner volume <= 0\n", geo, order, e);
      fail = 1;
    }
    for (int k = 0; k < 6 && m->nen == 10 && !fail; ++k) {
      const int *c = m->conn + 10 * e;
      double off = mid_off(m, c[vtk_edge[k][0]], c[vtk_edge[k][1]], c[4 + k]);
      /* straight edges: the mid-node is computed as the midpoint, round-off only */
      if (off > 1e-10) {
        fprintf(stderr, "%s: element %d node %d is %.3g edge lengths off the midpoint of edge "
                        "(%d,%d)\n", geo, e, 4 + k, off, vtk_edge[k][0], vtk_edge[k][1]);
        fail = 1;
      }
    }
  }
  for (int s = 0; s < m->nsurfaces && !fail; ++s) {
    const FemSurface *S = &m->surfaces[s];
    if (S->nfn != (order == 2 ? 6 : 3)) {
      fprintf(stderr, "%s: surface %s has %d nodes per face\n", geo, S->name, S->nfn);
      fail = 1;
    }
    for (int f = 0; f < S->nfaces && S->nfn == 6 && !fail; ++f)
      for (int k = 0; k < 3; ++k) {
        const int *c = S->faces + 6 * f;
        double off = mid_off(m, c[k], c[(k + 1) % 3], c[3 + k]);
        if (off > 1e-10) {
          fprintf(stderr, "%s: surface %s face %d node %d off its edge midpoint by %.3g\n", geo,
                  S->name, f, 3 + k, off);
          fail = 1;
          break;
        }
      }
  }
  if (!fail && fem_mesh_check(m, 1e-6)) {
    sa_error_print();
    fail = 1;
  }
  fem_mesh_destroy(&m);
  return fail;
}

static int check_curved(void)
{
  char path[512];
  const double A = 6e-3, B = 8.5e-3;
  FemMesh *m = NULL;
  if (fem_mesh_generate(mt_geo("cylinder.geo", path, sizeof path), 0, NULL, 1e-3, 2, &m)) {
    sa_error_print();
    return 1;
  }
  int fail = 0, ncurved = 0;
  for (int e = 0; e < m->nelem && !fail; ++e) {
    const int *c = m->conn + 10 * e;
    for (int k = 0; k < 6 && !fail; ++k) {
      int a = c[vtk_edge[k][0]], b = c[vtk_edge[k][1]], p = c[4 + k];
      double ra = hypot(m->xyz[3 * a], m->xyz[3 * a + 1]);
      double rb = hypot(m->xyz[3 * b], m->xyz[3 * b + 1]);
      double rp = hypot(m->xyz[3 * p], m->xyz[3 * p + 1]);
      /* 1e-9 relative: node placement on the CAD circle is exact up to OCC round-off */
      double R = 0;
      if (fabs(ra - A) < 1e-9 * A && fabs(rb - A) < 1e-9 * A) R = A;
      if (fabs(ra - B) < 1e-9 * B && fabs(rb - B) < 1e-9 * B) R = B;
      if (R > 0 && mid_off(m, a, b, p) > 1e-12) {
        ++ncurved;
        if (fabs(rp - R) > 1e-9 * R) {
          fprintf(stderr, "cylinder: element %d mid-node %d at r = %.12g, not on r = %g\n", e,
                  4 + k, rp, R);
          fail = 1;
        }
      } else if (R == 0 && mid_off(m, a, b, p) > 1e-10) {
        fprintf(stderr, "cylinder: element %d mid-node %d of a straight edge is off the midpoint\n",
                e, 4 + k);
        fail = 1;
      }
    }
  }
  if (!fail && ncurved == 0) {
    fprintf(stderr, "cylinder: no curved mid-node found (Mesh.SecondOrderLinear ignored?)\n");
    fail = 1;
  }
  if (!fail && fem_mesh_check(m, 1e-6)) {
    sa_error_print();
    fail = 1;
  }
  fem_mesh_destroy(&m);
  return fail;
}

int main(void)
{
  sa_log_set_level(SA_LOG_WARN);
  int fail = 0;
  fail |= check_gmsh_reference();
  fail |= check_straight("cook.geo", 1);
  fail |= check_straight("cook.geo", 2);
  fail |= check_curved();
  return fail;
}
