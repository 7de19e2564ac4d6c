/* fem_coupling.h - a coupling surface: the part of a FEM boundary that another code (the
 * LIGGGHTS DEM) sees as a wall mesh of flat triangles, and the two maps between them.
 *
 * Geometry map (FEM -> wall): the wall vertices ARE the surface's FEM nodes (local numbering
 * 0..nverts-1, global FEM node nodes[i]); a tri6 face (corners 0..2, mid-nodes 3 = edge 01,
 * 4 = edge 12, 5 = edge 20) becomes four flat triangles (0,3,5) (3,1,4) (5,4,2) (3,4,5), a tri3
 * face one. Orientation is kept: the right-hand normal points out of the solid.
 *
 * Force map (wall -> FEM) = the transpose of the geometry map for a force applied at the
 * triangle's centroid: the centroid is the mean of the three vertices, so by virtual work
 * F . dx_c = sum_i (F / 3) . dx_i each vertex receives F / 3. The resultant is kept exactly and
 * the moment about any point equals that of F acting at the centroid (exact for a constant
 * traction on each flat triangle). Tested in tests/fem/solver/test_coupling_surface.c.
 *
 * Velocities: the change of position over the last coupling interval divided by its length,
 * (x_now - x_mark) / dt with x_mark recorded by fem_coupling_surface_mark (a static FEM solve
 * has no velocity of its own).
 *
 * No call after create allocates. */
#ifndef FEM_COUPLING_H
#define FEM_COUPLING_H

#include "fem_mesh.h"

typedef struct FemCouplingSurface FemCouplingSurface;

/* The coupling surface made of the named surfaces of m [borrowed, must outlive it] (their
 * union, each node once). *out [owned]. */
int fem_coupling_surface_create(const FemMesh *m, int nsurf, const char *const *surfaces,
                                FemCouplingSurface **out);
/* The same made of those faces whose nodes all lie below z_max (reference coordinates): a
 * wall whose top part another code takes as rigid (the FEM-DEM scene's [dem] rigid_band). */
int fem_coupling_surface_create_below(const FemMesh *m, int nsurf, const char *const *surfaces,
                                      double z_max, FemCouplingSurface **out);
int fem_coupling_surface_nverts(const FemCouplingSurface *c);
int fem_coupling_surface_ntri(const FemCouplingSurface *c);
/* [borrowed] 3 * ntri local vertex indices of the flat triangles. */
const int *fem_coupling_surface_triangles(const FemCouplingSurface *c);
/* [borrowed] nverts global FEM node numbers of the local vertices. */
const int *fem_coupling_surface_nodes(const FemCouplingSurface *c);
/* Wall vertex positions from FEM positions: x_fem [in] 3 * nnodes, xw [out] 3 * nverts. */
void fem_coupling_surface_gather(const FemCouplingSurface *c, const double *x_fem, double *xw);
/* Remember x_fem [in] as the start of a coupling interval. */
void fem_coupling_surface_mark(FemCouplingSurface *c, const double *x_fem);
/* Wall vertex velocities over the interval: vw [out] 3 * nverts = (x_fem - x_mark) / dt. */
void fem_coupling_surface_velocities(const FemCouplingSurface *c, const double *x_fem, double dt,
                                     double *vw);
/* Nodal forces from triangle forces: f_tri [in] 3 * ntri [N] -> f_node [out] 3 * nverts [N]
 * (local vertices; overwritten), F / 3 to each vertex of its triangle. */
void fem_coupling_surface_scatter(const FemCouplingSurface *c, const double *f_tri,
                                  double *f_node);
/* Area [m^2] and outward normal of triangle t at positions xw [in] 3 * nverts. */
double fem_coupling_surface_tri_area(const FemCouplingSurface *c, const double *xw, int t,
                                     double n[3]);
void fem_coupling_surface_destroy(FemCouplingSurface **c);

#endif
