/* hmsa_integrate.h - time integration of the HMSA model with SUNDIALS 6.4.
 *
 *   erk   ARKODE ERKStep, Dormand-Prince 5(4) (ARKODE_DORMAND_PRINCE_7_4_5)
 *   dirk  ARKODE ARKStep, implicit only, ARKODE_ARK548L2SA_DIRK_8_4_5 (default DIRK 5th order),
 *         dense SUNMatrix + SUNLinSol_Dense with the analytic Jacobian; dense output from
 *         ARKODE's Hermite interpolant, or its Lagrange interpolant where the Maxwell branch
 *         is stiff (relaxation rate > 50 x 2 pi/T_ref at the start state; see start_solver)
 *   bdf   CVODE BDF (order <= 5), dense linear solver with the analytic Jacobian
 *   auto  start with erk; switch to bdf at the current state when explicit steps collapse:
 *         50 consecutive steps with h < switch_ratio * T_ref while h is stability-bound
 *         (h * r_stiff >= 1, r_stiff = -d xi'/d xi the Maxwell relaxation rate), or more than
 *         switch_steps (20000) steps since reset at h < switch_ratio * T_ref when the model has a
 *         relaxation mode. T_ref = forcing period, or 2 pi/omega_u of the rest state for
 *         constant loading. The PC model never switches (no dissipative stiff mode; its small
 *         steps near the pole are needed for accuracy).
 * One SUNContext per integrator: an integrator must be used by one thread at a time.
 * Output at tout is taken from the integrator's dense output (interpolation), never from the
 * nearest step. The PC pole is a recoverable RHS failure (the step is shrunk); if the
 * integrator cannot get past it, advance returns SA_ERR_DOMAIN with a diagnosis. */
#ifndef HMSA_INTEGRATE_H
#define HMSA_INTEGRATE_H

#include "hmsa_model.h"

typedef enum {
  HMSA_METHOD_AUTO = 0,
  HMSA_METHOD_ERK = 1,
  HMSA_METHOD_DIRK = 2,
  HMSA_METHOD_BDF = 3
} HmsaMethod;

typedef struct {
  HmsaMethod method;
  double rtol, atol;
  long max_steps;      /* per advance call (0 = 1e7) */
  double switch_ratio; /* auto: h/T_ref below which explicit steps count as collapsed (1e-3) */
  long switch_steps;   /* auto: steps since reset at collapsed h that trigger a switch (20000) */
  double h_max;        /* 0 = none; cap on the step (e.g. a fraction of the forcing period) */
} HmsaIntegratorOptions;

typedef struct {
  long steps;          /* accepted steps */
  long attempts;       /* step attempts */
  long err_fails;      /* error-test failures */
  long conv_fails;     /* nonlinear-solver convergence failures (implicit) */
  long rhs_evals;      /* right-hand-side evaluations */
  long jac_evals;
  long nli;            /* nonlinear iterations */
  long domain_fails;   /* RHS calls rejected as outside the model's domain */
  int switched;        /* auto switched from erk to bdf */
  double switch_tau;   /* where */
  HmsaMethod active;   /* method in use now */
  double h_last;
} HmsaIntegratorStats;

typedef struct HmsaIntegrator HmsaIntegrator;

void hmsa_integrator_options_default(HmsaIntegratorOptions *o); /* auto, 1e-8, 1e-10 */
/* m [borrowed: must outlive the integrator; may be modified between reset calls, e.g. omega].
 * out [owned]. */
int hmsa_integrator_create(const HmsaModel *m, const HmsaIntegratorOptions *o,
                           HmsaIntegrator **out);
/* Restart at (tau0, y0) (statistics are kept; auto returns to erk). */
int hmsa_integrator_reset(HmsaIntegrator *it, double tau0, const double *y0);
/* Integrate to tout (> current time); y [out] n = state at tout from dense output.
 * 0, SA_ERR_DOMAIN (> 0, PC pole), SA_ERR_STEP_TOO_SMALL / SA_ERR_NOT_CONVERGED (> 0), or < 0. */
int hmsa_integrator_advance(HmsaIntegrator *it, double tout, double *y);
/* Current internal time (may be past the last tout). */
double hmsa_integrator_time(const HmsaIntegrator *it);
void hmsa_integrator_get_stats(const HmsaIntegrator *it, HmsaIntegratorStats *s);
void hmsa_integrator_destroy(HmsaIntegrator **it);
const char *hmsa_method_name(HmsaMethod m);

#endif
