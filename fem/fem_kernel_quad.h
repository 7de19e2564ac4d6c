/* fem_kernel_quad.h - private: quadrature rules and shape functions of the element kernels.
 *
 * Reference tetrahedron: barycentric L = (1 - r - s - t, r, s, t), volume 1/6. VTK node order:
 * corners 0..3, then mid-nodes of edges 01, 12, 02, 03, 13, 23 (tet10: N_corner = L(2L - 1),
 * N_edge(ij) = 4 Li Lj). Reference triangle: L = (1 - r - s, r, s), area 1/2; tri6 mid-nodes of
 * edges 01, 12, 20.
 *
 * Rules (barycentric points, weights already scaled to the reference measure):
 *  - tet 1-point (degree 1): tet4 (F is constant).
 *  - tet 4-point (degree 2, weights 1/24): default for straight-sided tet10. With affine
 *    geometry the integrand of the small-strain stiffness B^T C B is quadratic, so this rule is
 *    exact there; the deviatoric strain (linear in X) is fixed by its values at 4 points, so the
 *    rule has exactly the rank of exact integration (no extra zero-energy modes), and
 *    int grad N dV is exact (patch test passed).
 *  - tet 8-point (degree 3, positive weights, derived in fem_kernel_quad.c): curved tet10
 *    (mid-nodes off the edge midpoints), where grad N det J0 is cubic, so the patch test needs
 *    degree >= 3 (the 4-point rule leaves interior forces of 2 % of the boundary forces on a
 *    patch with mid-nodes moved by 4 % of the edge length).
 *  - tet 14-point (degree 5, positive weights; Walkington 2014): the consistent-mass diagonal
 *    (degree 4) of the HRZ lumping.
 *  - triangle 3-point (degree 2) for tri3 and 6-point (degree 4, Strang-Fix/Dunavant) for tri6:
 *    N_a (x,r x x,s) and x.(x,r x x,s) are degree 4 on a tri6, so face forces, load stiffness
 *    and face volumes are integrated exactly. */
#ifndef FEM_KERNEL_QUAD_H
#define FEM_KERNEL_QUAD_H

#define FEM_KQ_MAX_QP 14

typedef struct {
  int n;
  double L[FEM_KQ_MAX_QP][4]; /* barycentric coordinates */
  double w[FEM_KQ_MAX_QP];    /* weights (sum = reference volume or area) */
} FemKqRule;

extern const FemKqRule fem_kq_tet1, fem_kq_tet4, fem_kq_tet8, fem_kq_tet14, fem_kq_tri3,
    fem_kq_tri6;

/* Tet shape functions N [out] nen (may be NULL) and derivatives dN [out] nen x 3 (d/dr, d/ds,
 * d/dt) at barycentric L [in]; nen = 4 or 10. */
void fem_kq_tet_shape(int nen, const double L[4], double *N, double (*dN)[3]);
/* Triangle shape functions, nfn = 3 or 6, dN = d/dr, d/ds. */
void fem_kq_tri_shape(int nfn, const double L[3], double *N, double (*dN)[2]);
/* 1 when a tet10 has a mid-node off its edge midpoint by more than 1e-10 of the edge length. */
int fem_kq_tet10_curved(const double *X);

#endif
