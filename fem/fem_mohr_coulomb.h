/* fem_mohr_coulomb.h - Mohr-Coulomb finite-strain elastoplasticity at one material point: a pure
 * kernel (no allocation, no global state besides the error trace) that a FEM can wrap, in the
 * shape of a libCEED QFunction: F and history in, P, tangent and new history out.
 *
 * Model (de Souza Neto, Peric & Owen, Computational Methods for Plasticity, 2008, sections 8.2
 * and 14): F = Fe Fp, Hencky elastic strain eps_e = ln(Ve) = (1/2) ln(b_e), Kirchhoff stress
 * tau = lambda tr(eps_e) 1 + 2 G eps_e (Young, Poisson), perfectly plastic Mohr-Coulomb yield
 * surface and a Mohr-Coulomb plastic potential with dilation angle psi <= phi (non-associated
 * when psi < phi), return mapping in principal Kirchhoff stress (plane, two edges, apex). The
 * exponential-map update makes the small-strain principal return exact in log strains.
 * docs/mohr_coulomb.md has the equations, the algorithm and the verification.
 *
 * Sign convention: TENSION POSITIVE everywhere in this kernel. Principal values are ordered
 * s1 >= s2 >= s3, so s3 is the most compressive. Yield function and flow potential:
 *   f   = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi)
 *   psi = (s1 - s3) + (s1 + s3) sin(psi)
 * Apex (phi > 0): s1 = s2 = s3 = c cot(phi) (the origin when c = 0).
 * Edges: LEFT = triaxial compression edge s1 = s2 > s3; RIGHT = triaxial extension edge
 * s1 > s2 = s3.
 *
 * Units: stresses and moduli in Pa (any consistent unit works), angles in radians.
 *
 * Return codes: 0 ok; SA_ERR_INPUT (< 0) bad parameters or initial stress; recoverable (> 0):
 * SA_ERR_INVERTED when det F <= 0, SA_ERR_DOMAIN for non-finite input or a non-positive-definite
 * trial b_e (corrupt history), SA_ERR_NOT_CONVERGED when no return (plane, edge, apex) lands on
 * an admissible state (only conceivable for phi = 0, which has no apex; never observed). */
#ifndef FEM_MOHR_COULOMB_H
#define FEM_MOHR_COULOMB_H

typedef struct {
  double young;   /* Young's modulus E [Pa], > 0 */
  double poisson; /* Poisson's ratio nu [-], -1 < nu < 0.5 */
  double phi;     /* friction angle [rad], 0 <= phi < pi/2 */
  double c;       /* cohesion [Pa], >= 0 (> 0 when phi = 0) */
  double psi;     /* dilation angle [rad], 0 <= psi <= phi */
  double apex_stiffness; /* [-] in [0, 1]: tangent at the apex = this times the elastic one
                            instead of the consistent zero (0, the default of a zero-initialised
                            struct: consistent). The stress is the apex's either way; a
                            cohesionless fill at near-zero stress returns there, and a zero
                            tangent leaves its nodes without stiffness (docs/mohr_coulomb.md) */
  double tau_over_dt; /* [-] >= 0, Duvaut-Lions viscoplasticity of this evaluation: the
                         relaxation time over the time step, w = tau / dt. The stress, the
                         plastic strain increment and the tangent are (inviscid + w elastic
                         trial) / (1 + w): the overstress relaxes as exp(-t / tau) (Simo and
                         Hughes, Computational Inelasticity, 1998, section 2.7). 0 (the default
                         of a zero-initialised struct): rate-independent */
} FemMohrCoulomb;

/* Region of the return mapping. */
typedef enum {
  FEM_MC_ELASTIC = 0,
  FEM_MC_PLANE = 1,      /* one active plane (s1 > s2 > s3) */
  FEM_MC_EDGE_RIGHT = 2, /* triaxial extension edge s1 > s2 = s3 (planes 13 and 12) */
  FEM_MC_EDGE_LEFT = 3,  /* triaxial compression edge s1 = s2 > s3 (planes 13 and 23) */
  FEM_MC_APEX = 4        /* hydrostatic apex c cot(phi) */
} FemMcRegion;

/* History per material point, FEM_MC_NHIST doubles:
 *   [0..5] C_p^-1 = Fp^-1 Fp^-T (inverse plastic right Cauchy-Green tensor, Lagrangian, so
 *          b_e = F C_p^-1 F^T needs no previous F), Voigt order xx, yy, zz, yz, xz, xy;
 *   [6]    equivalent plastic strain, sum of sqrt(2/3 |d eps_p|^2) over the steps [-];
 *   [7]    region (FemMcRegion) of the last return, as a double (output for plots, never read).
 * A virgin, stress-free point has C_p^-1 = I (fem_mc_hist_init with tau0 = NULL). */
#define FEM_MC_NHIST 8

/* Extra outputs of the principal return. */
typedef struct {
  FemMcRegion region;
  double dgamma[2]; /* plastic multipliers: [0] main plane 13, [1] second plane of an edge (12
                       for RIGHT, 23 for LEFT); both 0 in ELASTIC and APEX */
  double deps_p[3]; /* plastic strain increment, principal, same order as the input; in PLANE and
                       EDGE equal to dgamma[0] n_13 + dgamma[1] n_b with n the flow vectors;
                       at the APEX eps_trial - eps_e(apex) */
} FemMcReturn;

/* Validate parameters; SA_ERR_INPUT with a message naming the parameter and its range. */
int fem_mc_check(const FemMohrCoulomb *p);

/* 1 when the consistent tangent is symmetric (associated flow, psi == phi), else 0. */
int fem_mc_symmetric(const FemMohrCoulomb *p);

/* Small-strain return mapping in principal stresses (the core, also the finite-strain one in
 * principal log strains). eps_trial [in] 3 trial elastic principal strains (any order);
 * sig [out] 3 principal stresses (same order); D [out] 9 (row-major 3x3, may be NULL)
 * consistent tangent d sig / d eps_trial (unsymmetric when psi < phi); info [out] (may be NULL).
 * Parameters are not re-validated here (call fem_mc_check once). */
int fem_mc_return_principal(const FemMohrCoulomb *p, const double eps_trial[3], double sig[3],
                            double D[9], FemMcReturn *info);

/* Finite-strain law. F [in] 9 row-major; hist_n [in] FEM_MC_NHIST (NULL: virgin point);
 * hist_new [out] FEM_MC_NHIST (may be NULL, may not alias hist_n); P [out] 9 first
 * Piola-Kirchhoff stress; A [out] 81 (may be NULL) consistent tangent A_iJkL = dP_iJ/dF_kL at
 * index (3i+J)*9 + 3k+L, history held at hist_n; tau [out] 9 Kirchhoff stress (may be NULL). */
int fem_mc_eval(const FemMohrCoulomb *p, const double F[9], const double *hist_n,
                double *hist_new, double P[9], double A[81], double tau[9]);

/* Initialisation hook: history [out] FEM_MC_NHIST of a point that carries the initial
 * Kirchhoff stress tau0 [in] 6 (Voigt xx, yy, zz, yz, xz, xy; NULL: stress-free) at F = I,
 * through the initial elastic strain eps_e0 = D^-1 tau0 (C_p^-1 = exp(2 eps_e0)). tau0 must be
 * admissible (f <= 0 up to 1e-12 relative), else SA_ERR_INPUT. Geostatic K0 state with vertical
 * axis z and vertical stress sv < 0: tau0 = {K0 sv, K0 sv, sv, 0, 0, 0}, K0 = 1 - sin(phi). */
int fem_mc_hist_init(const FemMohrCoulomb *p, const double tau0[6], double hist[FEM_MC_NHIST]);
/* The same at deformation gradient F [in] (row-major, det F > 0): the point carries the
 * Kirchhoff stress tau0 at F (C_p^-1 = F^-1 b_e F^-T); hist [in/out] keeps its equivalent plastic
 * strain hist[6]. The stress of a settled state replaced in place (a K0 procedure). */
int fem_mc_hist_init_at(const FemMohrCoulomb *p, const double F[9], const double tau0[6],
                        double hist[FEM_MC_NHIST]);

/* The kernel as a law object (fem_law.h), found by fem_law_find("mohr_coulomb"): parameters
 * young [Pa], poisson [-], friction_angle [deg], cohesion [Pa], dilation_angle [deg] and the
 * optional apex_stiffness [-] (default 0) and relaxation_time [s] (default 0; > 0: Duvaut-Lions
 * with tau_over_dt = relaxation_time / FemLawCtx.dt, rate-independent where dt = 0); kind
 * FEM_LAW_FULL; FEM_MC_NHIST history values starting stress-free (C_p^-1 = I); a return that
 * finds no admissible state is SA_ERR_DOMAIN (recoverable); symmetric (symmetric_par) exactly
 * when dilation_angle == friction_angle, else the solver factorises with UMFPACK. */
struct FemLaw;
extern const struct FemLaw fem_law_mohr_coulomb;

#endif
