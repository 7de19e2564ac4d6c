/* smesh.h - structured tetrahedral meshes for the solver tests (no Gmsh; fem_mesh_blocks): one or more mapped
 * hexahedral blocks, each cell split into 6 tetrahedra (Kuhn split along the cell's main
 * diagonal, conforming between cells and between blocks whose shared index directions agree),
 * tet4 or tet10 with mid-nodes placed by the mapping (curved geometry is exact at the nodes).
 * Coincident nodes of different blocks are merged. Surfaces are the block sides given a name
 * (outward faces, the same convention as fem_mesh.h). */
#ifndef SMESH_H
#define SMESH_H

#include "fem_mesh.h"

/* The mesher itself is fem_mesh_blocks (fem_mesh.h); these are its test-side names. */
typedef FemMeshMap SmeshMap;
typedef FemMeshBlock SmeshBlock;

/* order 1 (tet4) or 2 (tet10); merge_tol: nodes closer than this are one node. */
/* The slender bar 1 x 0.2 x 0.2 used by several tests (ctx unused). */
void smesh_map_bar(const double xi[3], const void *ctx, double X[3]);

int smesh_build(int nblocks, const SmeshBlock *blocks, int order, double merge_tol,
                FemMesh **out);
void smesh_free(FemMesh **m);

#endif
