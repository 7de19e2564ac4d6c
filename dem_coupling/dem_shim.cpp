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
#include <neighbor.h>
#include <fix.h>
#include <fix_mesh_surface.h>
#include <fix_contact_history_mesh.h>
#include <atom.h>
#include <tri_mesh.h>
#include <vector_liggghts.h>

#include <algorithm>

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
  /* MultiNodeMesh::updateCenterRbound for elements [0, n), without its last call,
   * updateGlobalBoundingBox (two reductions over the ranks): the global box is read only by
   * insertion faces (fix insert/stream), never by a wall contact. The same arithmetic, so the
   * same bits. */
  static void centres(TriMesh *m, int n) {
    VectorContainer<double, 3> MultiNodeMesh<3>::*cp = &SurfaceAccess::center_;
    ScalarContainer<double> MultiNodeMesh<3>::*rp = &SurfaceAccess::rBound_;
    double ***node = nodes(m);
    for (int i = 0; i < n; i++) {
      double *c = (m->*cp)(i);
      vectorZeroize3D(c);
      for (int j = 0; j < 3; j++) vectorAdd3D(node[i][j], c, c);
      vectorScalarDiv3D(c, 3.0);
      double rb = 0., vec[3];
      for (int j = 0; j < 3; j++) {
        vectorSubtract3D(c, node[i][j], vec);
        rb = std::max(rb, vectorMag3D(vec));
      }
      (m->*rp)(i) = rb;
    }
  }
  /* SurfaceMesh::recalcLocalSurfProperties and recalcGhostSurfProperties for elements [0, n),
   * without the mesh's total area (a sum over the ranks, read only by insertion faces): edge
   * vectors and lengths, surface normal, edge normals, obtuse-angle flag, area, accumulated
   * area. The operations of SurfaceMesh::calcEdgeVecLen, calcSurfaceNorm, calcEdgeNormals,
   * calcObtuseAngleIndex and TriMesh::calcArea in their order, so the same bits, in one pass
   * over each element's data (theirs are five calls per element, and calcArea allocates). */
  static void surfaces(TriMesh *m, int n) {
    typedef MultiVectorContainer<double, 3, 3> MV;
    typedef VectorContainer<double, 3> V3;
    double ***node = nodes(m);
    double **len = m->prop().getElementProperty<V3>("edgeLen")->begin();
    double ***vec = m->prop().getElementProperty<MV>("edgeVec")->begin();
    double ***enorm = m->prop().getElementProperty<MV>("edgeNorm")->begin();
    double **snorm = m->prop().getElementProperty<V3>("surfaceNorm")->begin();
    double *area = m->prop().getElementProperty<ScalarContainer<double> >("area")->begin();
    double *acc = m->prop().getElementProperty<ScalarContainer<double> >("areaAcc")->begin();
    int *obtuse = m->prop().getElementProperty<ScalarContainer<int> >("obtuseAngleIndex")->begin();
    for (int i = 0; i < n; i++) {
      double **e = vec[i], *sn = snorm[i];
      for (int j = 0; j < 3; j++) {
        vectorSubtract3D(node[i][(j + 1) % 3], node[i][j], e[j]);
        len[i][j] = vectorMag3D(e[j]);
        vectorScalarDiv3D(e[j], len[i][j]);
      }
      surface_norm(e, sn);
      for (int j = 0; j < 3; j++) {
        double *en = enorm[i][j];
        vectorCross3D(e[j], sn, en);
        if (vectorMag3D(en) < 1e-15)
          vectorCopy3D(e[(j + 1) % 3], en);
        else
          vectorScalarDiv3D(en, vectorMag3D(en));
      }
      /* calcObtuseAngleIndex is called for corners 0, 1, 2 and each call overwrites the flag:
       * the last one decides */
      for (int j = 0; j < 3; j++) {
        if (vectorDot3D(e[j], e[(j + 2) % 3]) > 0.)
          obtuse[i] = j;
        else
          obtuse[i] = SurfaceMeshBase::NO_OBTUSE_ANGLE;
      }
      double t[3];
      vectorCross3D(e[0], e[1], t);
      area[i] = 0.5 * vectorMag3D(t) * len[i][0] * len[i][1];
      acc[i] = area[i];
      if (i > 0) acc[i] += acc[i - 1];
    }
  }
  /* SurfaceMesh::calcSurfaceNorm: the normal from the first pair of edges that is not
   * parallel (then from fixed vectors), normalised. */
  static void surface_norm(double **e, double *sn) {
    static const double t1[] = {1.1233, 2.123231, -3.3343434}, t2[] = {1.1233, -2.123231, 3.3343434};
    const double *pairs[7][2] = {{e[0], e[1]}, {e[1], e[2]}, {e[2], e[0]}, {e[0], t1},
                                 {e[1], t1},   {e[0], t2},   {e[1], t2}};
    for (int k = 0; k < 7; k++) {
      vectorCross3D(pairs[k][0], pairs[k][1], sn);
      if (!(vectorMag3D(sn) < 1e-15)) break; /* LIGGGHTS' test, NaN included */
    }
    vectorScalarDiv3D(sn, vectorMag3D(sn));
  }
};

FixMeshSurface *as_fix(void *p) { return static_cast<FixMeshSurface *>(p); }

/* The end of a node update: a neighbour rebuild at the next step when a node moved more than
 * half the skin since the last one (MultiNodeMesh::decideRebuild: one reduction over the
 * ranks, so that every rank decides alike). */
int request_rebuild(void *lmp, FixMeshSurface *fm, int after_setup) {
  /* before the first set-up LIGGGHTS has no neighbour-build positions (and builds anyway) */
  if (after_setup && fm->triMesh()->decideRebuild()) {
    *fm->get_next_reneighbor_ptr() = static_cast<LAMMPS *>(lmp)->update->ntimestep + 1;
    return 1;
  }
  return 0;
}

/* Every node copy (owned and ghost) of mesh m to xyz[3*idx[3*id+c]], its velocity to v[...]
 * (v NULL: zero). */
void copy_nodes(TriMesh *m, const int *idx, const double *xyz, const double *v) {
  const int nall = m->sizeLocal() + m->sizeGhost();
  double ***node = SurfaceAccess::nodes(m);
  typedef MultiVectorContainer<double, 3, 3> NodeVec;
  NodeVec *vc = m->prop().getElementProperty<NodeVec>("v");
  double ***vn = vc && vc->size() >= nall ? vc->begin() : 0;
  for (int i = 0; i < nall; i++) {
    const int *k = idx + 3 * m->id(i);
    for (int c = 0; c < 3; c++) {
      const double *p = xyz + 3 * k[c];
      node[i][c][0] = p[0];
      node[i][c][1] = p[1];
      node[i][c][2] = p[2];
      if (!vn) continue;
      if (v) {
        const double *q = v + 3 * k[c];
        vn[i][c][0] = q[0];
        vn[i][c][1] = q[1];
        vn[i][c][2] = q[2];
      } else {
        vn[i][c][0] = vn[i][c][1] = vn[i][c][2] = 0.;
      }
    }
  }
}

/* The stress module's force of the last step on each owned triangle, written (add = 0) or
 * added (add = 1) to out at 3*id. */
int forces_to(void *mesh, double *out, int add) {
  TriMesh *m = as_fix(mesh)->triMesh();
  VectorContainer<double, 3> *fc = m->prop().getElementProperty<VectorContainer<double, 3> >("f");
  if (!fc) return -1;
  const int n = m->sizeLocal();
  if (fc->size() < n) return -1;
  double **fe = fc->begin();
  for (int i = 0; i < n; i++) {
    double *o = out + 3 * m->id(i);
    for (int k = 0; k < 3; k++) o[k] = add ? o[k] + fe[i][k] : fe[i][k];
  }
  return 0;
}

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

int dem_shim_mesh_set_nodes(void *lmp, void *mesh, const int *idx, const double *xyz,
                            const double *v, int after_setup) {
  FixMeshSurface *fm = as_fix(mesh);
  TriMesh *m = fm->triMesh();
  copy_nodes(m, idx, xyz, v);
  m->updateCenterRbound(0, m->sizeLocal() + m->sizeGhost());
  SurfaceAccess::recalc(m);
  return request_rebuild(lmp, fm, after_setup);
}

void dem_shim_mesh_place(void *mesh, const int *idx, const double *xyz, const double *v) {
  TriMesh *m = as_fix(mesh)->triMesh();
  const int nall = m->sizeLocal() + m->sizeGhost();
  copy_nodes(m, idx, xyz, v);
  SurfaceAccess::centres(m, nall);
  SurfaceAccess::surfaces(m, nall);
}

void dem_shim_mesh_place_flat(void *mesh, double z, double vz) {
  TriMesh *m = as_fix(mesh)->triMesh();
  const int nall = m->sizeLocal() + m->sizeGhost();
  double ***node = SurfaceAccess::nodes(m);
  typedef MultiVectorContainer<double, 3, 3> NodeVec;
  NodeVec *vc = m->prop().getElementProperty<NodeVec>("v");
  double ***vn = vc && vc->size() >= nall ? vc->begin() : 0;
  for (int i = 0; i < nall; i++)
    for (int c = 0; c < 3; c++) {
      node[i][c][2] = z;
      if (vn) vn[i][c][0] = vn[i][c][1] = 0., vn[i][c][2] = vz;
    }
  /* every edge vector keeps its z component 0 exactly, so edges, normals and areas are the
   * ones a recomputation would give, bit for bit (test dem_bridge_place) */
  SurfaceAccess::centres(m, nall);
}

void dem_shim_mesh_request_rebuild(void *lmp, void *mesh) {
  *as_fix(mesh)->get_next_reneighbor_ptr() = static_cast<LAMMPS *>(lmp)->update->ntimestep + 1;
}

double dem_shim_skin(void *lmp) { return static_cast<LAMMPS *>(lmp)->neighbor->skin; }

void dem_shim_builds(void *lmp, long long *builds, long long *last) {
  Neighbor *n = static_cast<LAMMPS *>(lmp)->neighbor;
  *builds = n->ncalls;
  *last = n->lastcall;
}

int dem_shim_mesh_forces(void *mesh, double *f) { return forces_to(mesh, f, 0); }

int dem_shim_mesh_forces_add(void *mesh, double *sum) { return forces_to(mesh, sum, 1); }

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
