/* fem_element.h - total-Lagrangian element kernels.
 *
 * Solid elements: tet4 and tet10 with the mean-dilatation (F-bar / P2-P0 three-field) mixed
 * formulation, the pressure condensed at element level: the element energy is
 *   Pi_e = int_Ve [W_iso(F) + (kappa_s/2)(J - theta_e)^2] dV + V_e U(theta_e),
 *   theta_e = (1/V_e) int_Ve det F dV,
 * a pure displacement functional whose gradient and Hessian are the internal force and a
 * consistent (symmetric for hyperelastic laws) tangent. The mean volume change is penalised with
 * the full bulk modulus once per element (so the element does not lock, verified for K/mu up to
 * 1e4), the part of J varying inside the element with kappa_s = min(kappa, mix_alpha mu0)
 * (fem_material.h; default mix_alpha = 4). Why kappa_s: with kappa_s = 0 (plain P2-P0) every
 * tet10 has three zero-energy modes (u = 2 (a.X) X - |X|^2 a: no deviatoric strain, zero mean
 * dilatation) that a mesh with one or two elements through a wall restrains only weakly: a
 * one-layer cantilever came out 47 % (K/mu = 1000) to 59 % (nu = 0.3) too soft; with
 * kappa_s = 4 mu0 it is within 1.7 % of the converged answer, and K/mu = 1e4 still does not lock
 * (tests/fem/kernels/test_fem_locking.c). Because U(J) = (kappa/2)(J - 1)^2 is quadratic,
 * kappa_s = kappa gives exactly the displacement element: compressible laws (the stiff parts,
 * kappa = 2.2 mu) get it automatically.
 * A region whose law (fem_law.h) is of kind FEM_LAW_FULL has kappa = kappa_s = 0 here: the
 * law's own P (pressure included) in the displacement formulation.
 * Quadrature: tet4 1 point; straight-sided tet10 4 points (degree 2); curved tet10 (a mid-node
 * off its edge midpoint) 8 points (degree 3), because grad N det J0 is then cubic and the
 * 4-point rule would fail the patch test (see fem_kernel_quad.h).
 *
 * Composite tet10 (FemMaterial.tet10_composite; the idea of Abaqus's C3D10M): the same 10
 * nodes, but the interpolation (of X and of x) is piecewise LINEAR over 8 sub-tets: the 4
 * corner tets and the inner octahedron split along the diagonal mid-node 02 - mid-node 13
 * (composite_sub in fem_element.c). F is constant in each sub-tet, so quadrature point q is
 * sub-tet q (weight its volume; 8 points = fem_element_nqp(FEM_TET10), the history stride).
 * Each face is then 4 flat sub-triangles with linear functions, whose consistent load under a
 * uniform pressure is exactly the node-to-surface contact's lumped slave areas (corners A/12,
 * mid-nodes A/4), unlike the quadratic face's (corners 0, mid-nodes A/3): a composite body
 * passes the contact patch test with the default weights (docs/mohr_coulomb.md). It is a
 * displacement element in substance (linear sub-tets): meant for compressible regions (the
 * Mohr-Coulomb fill, nu = 0.3), not the near-incompressible silicone, which would lock; the
 * mixed terms above apply to it unchanged (theta over the whole element). Mid-nodes off
 * their edge midpoints only bend the sub-tets' faces into planes through them.
 *
 * Surface elements (tri3/tri6 faces, normal out of the solid): follower pressure and the
 * volume enclosed between a face and the origin (for cavity volume and volume control). */
#ifndef FEM_ELEMENT_H
#define FEM_ELEMENT_H

#include "fem_law.h"
#include "fem_material.h"
#include "fem_mesh.h"

/* Element kernel output. Arrays sized for nen = 10: 30 dofs. */
typedef struct {
  double energy;   /* Pi_e [J] */
  double fe[30];   /* internal force dPi/du, node-major (x,y,z per node) */
  double Ke[900];  /* tangent d2Pi/du2, row-major (ndof x ndof), filled if want_K */
  double theta;    /* element volume ratio v/V */
  double min_detF; /* smallest det F at the quadrature points */
} FemElemOut;

/* X [in] 3*nen reference coordinates, x [in] 3*nen current coordinates. hist_old [in],
 * hist_new [out]: fem_element_nqp(t) * mat->nhist per element, quadrature point q at
 * q * nhist (NULL if nhist == 0). out [out]: energy, fe, theta, min_detF always, Ke if want_K
 * (for a law whose fem_material_symmetric() is 0 every block is computed, not mirrored).
 * Returns SA_ERR_INVERTED (> 0) when det F <= 0 at a quadrature point or theta <= 0,
 * SA_ERR_INPUT for a degenerate reference element. Thread-safe, allocation-free. */
int fem_element_tl(FemElemType t, const double *X, const double *x, const FemMaterial *mat,
                   const double *hist_old, double *hist_new, int want_K, FemElemOut *out);
/* The same with the law context ctx [in] (time, time step, element, per-element data; the
 * quadrature point is filled in here; NULL: zeros). */
int fem_element_tl_ctx(FemElemType t, const double *X, const double *x, const FemMaterial *mat,
                       const FemLawCtx *ctx, const double *hist_old, double *hist_new,
                       int want_K, FemElemOut *out);
/* Quadrature points per element to allocate history for (the stride of hist_old/hist_new per
 * element): 1 for tet4, 8 for tet10 (straight-sided tet10 use only the first 4). */
int fem_element_nqp(FemElemType t);
/* Quadrature points an element with reference coordinates X [in] and material mat [in, may
 * be NULL: quadratic tet10] actually uses (1, 4 or 8; 8 for a composite tet10). */
int fem_element_nqp_used(FemElemType t, const double *X, const FemMaterial *mat);

/* Element-averaged Cauchy stress sigma [out] 9 (current-volume average, (1/v) int sigma dv,
 * including the mixed formulation's pressure) and principal stretches lam [out] 3 (descending)
 * of the volume-averaged F rescaled to det = theta. hist [in]: converged history (NULL if
 * nhist == 0). Returns SA_ERR_INVERTED for det F <= 0. */
int fem_element_stress(FemElemType t, const double *X, const double *x, const FemMaterial *mat,
                       const double *hist, double sigma[9], double lam[3]);

/* Lumped mass per node [out] nen (zeros for a degenerate element): tet4 rho V/4; tet10 HRZ (consistent-mass diagonal scaled to
 * the element mass; straight tet10: rho V/36 per corner, 4 rho V/27 per mid-node; all positive,
 * unlike the row sum, which is negative at the corners). */
void fem_element_lumped_mass(FemElemType t, const double *X, double rho, double *m);
/* The same for an element of material mat [in] (density mat->rho): a composite tet10 gets
 * each sub-tet's mass rho V_q / 4 at each of its 4 nodes (all positive, sum rho V; straight:
 * rho V/32 per corner, rho V/8 per mid-node, 3 rho V/16 at the two on the octahedron's
 * diagonal); otherwise fem_element_lumped_mass. */
void fem_element_lumped_mass_mat(FemElemType t, const double *X, const FemMaterial *mat,
                                 double *m);

/* Follower pressure p on one face in the current configuration x [in] 3*nfn (normal out of the
 * solid): the external force on the solid is f = -p int N n da. fe [out] 3*nfn receives f;
 * Ke [out] (3nfn)^2 receives -df/dx (the load stiffness to ADD to the tangent; unsymmetric per
 * face, symmetric after assembly over a closed surface or one whose rim is fixed). Ke may be NULL. */
void fem_face_pressure(int nfn, const double *x, double p, double *fe, double *Ke);
/* Volume between the face and the origin, -(1/3) int x.n da with n out of the solid (so the
 * faces of a cavity wall sum to the cavity volume when the cavity is closed, or closed by a
 * plane through the origin). dv [out] 3*nfn gradient, d2v [out] Hessian (may be NULL). */
double fem_face_volume(int nfn, const double *x, double *dv, double *d2v);

#endif
