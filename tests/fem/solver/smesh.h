/* smesh.h - structured tetrahedral meshes for the solver tests (no Gmsh): one or more mapped
 * hexahedral blocks, each cell split into 6 tetrahedra (Kuhn split along the cell's main
 * diagonal, conforming between cells and between blocks whose shared index directions agree),
 * tet4 or tet10 with mid-nodes placed by the mapping (curved geometry is exact at the nodes).
 * Coincident nodes of different blocks are merged. Surfaces are the block sides given a name
 * (outward faces, the same convention as fem_mesh.h). */
#ifndef SMESH_H
#define SMESH_H

#include "fem_mesh.h"

typedef void (*SmeshMap)(const double xi[3], const void *ctx, double X[3]);

typedef struct {
  int n[3];             /* cells per direction */
  SmeshMap map;         /* [0,1]^3 -> reference coordinates */
  const void *ctx;
  const char *side[6];  /* surface names of sides xi0=0, xi0=1, xi1=0, xi1=1, xi2=0, xi2=1 */
} SmeshBlock;

/* order 1 (tet4) or 2 (tet10); merge_tol: nodes closer than this are one node. */
/* The slender bar 1 x 0.2 x 0.2 used by several tests (ctx unused). */
void smesh_map_bar(const double xi[3], const void *ctx, double X[3]);

int smesh_build(int nblocks, const SmeshBlock *blocks, int order, double merge_tol,
                FemMesh **out);
void smesh_free(FemMesh **m);

#endif
