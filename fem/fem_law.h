/* fem_law.h - constitutive laws as objects (the open shape of libCEED's QFunctions / MOOSE's
 * material objects): a law declares its parameters, its history variables and their
 * initialisation, whether its tangent is symmetric, and its kind; its evaluation gets a context
 * (time, time step, element, quadrature point, per-element data such as a magnetisation vector)
 * and may fail recoverably. Laws are registered by name (fem_law_register, also from outside
 * fem/, e.g. a test) and a region's material is a law plus its parameter values
 * (fem_material_from_law), chosen in the case file (fem_actuator.h).
 *
 * Kinds (the element formulation follows from it, fem_element.h):
 *  - FEM_LAW_ISOCHORIC: eval returns the isochoric part W_iso(C_bar) and its P, A; the element
 *    adds the volumetric U(J) = (kappa/2)(J - 1)^2 through the mean-dilatation mixed
 *    formulation (near-incompressible rubbers). The parameter named "kappa" is the bulk
 *    modulus and mu0() the initial shear modulus (for the stabilisation kappa_s).
 *  - FEM_LAW_FULL: eval returns the full first Piola-Kirchhoff stress P (pressure included) and
 *    A = dP/dF; the element is the displacement formulation (compressible and plastic laws
 *    with their own pressure and dilatant flow).
 *
 * eval: F [in] row-major 3x3; hist_old [in] / hist_new [out] nhist values (NULL if 0); W [out]
 * energy density (or 0 for a non-potential law), P [out] 9, A [out] 81 as in fem_material.h
 * (may be NULL: residual only). Returns 0, SA_ERR_INVERTED for det F <= 0, SA_ERR_DOMAIN (> 0,
 * recoverable: the Newton line search backtracks, then the step is cut) for a state the law
 * cannot evaluate (e.g. a return mapping that did not converge). Must be thread-safe and must
 * not allocate. */
#ifndef FEM_LAW_H
#define FEM_LAW_H

#define FEM_LAW_MAX_PARAMS 16

typedef enum { FEM_LAW_ISOCHORIC = 0, FEM_LAW_FULL = 1 } FemLawKind;

typedef struct {
  double time, dt;         /* [s] of the state being evaluated (dt = 0 in a static substep) */
  int elem, qp;            /* element and quadrature point (-1 when unknown) */
  const double *elem_data; /* this element's data (fem_solver_set_element_data) or NULL */
} FemLawCtx;

typedef struct FemLaw {
  const char *name;
  int nparams;
  const char *const *param_names; /* nparams names, e.g. {"c10", "kappa"} */
  int nhist;                      /* history variables per quadrature point */
  int symmetric;                  /* A_iJkL = A_kLiJ (the element then builds half the tangent) */
  FemLawKind kind;
  /* history at the start (NULL: zeros); par [in] nparams, hist [out] nhist */
  void (*init_hist)(const double *par, double *hist);
  int (*eval)(const double *par, const FemLawCtx *ctx, const double F[9], const double *hist_old,
              double *hist_new, double *W, double P[9], double A[81]);
  /* parameter check (NULL: none): SA_ERR_INPUT naming the bad parameter */
  int (*check)(const double *par);
  /* initial shear modulus (ISOCHORIC kind: the mixed element's stabilisation) */
  double (*mu0)(const double *par);
  /* symmetry that depends on the parameters (NULL: the flag `symmetric` holds for all): 1 when
   * the tangent is symmetric for these parameters (Mohr-Coulomb: associated flow). The linear
   * solver follows it: a model with a region whose law says 0 is factorised by UMFPACK LU
   * without trying CHOLMOD (fem_newton.c). */
  int (*symmetric_par)(const double *par);
  /* nparams defaults (NULL: every parameter must be given; NAN: this one must): a parameter
   * left out of a law entry takes its default (Mohr-Coulomb's apex_stiffness, 0) */
  const double *param_defaults;
} FemLaw;

/* Register law [borrowed: must outlive every use] under law->name; SA_ERR_INPUT if the name is
 * taken by another law or the descriptor is incomplete. */
int fem_law_register(const FemLaw *law);
/* The law registered under name, or NULL. The built-in laws are always there: neohooke
 * (c10, kappa), mooney_rivlin (c10, c01, kappa), yeoh (c10, c20, c30, kappa),
 * stiff_neohooke (e, nu) - the kernels of fem_material.h behind the law interface - and
 * mohr_coulomb (young, poisson, friction_angle, cohesion, dilation_angle; fem_mohr_coulomb.h). */
const FemLaw *fem_law_find(const char *name);
/* Index of parameter name in law, or -1. */
int fem_law_param(const FemLaw *law, const char *name);
/* "a, b, c" of the registered names into buf. */
void fem_law_list(char *buf, int n);

#endif
