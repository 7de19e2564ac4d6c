/* smesh.c - the solver tests' structured meshes: fem_mesh_blocks (fem/fem_mesh_block.c) under
 * the names the tests use, and the bar every cantilever test shares. */
#include "smesh.h"

int smesh_build(int nblocks, const SmeshBlock *blocks, int order, double merge_tol,
                FemMesh **out) {
  return fem_mesh_blocks(nblocks, blocks, order, merge_tol, out);
}

void smesh_free(FemMesh **pm) { fem_mesh_destroy(pm); }

void smesh_map_bar(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  X[0] = xi[0];
  X[1] = 0.2 * xi[1];
  X[2] = 0.2 * xi[2];
}
