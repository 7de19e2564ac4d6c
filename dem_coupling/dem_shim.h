/* dem_shim.h - private C interface to the few LIGGGHTS internals that library.h cannot reach
 * (dem_shim.cpp): the TriMesh of a `fix mesh/surface/stress`, its nodes, per-node velocities
 * and per-triangle forces. Used by dem_bridge.c only.
 *
 * LIGGGHTS stores each triangle with its own three node copies, in its own element order; an
 * element keeps its id (0-based position in the mesh file) when LIGGGHTS reorders elements,
 * so every function here addresses triangles by that id: idx[3*id + c] is the caller vertex
 * of corner c of the triangle with id `id`, and per-triangle outputs are indexed by id.
 * On several MPI ranks each function sees this rank's triangles (owned; set_nodes also writes
 * the ghost copies); dem_bridge.c combines the ranks. No function allocates. */
#ifndef DEM_SHIM_H
#define DEM_SHIM_H

#ifdef __cplusplus
extern "C" {
#endif

/* The `fix mesh/surface` fix_id [in] of instance lmp [borrowed], or NULL if there is none.
 * The result [borrowed] lives as long as the fix; every function below takes it. */
void *dem_shim_mesh(void *lmp, const char *fix_id);
/* Triangles LIGGGHTS holds on this process (owned). */
int dem_shim_mesh_size(void *mesh);
/* Id of the i-th owned triangle. */
int dem_shim_mesh_id(void *mesh, int i);
/* Corner c of the i-th owned triangle, xyz [out] 3. */
void dem_shim_mesh_node(void *mesh, int i, int c, double *xyz);
/* Declare the mesh moving (translation; before the first run, so that LIGGGHTS keeps the node
 * positions of the last neighbour build) and give it the per-node velocity property `v` that
 * the wall contact model reads. 0 ok, -1 if it cannot. */
int dem_shim_mesh_make_moving(void *mesh);
/* Overwrite every node copy with xyz[3*idx[3*id+c]] and its velocity with v[...] (v NULL:
 * zero), recompute centres, bounding radii, edge vectors, normals and areas, and request a
 * neighbour rebuild at the next step if a node moved more than half the skin since the last
 * build (after_setup: LIGGGHTS has run its set-up once). Returns 1 if a rebuild was requested,
 * 0 if not. */
int dem_shim_mesh_set_nodes(void *lmp, void *mesh, const int *idx, const double *xyz,
                            const double *v, int after_setup);
/* dem_shim_mesh_set_nodes (v required) without the quantities that are summed over the ranks:
 * the mesh's global bounding box and total area (read only by insertion faces, never by a wall
 * contact) and the rebuild decision (the caller decides, dem_shim_mesh_request_rebuild). Every
 * other quantity gets the same bits. For a mesh moved every DEM step. */
void dem_shim_mesh_place(void *mesh, const int *idx, const double *xyz, const double *v);
/* A flat mesh (every node at one height) moved to height z [m] with node velocity (0, 0, vz):
 * only the node heights, velocities, centres and bounding radii change (edges, normals and
 * areas of a flat mesh do not); otherwise as dem_shim_mesh_place. */
void dem_shim_mesh_place_flat(void *mesh, double z, double vz);
/* A neighbour rebuild at the next step (what MultiNodeMesh::decideRebuild asks for when a node
 * moved more than half the skin since the last build). */
void dem_shim_mesh_request_rebuild(void *lmp, void *mesh);
/* The neighbour skin [m]; the neighbour builds since the last set-up (a set-up resets the
 * count) and the step of the last one. */
double dem_shim_skin(void *lmp);
void dem_shim_builds(void *lmp, long long *builds, long long *last);
/* Force of the last step on each triangle, f [out] at 3*id [N]; -1 if the mesh tracks no
 * stress. */
int dem_shim_mesh_forces(void *mesh, double *f);
/* dem_shim_mesh_forces added to sum [in/out] at 3*id (this rank's triangles only; the others'
 * entries are left as they are, the bits of adding 0 to a sum that started at +0). */
int dem_shim_mesh_forces_add(void *mesh, double *sum);
/* The grain-wall contacts in the mesh's contact history (fix contacthistory/mesh): for each,
 * the grain's atom tag, the triangle id and the first three history values (the tangential
 * spring of `tangential history`), tag, tri [out] max, hist [out] 3 max. Returns how many
 * there are (may exceed max: only max are written), -1 if the mesh has no contact history.
 * Only after a run's set-up (before it, the history is not laid out per neighbour). */
int dem_shim_mesh_contacts(void *lmp, void *mesh, int max, int *tag, int *tri, double *hist);

#ifdef __cplusplus
}
#endif

#endif
