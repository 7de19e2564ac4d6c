/* fem_material.h - constitutive laws behind one interface.
 *
 * A law maps the deformation gradient F (row-major 3x3) at a quadrature point, with optional
 * history variables, to the first Piola-Kirchhoff stress P (3x3) and the tangent
 * A_iJkL = dP_iJ / dF_kL (81 entries, index [(3i+J)*9 + 3k+L]). A is general (not assumed
 * symmetric), so a non-associated plasticity law (Mohr-Coulomb, coming later) fits, and the
 * assembly then hands UMFPACK an unsymmetric tangent.
 *
 * Hyperelastic laws are split into an isochoric part W_iso(C_bar) (C_bar = J^-2/3 C) and a
 * volumetric part U(J) = (kappa/2)(J - 1)^2 for every law (the form CalculiX/Abaqus use for
 * D1 = 2/kappa, so peer comparisons use the same model; U'' = kappa > 0 for all J).
 * W_iso = C10 (I1b - 3) + C01 (I2b - 3) + C20 (I1b - 3)^2 + C30 (I1b - 3)^3 with
 * I1b = J^-2/3 tr C, I2b = J^-4/3 (tr^2 C - tr C^2)/2; each kind uses only its coefficients.
 * fem_material_eval_iso returns P and A of W_iso only; the element adds the volumetric part
 * through the mixed (mean-dilatation) formulation, which avoids volumetric locking.
 *
 * Laws: NEOHOOKE (C10 = mu/2), MOONEY_RIVLIN (C10, C01), YEOH (C10, C20, C30) for silicone;
 * stiff parts (reinforcement, strain-limiting layer): STIFF_NEOHOOKE = compressible
 * neo-Hookean with mu, kappa from E, nu (small-strain limit equals Hooke's law). */
#ifndef FEM_MATERIAL_H
#define FEM_MATERIAL_H

typedef enum {
  FEM_MAT_NEOHOOKE,
  FEM_MAT_MOONEY_RIVLIN,
  FEM_MAT_YEOH,
  FEM_MAT_STIFF_NEOHOOKE /* from E, nu */
} FemMaterialKind;

struct FemLaw;

typedef struct {
  /* A law object (fem_law.h) with its parameter values par; NULL for the built-in kinds below
   * (the fields kind, c10 ... c30 then select and parameterise the law). For a law of kind
   * FEM_LAW_ISOCHORIC, kappa (and mix_alpha) still define the mixed volumetric part; nhist is
   * the law's. */
  const struct FemLaw *law;
  double par[16];            /* FEM_LAW_MAX_PARAMS */
  FemMaterialKind kind;
  double c10, c01, c20, c30; /* [Pa] */
  double kappa;              /* bulk modulus [Pa] */
  double rho;                /* density [kg/m^3] */
  double mix_alpha;          /* mixed element: bulk modulus kept for the part of the volume
                                change that varies inside an element, kappa_s = min(kappa,
                                mix_alpha mu0); 0 selects FEM_MAT_MIX_ALPHA_DEFAULT, < 0 gives
                                kappa_s = 0 (pure mean dilatation); see fem_element.h */
  int nhist;                 /* history variables per quadrature point (0 for hyperelastic),
                                at most FEM_MAT_MAX_HIST */
  int tet10_composite;       /* 1: a tet10 of this region is the composite element (piecewise
                                linear over 8 sub-tets, fem_element.h); 0: quadratic. No
                                effect on tet4 */
} FemMaterial;

#define FEM_MAT_MAX_HIST 32
#define FEM_MAT_MIX_ALPHA_DEFAULT 4.0

/* Initial shear modulus mu0 = 2 (C10 + C01). */
double fem_material_mu0(const FemMaterial *m);
/* kappa_s = min(kappa, mix_alpha mu0) (see mix_alpha). */
double fem_material_kappa_fluct(const FemMaterial *m);
/* Build a stiff law from Young's modulus and Poisson's ratio. */
FemMaterial fem_material_from_e_nu(double E, double nu, double rho);

/* Material of the registered law `name` (fem_law.h) with nvals parameters given by names [in]
 * and values [in] (every parameter of the law exactly once) and density rho. The built-in laws
 * (neohooke, mooney_rivlin, yeoh, stiff_neohooke) give the built-in kinds, exactly the
 * materials built by hand; "kappa" sets the bulk modulus of an isochoric law. SA_ERR_INPUT
 * naming an unknown law or a missing/unknown parameter. */
int fem_material_from_law(const char *name, int nvals, const char *const *names,
                          const double *values, double rho, FemMaterial *out);

/* Validate parameters: SA_ERR_INPUT naming the bad one (mu0 <= 0, kappa <= 0, C10 <= 0 ...). */
int fem_material_check(const FemMaterial *m);
/* 1 when A is symmetric (A_iJkL = A_kLiJ: every hyperelastic law); the element then builds only
 * half of the tangent. A law with an unsymmetric A (non-associated plasticity) returns 0. */
int fem_material_symmetric(const FemMaterial *m);

/* Isochoric part: energy W_iso [out], P [out] 9, A [out] 81 (A may be NULL). hist_old [in] and
 * hist_new [out] have m->nhist entries (may be NULL when nhist == 0). Returns SA_ERR_INVERTED
 * when det F <= 0. */
int fem_material_eval_iso(const FemMaterial *m, const double F[9], const double *hist_old,
                          double *hist_new, double *W, double P[9], double A[81]);
/* Volumetric part U(J), U'(J), U''(J) [out] (each may be NULL). */
void fem_material_eval_vol(const FemMaterial *m, double J, double *U, double *dU, double *d2U);

#endif
