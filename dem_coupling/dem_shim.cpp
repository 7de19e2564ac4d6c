/* dem_shim.cpp - the LIGGGHTS internals behind dem_shim.h: node-by-node motion of a wall mesh
 * and per-triangle forces of a `fix mesh/surface/stress`.
 *
 * LIGGGHTS moves meshes only rigidly (fix move/mesh); a deforming FEM wall needs every node set.
 * What a rigid mover does each step is repeated here for arbitrary node positions:
 *   - the mesh is registered as moving before the first run (MultiNodeMesh::registerMove), so
 *     LIGGGHTS keeps the node positions of the last neighbour build and treats the triangle
 *     neighbour lists with the skin (FixNeighlistMesh), and the wall contact reads the
 *     per-node velocity property `v` (FixWallGran::post_force_mesh);
 *   - after the nodes are overwritten, centres and bounding radii (updateCenterRbound) and
 *     edge vectors, normals and areas (SurfaceMesh::recalcLocalSurfProperties, protected:
 *     reached through a pointer to member named in a derived class, which is legal C++) are
 *     recomputed;
 *   - MultiNodeMesh::decideRebuild (a node moved more than half the skin since the last build)
 *     requests a neighbour rebuild at the next step through the fix's next_reneighbor, as
 *     FixMesh::pre_force would one step later.
 * Forces: the stress module sums the force of every grain contact into the element property
 * `f` (MeshModuleStress::add_particle_contribution), cleared every step. */
#include "dem_shim.h"

#include <lammps.h>
#include <modify.h>
#include <update.h>
#include <fix.h>
#include <fix_mesh_surface.h>
#include <fix_contact_history_mesh.h>
#include <atom.h>
#include <tri_mesh.h>
#include <neighbor.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace LAMMPS_NS;

namespace {

/* Names protected members of a TriMesh's bases (surface properties, node container) so that
 * they can be reached on a TriMesh; never instantiated. */
struct SurfaceAccess : TriMesh {
  static void recalc(TriMesh *m) {
    void (SurfaceMeshBase::*local)() = &SurfaceAccess::recalcLocalSurfProperties;
    void (SurfaceMeshBase::*ghost)() = &SurfaceAccess::recalcGhostSurfProperties;
    (m->*local)();
    if (m->sizeGhost() > 0) (m->*ghost)();
  }
  /* The node container (MultiNodeMesh::nodePtr is private). */
  static double ***nodes(TriMesh *m) {
    MultiVectorContainer<double, 3, 3> MultiNodeMesh<3>::*node = &SurfaceAccess::node_;
    return (m->*node).begin();
  }
  /* The per-node velocity property `v`, or 0 if it is missing or short. */
  static double ***velocities(TriMesh *m, int nall) {
    typedef MultiVectorContainer<double, 3, 3> NodeVec;
    NodeVec *vc = m->prop().getElementProperty<NodeVec>("v");
    return vc && vc->size() >= nall ? vc->begin() : 0;
  }
  static double **centers(TriMesh *m) {
    VectorContainer<double, 3> MultiNodeMesh<3>::*c = &SurfaceAccess::center_;
    return (m->*c).begin();
  }
  static double *rbounds(TriMesh *m) {
    ScalarContainer<double> MultiNodeMesh<3>::*r = &SurfaceAccess::rBound_;
    return (m->*r).begin();
  }
  static double ***last_build(TriMesh *m) {
    MultiVectorContainer<double, 3, 3> MultiNodeMesh<3>::*o = &SurfaceAccess::nodesLastRe_;
    return (m->*o).begin();
  }
  static int last_build_size(TriMesh *m) {
    MultiVectorContainer<double, 3, 3> MultiNodeMesh<3>::*o = &SurfaceAccess::nodesLastRe_;
    return (m->*o).size();
  }
  /* LIGGGHTS' normal of element i, with its fallbacks for a degenerate triangle. */
  static void surface_norm(TriMesh *m, int i, double *n) {
    void (SurfaceMeshBase::*f)(int, double *) = &SurfaceAccess::calcSurfaceNorm;
    (m->*f)(i, n);
  }
};

/* Raw arrays of what a moved TriMesh must recompute: the node copies, centres and bounding
 * radii of MultiNodeMesh, and the element properties SurfaceMesh registers by name. */
struct LeanSurface {
  double ***node, **center, *rbound, ***last_build;
  double *edge_len_flat, **edge_len, ***edge_vec, ***edge_norm, **normal, *area, *area_acc;
  double *area_mesh;
  int *obtuse;
  explicit LeanSurface(TriMesh *m) {
    CustomValueTracker &p = m->prop();
    node = SurfaceAccess::nodes(m);
    center = SurfaceAccess::centers(m);
    rbound = SurfaceAccess::rbounds(m);
    last_build = SurfaceAccess::last_build(m);
    edge_len = p.getElementProperty<VectorContainer<double, 3> >("edgeLen")->begin();
    edge_vec = p.getElementProperty<MultiVectorContainer<double, 3, 3> >("edgeVec")->begin();
    edge_norm = p.getElementProperty<MultiVectorContainer<double, 3, 3> >("edgeNorm")->begin();
    normal = p.getElementProperty<VectorContainer<double, 3> >("surfaceNorm")->begin();
    area = p.getElementProperty<ScalarContainer<double> >("area")->begin();
    area_acc = p.getElementProperty<ScalarContainer<double> >("areaAcc")->begin();
    obtuse = p.getElementProperty<ScalarContainer<int> >("obtuseAngleIndex")->begin();
    area_mesh = p.getGlobalProperty<ScalarContainer<double> >("areaMesh")->begin();
  }
};

FixMeshSurface *as_fix(void *p) { return static_cast<FixMeshSurface *>(p); }

}  // namespace

extern "C" {

void *dem_shim_mesh(void *lmp, const char *fix_id) {
  LAMMPS *l = static_cast<LAMMPS *>(lmp);
  Fix *f = l->modify->find_fix_id(fix_id);
  FixMeshSurface *fm = f ? dynamic_cast<FixMeshSurface *>(f) : 0;
  return fm;
}

int dem_shim_mesh_size(void *mesh) { return as_fix(mesh)->triMesh()->sizeLocal(); }

int dem_shim_mesh_id(void *mesh, int i) { return as_fix(mesh)->triMesh()->id(i); }

void dem_shim_mesh_node(void *mesh, int i, int c, double *xyz) {
  as_fix(mesh)->triMesh()->node(i, c, xyz);
}

int dem_shim_mesh_make_moving(void *mesh) {
  TriMesh *m = as_fix(mesh)->triMesh();
  if (m->isMoving()) return -1;
  if (m->sizeLocal() + m->sizeGhost() == 0 && m->sizeGlobal() == 0) return -1;
  m->registerMove(false, true, false);
  typedef MultiVectorContainer<double, 3, 3> NodeVec;
  NodeVec *v = m->prop().getElementProperty<NodeVec>("v");
  if (!v) v = m->prop().addElementProperty<NodeVec>("v", "comm_exchange_borders", "frame_invariant",
                                                   "restart_no");
  if (!v) return -1;
  v->setAll(0.);
  return 0;
}

/* Node copies (and velocities) from the caller's vertex arrays. */
static void copy_nodes(TriMesh *m, const int *idx, const double *xyz, const double *v) {
  const int nall = m->sizeLocal() + m->sizeGhost();
  double ***node = SurfaceAccess::nodes(m);
  double ***vn = SurfaceAccess::velocities(m, nall);
  for (int i = 0; i < nall; i++) {
    const int *k = idx + 3 * m->id(i);
    for (int c = 0; c < 3; c++) {
      const double *p = xyz + 3 * k[c];
      node[i][c][0] = p[0];
      node[i][c][1] = p[1];
      node[i][c][2] = p[2];
      if (!vn) continue;
      const double *q = v ? v + 3 * k[c] : 0;
      vn[i][c][0] = q ? q[0] : 0.;
      vn[i][c][1] = q ? q[1] : 0.;
      vn[i][c][2] = q ? q[2] : 0.;
    }
  }
}

/* Request a neighbour rebuild at the next step (as FixMesh::pre_force would one step later). */
static int request_rebuild(void *lmp, FixMeshSurface *fm) {
  *fm->get_next_reneighbor_ptr() = static_cast<LAMMPS *>(lmp)->update->ntimestep + 1;
  return 1;
}

int dem_shim_mesh_set_nodes_liggghts(void *lmp, void *mesh, const int *idx, const double *xyz,
                                     const double *v, int after_setup) {
  FixMeshSurface *fm = as_fix(mesh);
  TriMesh *m = fm->triMesh();
  copy_nodes(m, idx, xyz, v);
  m->updateCenterRbound(0, m->sizeLocal() + m->sizeGhost());
  SurfaceAccess::recalc(m);
  /* before the first set-up LIGGGHTS has no neighbour-build positions (and builds anyway) */
  if (after_setup && m->decideRebuild()) return request_rebuild(lmp, fm);
  return 0;
}

/* A container's storage as one flat array of `per` doubles per element, or 0 if LIGGGHTS did
 * not lay it out contiguously (then the caller takes LIGGGHTS' own path). */
static double *flat3(double ***p, int n) {
  if (n == 0) return 0;
  double *f = p[0][0];
  return p[n - 1][2] == f + 9 * (n - 1) + 6 && p[n - 1][0] == f + 9 * (n - 1) ? f : 0;
}
static double *flat2(double **p, int n) {
  if (n == 0) return 0;
  return p[n - 1] == p[0] + 3 * (n - 1) ? p[0] : 0;
}

/* Working memory of the wall update, kept between calls (no allocation per DEM step once
 * it has grown to the mesh: 9 values per element). */
static std::vector<double> &scratch(int n3) {
  static std::vector<double> w;
  if (w.size() < 3 * (size_t)n3) w.resize(3 * (size_t)n3);
  return w;
}

/* root[k] = sqrt(sq[k]), inv[k] = 1 / root[k]: what vectorMag3D and vectorScalarDiv3D do. */
static void roots_and_reciprocals(const double *sq, double *root, double *inv, int n) {
  for (int k = 0; k < n; k++) root[k] = ::sqrt(sq[k]);
  for (int k = 0; k < n; k++) inv[k] = 1. / root[k];
}

/* v[3k + c] *= s[k]: vectorScalarDiv3D's multiplication by the reciprocal. */
static void scale_rows(double *v, const double *s, int n) {
  for (int k = 0; k < n; k++) v[3 * k] *= s[k], v[3 * k + 1] *= s[k], v[3 * k + 2] *= s[k];
}

int dem_shim_mesh_set_nodes(void *lmp, void *mesh, const int *idx, const double *xyz,
                            const double *v, int after_setup) {
  FixMeshSurface *fm = as_fix(mesh);
  TriMesh *m = fm->triMesh();
  const int nlocal = m->sizeLocal(), nall = nlocal + m->sizeGhost();
  LeanSurface s(m);
  double *X = flat3(s.node, nall), *E = flat3(s.edge_vec, nall), *EN = flat3(s.edge_norm, nall);
  double *C = flat2(s.center, nall), *L = flat2(s.edge_len, nall), *N = flat2(s.normal, nall);
  double *O = after_setup ? flat3(s.last_build, nlocal) : 0;
  /* the rebuild test needs LIGGGHTS' build positions of every owned element: if they are not
   * laid out (LIGGGHTS would stop with an internal error), or a container is not one block,
   * take LIGGGHTS' own path */
  if (!X || !E || !EN || !C || !L || !N || (after_setup && (!O ||
      SurfaceAccess::last_build_size(m) != nlocal)))
    return dem_shim_mesh_set_nodes_liggghts(lmp, mesh, idx, xyz, v, after_setup);
  copy_nodes(m, idx, xyz, v);
  /* The arithmetic of LIGGGHTS' routines operation for operation (so every bit agrees), in
   * separate passes over the elements: each pass is short and its elements independent, so
   * the square roots and divisions of many elements overlap instead of waiting on each other
   * along one element's chain (4x faster than one pass per element, measured). */
  /* centre and bounding radius: MultiNodeMesh::updateCenterRbound (the largest radius is the
   * root of the largest square: sqrt is monotone and correctly rounded) */
  const double third = 1. / 3.;
  for (int i = 0; i < nall; i++) {
    const double *x = X + 9 * i;
    double *c = C + 3 * i;
    for (int k = 0; k < 3; k++) c[k] = (((0. + x[k]) + x[3 + k]) + x[6 + k]) * third;
    double r2 = 0.;
    for (int j = 0; j < 3; j++) {
      const double d0 = c[0] - x[3 * j], d1 = c[1] - x[3 * j + 1], d2 = c[2] - x[3 * j + 2];
      r2 = std::max(r2, d0 * d0 + d1 * d1 + d2 * d2);
    }
    s.rbound[i] = ::sqrt(r2);
  }
  /* unit edge vectors and lengths: SurfaceMesh::calcEdgeVecLen; the roots and reciprocals
   * in loops of their own, which the compiler vectorises (sqrt and division are correctly
   * rounded, packed or not) */
  std::vector<double> &q = scratch(3 * nall);
  double *Q = q.data(), *R = Q + 3 * nall; /* squares, reciprocals */
  for (int i = 0; i < nall; i++)
    for (int j = 0; j < 3; j++) {
      const double *a = X + 9 * i + 3 * ((j + 1) % 3), *b = X + 9 * i + 3 * j;
      double *e = E + 9 * i + 3 * j;
      e[0] = a[0] - b[0], e[1] = a[1] - b[1], e[2] = a[2] - b[2];
      Q[3 * i + j] = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    }
  roots_and_reciprocals(Q, L, R, 3 * nall);
  scale_rows(E, R, 3 * nall);
  /* unit normal e0 x e1 (calcSurfaceNorm) and area 0.5 |e0 x e1| l0 l1 (TriMesh::calcArea) */
  for (int i = 0; i < nall; i++) {
    const double *e0 = E + 9 * i, *e1 = e0 + 3;
    double *n = N + 3 * i;
    n[0] = e0[1] * e1[2] - e0[2] * e1[1];
    n[1] = e0[2] * e1[0] - e0[0] * e1[2];
    n[2] = e0[0] * e1[1] - e0[1] * e1[0];
    Q[i] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  }
  double *CR = Q + nall; /* |e0 x e1| (Q holds only nall squares here) */
  roots_and_reciprocals(Q, CR, R, nall);
  int degenerate = 0;
  for (int i = 0; i < nall; i++) {
    s.area[i] = 0.5 * CR[i] * L[3 * i] * L[3 * i + 1];
    degenerate |= CR[i] < 1e-15;
  }
  scale_rows(N, R, nall);
  if (degenerate) /* LIGGGHTS' fallback normals for a (nearly) collinear triangle */
    for (int i = 0; i < nall; i++)
      if (CR[i] < 1e-15) SurfaceAccess::surface_norm(m, i, N + 3 * i);
  /* in-plane edge normals e_j x n (calcEdgeNormals) */
  for (int i = 0; i < nall; i++)
    for (int j = 0; j < 3; j++) {
      const double *e = E + 9 * i + 3 * j, *n = N + 3 * i;
      double *o = EN + 9 * i + 3 * j;
      o[0] = e[1] * n[2] - e[2] * n[1];
      o[1] = e[2] * n[0] - e[0] * n[2];
      o[2] = e[0] * n[1] - e[1] * n[0];
      Q[3 * i + j] = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
    }
  double *M = R + 3 * nall; /* |e_j x n|: the scratch's last third */
  roots_and_reciprocals(Q, M, R, 3 * nall);
  scale_rows(EN, R, 3 * nall);
  for (int k = 0; k < 3 * nall; k++)
    if (M[k] < 1e-15) { /* edge parallel to the normal: LIGGGHTS takes the next edge */
      const int i = k / 3, j = k % 3;
      const double *f = E + 9 * i + 3 * ((j + 1) % 3);
      double *o = EN + 3 * k;
      o[0] = f[0], o[1] = f[1], o[2] = f[2];
    }
  /* calcObtuseAngleIndex is called for corners 0, 1, 2 and each call overwrites the last:
   * what LIGGGHTS keeps is corner 2's test, so that is what is stored; accumulated areas */
  double sum_local = 0., sum_ghost = 0.;
  for (int i = 0; i < nall; i++) {
    const double *e1 = E + 9 * i + 3, *e2 = E + 9 * i + 6;
    const double dot = e2[0] * e1[0] + e2[1] * e1[1] + e2[2] * e1[2];
    s.obtuse[i] = dot > 0. ? 2 : SurfaceMeshBase::NO_OBTUSE_ANGLE;
    s.area_acc[i] = s.area[i] + (i > 0 ? s.area_acc[i - 1] : 0.);
    if (i < nlocal) sum_local += s.area[i];
    else sum_ghost += s.area[i];
  }
  s.area_mesh[1] = sum_local;
  s.area_mesh[2] = sum_ghost;
  MPI_Comm world = static_cast<LAMMPS *>(lmp)->world;
  MPI_Allreduce(&sum_local, &s.area_mesh[0], 1, MPI_DOUBLE, MPI_SUM, world);
  m->updateGlobalBoundingBox();
  if (!after_setup) return 0;
  /* MultiNodeMesh::decideRebuild: a node moved more than half the skin since the last build */
  const double skin = static_cast<LAMMPS *>(lmp)->neighbor->skin, trigger = 0.25 * skin * skin;
  int moved = 0;
  for (int k = 0; k < 3 * nlocal; k++) {
    const double d0 = X[3 * k] - O[3 * k], d1 = X[3 * k + 1] - O[3 * k + 1],
                 d2 = X[3 * k + 2] - O[3 * k + 2];
    moved |= d0 * d0 + d1 * d1 + d2 * d2 > trigger;
  }
  int any = 0;
  MPI_Allreduce(&moved, &any, 1, MPI_INT, MPI_MAX, world);
  return any ? request_rebuild(lmp, fm) : 0;
}

int dem_shim_mesh_surface(void *mesh, int i, double *out) {
  TriMesh *m = as_fix(mesh)->triMesh();
  if (i < 0 || i >= m->sizeLocal() + m->sizeGhost()) return -1;
  LeanSurface s(m);
  double *o = out;
  for (int k = 0; k < 3; k++) *o++ = s.center[i][k];
  *o++ = s.rbound[i];
  for (int j = 0; j < 3; j++) *o++ = s.edge_len[i][j];
  for (int j = 0; j < 3; j++)
    for (int k = 0; k < 3; k++) *o++ = s.edge_vec[i][j][k];
  for (int j = 0; j < 3; j++)
    for (int k = 0; k < 3; k++) *o++ = s.edge_norm[i][j][k];
  for (int k = 0; k < 3; k++) *o++ = s.normal[i][k];
  *o++ = s.area[i];
  *o++ = s.area_acc[i];
  *o++ = s.obtuse[i];
  *o++ = s.area_mesh[0];
  *o++ = s.area_mesh[1];
  *o++ = s.area_mesh[2];
  return (int)(o - out);
}

int dem_shim_mesh_forces(void *mesh, double *f) {
  TriMesh *m = as_fix(mesh)->triMesh();
  VectorContainer<double, 3> *fc = m->prop().getElementProperty<VectorContainer<double, 3> >("f");
  if (!fc) return -1;
  const int n = m->sizeLocal();
  if (fc->size() < n) return -1;
  double **fe = fc->begin();
  for (int i = 0; i < n; i++) {
    double *o = f + 3 * m->id(i);
    o[0] = fe[i][0];
    o[1] = fe[i][1];
    o[2] = fe[i][2];
  }
  return 0;
}

int dem_shim_mesh_contacts(void *lmp, void *mesh, int max, int *tag, int *tri, double *hist) {
  FixContactHistoryMesh *h = as_fix(mesh)->contactHistory();
  if (!h) return -1;
  Atom *atom = static_cast<LAMMPS *>(lmp)->atom;
  const int nlocal = atom->nlocal, dnum = h->get_dnum();
  int n = 0;
  for (int i = 0; i < nlocal; i++) {
    const int nn = h->nneighs(i);
    for (int j = 0; j < nn; j++) {
      const int t = h->get_partner_idTri(i, j);
      if (t < 0) continue;
      if (n < max) {
        tag[n] = atom->tag[i];
        tri[n] = t;
        const double *c = h->contacthistory(i, j);
        for (int k = 0; k < 3; k++) hist[3 * n + k] = k < dnum ? c[k] : 0.;
      }
      n++;
    }
  }
  return n;
}

}  /* extern "C" */
