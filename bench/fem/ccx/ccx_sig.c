/* ccx_sig.c - a mesh signature, printed by ccx_export and ccx_ours to prove that CalculiX and our
 * solver were handed the same mesh: sum over nodes of (i + 1) (x + 2 y + 3 z) plus the sum over
 * elements of (e + 1) * (sum of node indices) * 1e-9 (any renumbering or moved node changes it). */
#include "fem_mesh.h"

double ccx_mesh_signature(const FemMesh *m);

double ccx_mesh_signature(const FemMesh *m)
{
  double s = 0;
  for (int i = 0; i < m->nnodes; ++i)
    s += (i + 1.0) * (m->xyz[3 * i] + 2 * m->xyz[3 * i + 1] + 3 * m->xyz[3 * i + 2]);
  for (int e = 0; e < m->nelem; ++e) {
    double c = 0;
    for (int k = 0; k < m->nen; ++k) c += m->conn[(size_t)m->nen * e + k];
    s += (e + 1.0) * c * 1e-9;
  }
  return s;
}
