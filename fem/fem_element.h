/* fem_element.h - total-Lagrangian element kernels.
 *
 * Solid elements: tet4 and tet10 with the mean-dilatation (F-bar / P2-P0 three-field) mixed
 * formulation, the pressure condensed at element level: the element energy is
 *   Pi_e = int_Ve W_iso(F) dV + V_e U(theta_e),   theta_e = (1/V_e) int_Ve det F dV,
 * a pure displacement functional whose gradient and Hessian are the internal force and a
 * consistent (symmetric for hyperelastic laws) tangent. Because the volume constraint is
 * enforced once per element instead of at every quadrature point, the element does not lock
 * for K/mu up to 1e4 (verified in tests/fem).
 *
 * Surface elements (tri3/tri6 faces, normal out of the solid): follower pressure and the
 * volume enclosed between a face and the origin (for cavity volume and volume control). */
#ifndef FEM_ELEMENT_H
#define FEM_ELEMENT_H

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
 * hist_new [out]: nqp * mat->nhist (NULL if nhist == 0). Returns SA_ERR_INVERTED (> 0) when
 * det F <= 0 at a quadrature point or theta <= 0. */
int fem_element_tl(FemElemType t, const double *X, const double *x, const FemMaterial *mat,
                   const double *hist_old, double *hist_new, int want_K, FemElemOut *out);
int fem_element_nqp(FemElemType t);

/* Element-averaged Cauchy stress sigma [out] 9 and principal stretches lam [out] 3
 * (descending), with the mixed formulation's volumetric part. */
int fem_element_stress(FemElemType t, const double *X, const double *x, const FemMaterial *mat,
                       const double *hist, double sigma[9], double lam[3]);

/* Lumped mass per node [out] nen (row-sum of the consistent mass, positive for tet10 by using
 * the HRZ scaling). */
void fem_element_lumped_mass(FemElemType t, const double *X, double rho, double *m);

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
