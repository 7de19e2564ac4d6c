/* hmsa_model.h - reduced-order model of a planar hard-magnetic soft actuator (HMSA),
 * dimensionless form of /work/shared/hmsa/MODEL.md (section 5), statics and linearisation
 * (section 6). Pure functions, no SUNDIALS, thread-safe (no global state).
 *
 * State y: Zener  (lambda, lambda', xi)      n = 3
 *          PC     (lambda, lambda')          n = 2
 *   (1 + 2 c l^-6) l'' - 6 c l^-7 l'^2 + 3 F = 0                          (E1)
 *   xi' = k (l^2 xi^-3 - l^-4 xi^3),  k = 2 beta / eta_bar   (Zener)      (E2)
 *   Zener: F = (l - l^-5) + beta (l xi^-2 - l^-5 xi^4) - S + b2(tau) l^-3
 *   PC:    F = m_c (l - l^-5)[1/3 + 2 lm^2/(3 lm^2 - I1)] + m_e (1 + l - l^-2 - l^-3)
 *              - S + b2(tau) l^-3,        I1 = 2 l^2 + l^-4 < 3 lm^2
 * Loading b2(tau): const b2; sq: sgn b_a^2 sin^2(Omega tau); lin: b2_dc + b2_ac sin(Omega tau). */
#ifndef HMSA_MODEL_H
#define HMSA_MODEL_H

typedef enum { HMSA_ZENER = 0, HMSA_PC = 1 } HmsaModelKind;
typedef enum { HMSA_LOAD_CONST = 0, HMSA_LOAD_SQ = 1, HMSA_LOAD_LIN = 2 } HmsaLoading;

#define HMSA_NEQ_MAX 3
#define HMSA_PI 3.14159265358979323846

typedef struct {
  HmsaModelKind model;
  double c;          /* H^2/L^2 */
  double beta;       /* Maxwell/equilibrium modulus ratio (Zener) */
  double eta_bar;    /* dimensionless viscosity (Zener) */
  double S;          /* prestress sigma/mu */
  double mu_c, mu_e; /* m_c, m_e (PC) */
  double lambda_max; /* chain extensibility (PC), > 1 */
  HmsaLoading loading;
  double b2;         /* constant load (loading = const) */
  double b_a, sgn;   /* sq: b2 = sgn b_a^2 sin^2(omega tau) */
  double omega;      /* forcing frequency Omega (sq, lin) */
  double b2_dc, b2_ac; /* lin */
} HmsaModel;

/* Defaults: Zener, c = 1, beta = 2, eta_bar = 50, S = 0, const b2 = 0.16, b_a = 0.4, sgn = +1,
 * omega = 2.13, m_c = 1, m_e = 0, lambda_max = 2. */
void hmsa_model_default(HmsaModel *m);
int hmsa_model_neq(const HmsaModel *m);
/* Load at time tau. */
double hmsa_model_b2(const HmsaModel *m, double tau);
/* Mean of b2(tau) over a period (the static part of the load). */
double hmsa_model_b2_mean(const HmsaModel *m);
/* Forcing period 2 pi/omega for periodic loading, 0 for const. */
double hmsa_model_period(const HmsaModel *m);
/* Rest state (1, 0, 1). y [out] n. */
void hmsa_model_rest(const HmsaModel *m, double *y);

/* Generalised force F(lambda, xi; b2) and its partials (any of the outputs may be NULL).
 * Returns 0, or SA_ERR_DOMAIN (> 0, recoverable) when the PC model has I1 >= 3 lm^2 or
 * lambda/xi <= 0; outputs are then untouched (never NaN). */
int hmsa_model_force(const HmsaModel *m, double lambda, double xi, double b2, double *F,
                     double *dF_dl, double *dF_dxi);
/* ydot [out] = f(tau, y). 0, or SA_ERR_DOMAIN (recoverable) outside the model's domain. */
int hmsa_model_rhs(const HmsaModel *m, double tau, const double *y, double *ydot);
/* J [out] n x n row-major, J[i*n+j] = d f_i / d y_j (analytic). */
int hmsa_model_jacobian(const HmsaModel *m, double tau, const double *y, double *J);
/* Dimensionless energies at load b2: kinetic T/(mu V) = (1/3)(1+2c l^-6) l'^2 and potential
 * U = W/mu of section 5 (W0 chosen so U(rest, b2=0, S=0) = 0 for PC). */
int hmsa_model_energy(const HmsaModel *m, const double *y, double b2, double *T, double *U);
/* Zener dissipation rate eta_bar (xi')^2 = (2 beta/k)(xi')^2 (0 for PC). */
double hmsa_model_dissipation(const HmsaModel *m, const double *y, double b2);

/* lambda3 = lambda^-2 and dlambda3/dtau = -2 lambda^-3 lambda'. */
double hmsa_lambda3(const double *y);
double hmsa_dlambda3(const double *y);

/* PC domain: (lo, hi) with I1(lambda) < 3 lm^2 on lo < lambda < hi. */
int hmsa_model_pc_domain(const HmsaModel *m, double *lo, double *hi);

/* ---- statics and linearisation (section 6) ---- */
typedef struct {
  double lambda, lambda3;
  double K_r, K_u;        /* relaxed and instantaneous stiffness dF/dlambda */
  int stable;             /* K_r > 0 (and not a limit point) */
  int limit_point;        /* double root of F_r: K_r = 0 within rounding (a limit point of the
                             prestress path; marginal, reported as not stable) */
  double omega_r, omega_u; /* sqrt(3 K/M0) (NaN-free: 0 when K <= 0) */
  double omega_d, zeta;   /* damped frequency and damping ratio from the cubic (Zener);
                             PC: omega_d = omega_r, zeta = 0 */
  double decay, creep;    /* -Re of the complex pair, creep (real-root) rate */
} HmsaEquilibrium;

#define HMSA_MAX_ROOTS 8

/* Relaxed force F_r(lambda) (xi = lambda for Zener) and K_r = dF_r/dlambda at load b2. */
int hmsa_static_force(const HmsaModel *m, double lambda, double b2, double *F, double *K);
/* Every root of F_r(lambda; b2) = 0 on lambda in (1e-3, 1e3) (PC: inside the domain), with
 * stability and frequencies: the zeros of dF_r/dlambda are bracketed on a fine grid and
 * bisected; between them F_r is monotone and each sign change is one root (bisection to
 * machine precision, however close two roots lie); a zero of dF_r/dlambda where F_r vanishes
 * within rounding is a double root, returned once with limit_point = 1. eq [out] capacity
 * HMSA_MAX_ROOTS, sorted by lambda. */
int hmsa_static_solve(const HmsaModel *m, double b2, HmsaEquilibrium *eq, int *nroots);
/* Linearisation about the relaxed equilibrium lambda0 (fills every field of *eq). */
int hmsa_linearise(const HmsaModel *m, double lambda0, double b2, HmsaEquilibrium *eq);
/* Limit points of the prestress path at load b2: lambda where K_r = 0, with the prestress S
 * at which the relaxed equilibrium passes it (S_lp = F_r + S evaluated there). lambda_lp, S_lp
 * [out] capacity HMSA_MAX_ROOTS. */
int hmsa_static_limit_points(const HmsaModel *m, double b2, double *lambda_lp, double *S_lp,
                             int *n);

#endif
