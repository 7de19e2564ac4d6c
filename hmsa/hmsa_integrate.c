/* hmsa_integrate.c - SUNDIALS 6.4 drivers for the HMSA model (see hmsa_integrate.h).
 *
 * Every method is driven one step at a time (ARK_ONE_STEP / CV_ONE_STEP) so that
 *  - the output at tout comes from the integrator's own dense output (ERKStepGetDky,
 *    ARKStepGetDky, CVodeGetDky) inside the step that covers tout;
 *  - the last accepted state is known: ERKStep 6.4 treats a recoverable RHS failure inside a
 *    stage as unrecoverable (ARK_UNREC_RHSFUNC_ERR), so a stage beyond the PC pole is handled
 *    here by restarting from the last accepted state with a quarter of the step;
 *  - auto can watch the explicit step size and switch to BDF at an accepted state. */
#include "hmsa_integrate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "sa_error.h"
#include "sa_output.h"

struct HmsaIntegrator {
  const HmsaModel *m;
  HmsaIntegratorOptions o;
  int n;
  SUNContext ctx;
  N_Vector y;      /* state handed to / returned by the solver */
  N_Vector ylast;  /* last accepted state */
  N_Vector yo;     /* dense-output buffer */
  SUNMatrix A;
  SUNLinearSolver LS;
  void *erk, *ark, *cv;
  HmsaMethod active;
  int live;        /* active solver holds the current step */
  double t;        /* internal time of the active solver (last accepted step end) */
  double tlast;    /* time of ylast */
  double T_ref;
  HmsaIntegratorStats base; /* counters of finished solver instances */
  long domain_fails;
  int switched;
  double switch_tau;
  long collapsed, stiff_run, tiny_run; /* auto-switch and stagnation counters since reset */
};

static void silent_err(int code, const char *module, const char *function, char *msg, void *ud) {
  (void)code, (void)module, (void)function, (void)msg, (void)ud;
}

static int rhs_cb(realtype t, N_Vector y, N_Vector ydot, void *ud) {
  HmsaIntegrator *it = ud;
  int rc = hmsa_model_rhs(it->m, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
  if (rc > 0) it->domain_fails++;
  return rc; /* > 0: recoverable (PC pole), SUNDIALS shrinks the step */
}

/* Error weights 1/(rtol |y_i| + atol), the formula of ARKODE's scalar tolerances evaluated in
 * the same order (bitwise the same weights) in one loop instead of four vector operations:
 * ~6% less CPU for ERK on the benchmark sweep (3 equations: call overhead dominates). */
static int ewt_cb(N_Vector y, N_Vector w, void *ud) {
  const HmsaIntegrator *it = ud;
  const double *yy = N_VGetArrayPointer(y);
  double *ww = N_VGetArrayPointer(w);
  for (int i = 0; i < it->n; i++) {
    double d = it->o.rtol * fabs(yy[i]) + it->o.atol;
    if (!(d > 0.0)) return -1;
    ww[i] = 1.0 / d;
  }
  return 0;
}

static int jac_cb(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *ud, N_Vector t1,
                  N_Vector t2, N_Vector t3) {
  (void)fy, (void)t1, (void)t2, (void)t3;
  HmsaIntegrator *it = ud;
  double Jl[HMSA_NEQ_MAX * HMSA_NEQ_MAX];
  int rc = hmsa_model_jacobian(it->m, t, N_VGetArrayPointer(y), Jl);
  if (rc) return rc > 0 ? 1 : -1;
  for (int i = 0; i < it->n; i++)
    for (int j = 0; j < it->n; j++) SM_ELEMENT_D(J, i, j) = Jl[i * it->n + j];
  return 0;
}

const char *hmsa_method_name(HmsaMethod m) {
  switch (m) {
  case HMSA_METHOD_ERK: return "erk";
  case HMSA_METHOD_DIRK: return "dirk";
  case HMSA_METHOD_BDF: return "bdf";
  default: return "auto";
  }
}

void hmsa_integrator_options_default(HmsaIntegratorOptions *o) {
  memset(o, 0, sizeof *o);
  o->method = HMSA_METHOD_AUTO;
  o->rtol = 1e-8;
  o->atol = 1e-10;
  o->max_steps = 10000000;
  o->switch_ratio = 1e-3;
  o->switch_steps = 20000;
  o->h_max = 0.0;
}

/* Add the counters of the active solver instance to base (before it is re-initialised). */
static void read_counters(const HmsaIntegrator *it, HmsaIntegratorStats *s) {
  memset(s, 0, sizeof *s);
  long a = 0, b = 0, c = 0, d = 0, e = 0, f = 0;
  double h = 0;
  if (it->active == HMSA_METHOD_ERK && it->erk) {
    ERKStepGetNumSteps(it->erk, &a);
    ERKStepGetNumStepAttempts(it->erk, &b);
    ERKStepGetNumErrTestFails(it->erk, &c);
    ERKStepGetNumRhsEvals(it->erk, &d);
    ERKStepGetLastStep(it->erk, &h);
    s->steps = a, s->attempts = b, s->err_fails = c, s->rhs_evals = d;
  } else if (it->active == HMSA_METHOD_DIRK && it->ark) {
    long nfe = 0, nfi = 0;
    ARKStepGetNumSteps(it->ark, &a);
    ARKStepGetNumStepAttempts(it->ark, &b);
    ARKStepGetNumErrTestFails(it->ark, &c);
    ARKStepGetNumRhsEvals(it->ark, &nfe, &nfi);
    ARKStepGetNumNonlinSolvIters(it->ark, &e);
    ARKStepGetNumNonlinSolvConvFails(it->ark, &f);
    ARKStepGetNumJacEvals(it->ark, &d);
    ARKStepGetLastStep(it->ark, &h);
    s->steps = a, s->attempts = b, s->err_fails = c, s->rhs_evals = nfe + nfi;
    s->nli = e, s->conv_fails = f, s->jac_evals = d;
  } else if (it->active == HMSA_METHOD_BDF && it->cv) {
    long nfe = 0;
    CVodeGetNumSteps(it->cv, &a);
    CVodeGetNumErrTestFails(it->cv, &c);
    CVodeGetNumRhsEvals(it->cv, &nfe);
    CVodeGetNumNonlinSolvIters(it->cv, &e);
    CVodeGetNumNonlinSolvConvFails(it->cv, &f);
    CVodeGetNumJacEvals(it->cv, &d);
    CVodeGetLastStep(it->cv, &h);
    s->steps = a, s->err_fails = c, s->rhs_evals = nfe, s->nli = e, s->conv_fails = f;
    s->jac_evals = d, s->attempts = a + c + f;
  }
  s->h_last = h;
}

static void bank_counters(HmsaIntegrator *it) {
  if (!it->live) return;
  HmsaIntegratorStats s;
  read_counters(it, &s);
  it->base.steps += s.steps;
  it->base.attempts += s.attempts;
  it->base.err_fails += s.err_fails;
  it->base.conv_fails += s.conv_fails;
  it->base.rhs_evals += s.rhs_evals;
  it->base.jac_evals += s.jac_evals;
  it->base.nli += s.nli;
  it->base.h_last = s.h_last;
  it->live = 0;
}

#define SUN_CHECK(call)                                                                  \
  do {                                                                                   \
    int sun_rc_ = (call);                                                                \
    if (sun_rc_ < 0) return SA_ERROR(SA_ERR_LIBRARY, "%s failed (%d)", #call, sun_rc_); \
  } while (0)

static double stiff_rate(const HmsaIntegrator *it, double t, const double *y);

/* DIRK dense output: Lagrange above this ratio of the Maxwell relaxation rate to the
 * reference angular frequency, Hermite below (see start_solver) */
#define HMSA_DIRK_LAGRANGE_RATIO 50.0

/* (Re)start solver `method` at (t0, it->y) with initial step h0 (0 = estimate). */
static int start_solver(HmsaIntegrator *it, HmsaMethod method, double t0, double h0) {
  bank_counters(it);
  it->active = method;
  const HmsaIntegratorOptions *o = &it->o;
  if (method == HMSA_METHOD_ERK) {
    if (!it->erk) {
      it->erk = ERKStepCreate(rhs_cb, t0, it->y, it->ctx);
      if (!it->erk) return SA_ERROR(SA_ERR_LIBRARY, "ERKStepCreate failed");
      SUN_CHECK(ERKStepSetTableNum(it->erk, ARKODE_DORMAND_PRINCE_7_4_5));
      SUN_CHECK(ERKStepSetErrHandlerFn(it->erk, silent_err, NULL));
      SUN_CHECK(ERKStepSetUserData(it->erk, it));
      /* Step-size controller: ARKODE's ImEx Gustafsson controller (method 5, default parameters)
       * with the method order q = 5 in its exponents (pq = 1). On the benchmark sweep
       * (bench/hmsa, docs/hmsa_benchmark.md) it rejects 0.3-2% of the attempted steps against
       * ~15-20% for the default PI controller and reaches a given max error in a3 with 15%
       * (1e-6 level) to 25% (1e-8 level) less CPU time. Compared at equal error, not equal
       * rtol: at equal rtol it is ~4x more accurate. Methods 0-4 were no better at equal error;
       * the implicit solvers keep their defaults. */
      SUN_CHECK(ERKStepSetAdaptivityMethod(it->erk, 5, 1, 1, NULL));
    } else {
      SUN_CHECK(ERKStepReInit(it->erk, rhs_cb, t0, it->y));
    }
    if (o->atol > 0) SUN_CHECK(ERKStepWFtolerances(it->erk, ewt_cb));
    else SUN_CHECK(ERKStepSStolerances(it->erk, o->rtol, o->atol));
    SUN_CHECK(ERKStepSetMaxNumSteps(it->erk, -1));
    SUN_CHECK(ERKStepSetInitStep(it->erk, h0));
    if (o->h_max > 0) SUN_CHECK(ERKStepSetMaxStep(it->erk, o->h_max));
  } else if (method == HMSA_METHOD_DIRK) {
    if (!it->ark) {
      it->ark = ARKStepCreate(NULL, rhs_cb, t0, it->y, it->ctx);
      if (!it->ark) return SA_ERROR(SA_ERR_LIBRARY, "ARKStepCreate failed");
      SUN_CHECK(ARKStepSetTableNum(it->ark, ARKODE_ARK548L2SA_DIRK_8_4_5, ARKODE_ERK_NONE));
      SUN_CHECK(ARKStepSetErrHandlerFn(it->ark, silent_err, NULL));
      SUN_CHECK(ARKStepSetUserData(it->ark, it));
      SUN_CHECK(ARKStepSetLinearSolver(it->ark, it->LS, it->A));
      SUN_CHECK(ARKStepSetJacFn(it->ark, jac_cb));
    } else {
      SUN_CHECK(ARKStepReInit(it->ark, NULL, rhs_cb, t0, it->y));
    }
    /* Dense output (docs/hmsa_benchmark.md, issue 15). ARKODE's Lagrange interpolant is a
     * degree-5 polynomial through the last six accepted step values, without derivatives; on
     * the non-stiff benchmark case its error at the output points is 4-20x the DIRK's own
     * step error (final state 36-390 rtol at rtol 1e-7..1e-10, against 12-22 rtol when the
     * output lands on a step or comes from the Hermite interpolant). The Hermite interpolant
     * (degree 5: y and f at both ends plus two interior RHS calls) tracks the steps, but where
     * the Maxwell branch is stiff its interior RHS calls at interpolated states leave xi off the
     * slow manifold between steps (xi - lambda ~ 1e-5 at eta_bar 1e-5, a spurious xi' ~ 1e2,
     * energy balance 1e3 instead of 1e-6). So: Hermite unless the relaxation rate exceeds 50
     * times the reference angular frequency 2 pi/T_ref; measured crossover of the two
     * interpolants' accuracy between 20 and 60. */
    {
      const double *y0 = N_VGetArrayPointer(it->y);
      int stiff = stiff_rate(it, t0, y0) * it->T_ref > HMSA_DIRK_LAGRANGE_RATIO * 2.0 * HMSA_PI;
      SUN_CHECK(ARKStepSetInterpolantType(it->ark, stiff ? ARK_INTERP_LAGRANGE : ARK_INTERP_HERMITE));
    }
    SUN_CHECK(ARKStepSStolerances(it->ark, o->rtol, o->atol));
    SUN_CHECK(ARKStepSetMaxNumSteps(it->ark, -1));
    SUN_CHECK(ARKStepSetMaxErrTestFails(it->ark, 50));
    SUN_CHECK(ARKStepSetMaxConvFails(it->ark, 50));
    SUN_CHECK(ARKStepSetInitStep(it->ark, h0));
    if (o->h_max > 0) SUN_CHECK(ARKStepSetMaxStep(it->ark, o->h_max));
  } else {
    if (!it->cv) {
      it->cv = CVodeCreate(CV_BDF, it->ctx);
      if (!it->cv) return SA_ERROR(SA_ERR_LIBRARY, "CVodeCreate failed");
      SUN_CHECK(CVodeInit(it->cv, rhs_cb, t0, it->y));
      SUN_CHECK(CVodeSetErrHandlerFn(it->cv, silent_err, NULL));
      SUN_CHECK(CVodeSetUserData(it->cv, it));
      SUN_CHECK(CVodeSetLinearSolver(it->cv, it->LS, it->A));
      SUN_CHECK(CVodeSetJacFn(it->cv, jac_cb));
    } else {
      SUN_CHECK(CVodeReInit(it->cv, t0, it->y));
    }
    SUN_CHECK(CVodeSStolerances(it->cv, o->rtol, o->atol));
    SUN_CHECK(CVodeSetMaxNumSteps(it->cv, -1));
    SUN_CHECK(CVodeSetInitStep(it->cv, h0));
    SUN_CHECK(CVodeSetMaxConvFails(it->cv, 50));
    SUN_CHECK(CVodeSetMaxErrTestFails(it->cv, 50));
    if (o->h_max > 0) SUN_CHECK(CVodeSetMaxStep(it->cv, o->h_max));
  }
  it->live = 1;
  it->t = t0;
  return 0;
}

int hmsa_integrator_create(const HmsaModel *m, const HmsaIntegratorOptions *o,
                           HmsaIntegrator **out) {
  *out = NULL;
  HmsaIntegrator *it;
  SA_CALLOC(it, 1);
  it->m = m;
  if (o) it->o = *o; else hmsa_integrator_options_default(&it->o);
  if (it->o.max_steps <= 0) it->o.max_steps = 10000000;
  if (it->o.switch_ratio <= 0) it->o.switch_ratio = 1e-3;
  if (it->o.switch_steps <= 0) it->o.switch_steps = 20000;
  it->n = hmsa_model_neq(m);
  int rc = 0;
  if (SUNContext_Create(NULL, &it->ctx)) { rc = SA_ERROR(SA_ERR_LIBRARY, "SUNContext_Create failed"); goto fail; }
  it->y = N_VNew_Serial(it->n, it->ctx);
  it->ylast = N_VNew_Serial(it->n, it->ctx);
  it->yo = N_VNew_Serial(it->n, it->ctx);
  /* Fused vector kernels (one loop for the stage combinations instead of a chain of
   * N_VLinearSum/N_VScale calls): every solver clones its work vectors from y, so they inherit
   * them. For 3 equations the per-call overhead dominates: ~8% less CPU for ERK. */
  if (it->y && N_VEnableFusedOps_Serial(it->y, SUNTRUE)) {
    rc = SA_ERROR(SA_ERR_LIBRARY, "N_VEnableFusedOps_Serial failed");
    goto fail;
  }
  it->A = SUNDenseMatrix(it->n, it->n, it->ctx);
  if (!it->y || !it->ylast || !it->yo || !it->A) { rc = SA_ERROR(SA_ERR_MEMORY, "SUNDIALS allocation failed"); goto fail; }
  it->LS = SUNLinSol_Dense(it->y, it->A, it->ctx);
  if (!it->LS) { rc = SA_ERROR(SA_ERR_LIBRARY, "SUNLinSol_Dense failed"); goto fail; }
  *out = it;
  return 0;
fail:
  hmsa_integrator_destroy(&it);
  return rc;
}

void hmsa_integrator_destroy(HmsaIntegrator **pit) {
  if (!pit || !*pit) return;
  HmsaIntegrator *it = *pit;
  if (it->erk) ERKStepFree(&it->erk);
  if (it->ark) ARKStepFree(&it->ark);
  if (it->cv) CVodeFree(&it->cv);
  if (it->LS) SUNLinSolFree(it->LS);
  if (it->A) SUNMatDestroy(it->A);
  if (it->y) N_VDestroy(it->y);
  if (it->ylast) N_VDestroy(it->ylast);
  if (it->yo) N_VDestroy(it->yo);
  if (it->ctx) SUNContext_Free(&it->ctx);
  free(it);
  *pit = NULL;
}

static double reference_period(const HmsaModel *m) {
  double P = hmsa_model_period(m);
  if (P > 0) return P;
  HmsaEquilibrium eq;
  if (hmsa_linearise(m, 1.0, 0.0, &eq) == 0 && eq.omega_u > 0) return 2.0 * HMSA_PI / eq.omega_u;
  sa_error_clear();
  return 1.0;
}

int hmsa_integrator_reset(HmsaIntegrator *it, double tau0, const double *y0) {
  double *y = N_VGetArrayPointer(it->y);
  for (int i = 0; i < it->n; i++) y[i] = y0[i];
  N_VScale(1.0, it->y, it->ylast);
  it->tlast = tau0;
  it->T_ref = reference_period(it->m);
  it->collapsed = it->stiff_run = it->tiny_run = 0;
  double f[HMSA_NEQ_MAX];
  int rc = hmsa_model_rhs(it->m, tau0, y0, f);
  SA_REQUIRE(rc == 0, SA_ERR_DOMAIN, "initial state (lambda = %g) outside the model's domain", y0[0]);
  HmsaMethod m0 = it->o.method == HMSA_METHOD_AUTO ? HMSA_METHOD_ERK : it->o.method;
  SA_CHECK(start_solver(it, m0, tau0, 0.0));
  return 0;
}

double hmsa_integrator_time(const HmsaIntegrator *it) { return it->t; }

/* Relaxation rate of the stiff mode: -d xi'/d xi of the Maxwell branch (Zener). The PC model
 * has no dissipative mode: its fast oscillations near the pole need small steps for accuracy,
 * which an implicit method would not remove. */
static double stiff_rate(const HmsaIntegrator *it, double t, const double *y) {
  if (it->m->model != HMSA_ZENER) return 0.0;
  double J[HMSA_NEQ_MAX * HMSA_NEQ_MAX];
  if (hmsa_model_jacobian(it->m, t, y, J)) return 0.0;
  return fmax(0.0, -J[2 * it->n + 2]);
}

static int get_dky(HmsaIntegrator *it, double tout, N_Vector out) {
  int rc;
  if (it->active == HMSA_METHOD_ERK) rc = ERKStepGetDky(it->erk, tout, 0, out);
  else if (it->active == HMSA_METHOD_DIRK) rc = ARKStepGetDky(it->ark, tout, 0, out);
  else rc = CVodeGetDky(it->cv, tout, 0, out);
  SA_REQUIRE(rc >= 0, SA_ERR_LIBRARY, "dense output at tau = %.17g failed (%d)", tout, rc);
  return 0;
}

/* The case key that sets the load's size, for the advice of diagnose_domain. */
static const char *load_keys(const HmsaModel *m) {
  switch (m->loading) {
  case HMSA_LOAD_SQ: return "b_a";
  case HMSA_LOAD_LIN: return "b2_dc and b2_ac";
  default: return "b2";
  }
}

/* Why the steps collapsed at the domain boundary, in the terms of the model that ran: the PC
 * model's boundary is the chain-locking pole I1 = 3 lambda_max^2 (at both ends of its lambda
 * range), the Zener model's is only lambda > 0, xi > 0 (it has no lambda_max), which only an
 * enormous load crosses within a step. */
static int diagnose_domain(HmsaIntegrator *it, int rc_sun) {
  const double *y = N_VGetArrayPointer(it->ylast);
  HmsaIntegratorStats st;
  hmsa_integrator_get_stats(it, &st);
  double h = st.h_last;
  if (it->m->model == HMSA_PC) {
    double lm2 = it->m->lambda_max * it->m->lambda_max;
    double y2 = y[0] * y[0], I1 = 2 * y2 + 1.0 / (y2 * y2);
    return SA_ERROR(SA_ERR_DOMAIN,
                    "%s cannot step past tau = %.10g: the solution runs into the PC pole "
                    "I1 = 3 lambda_max^2 = %.10g (I1 = %.12g, gap %.3g at the last accepted state "
                    "lambda = %.12g, lambda' = %.6g); the step collapsed to %.3g with %ld RHS calls "
                    "outside the domain rejected (solver code %d). The turning point is closer to "
                    "the pole than double precision resolves: lower |%s| or raise lambda_max",
                    hmsa_method_name(it->active), it->tlast, 3 * lm2, I1, 3 * lm2 - I1, y[0], y[1],
                    h, it->domain_fails, rc_sun, load_keys(it->m));
  }
  return SA_ERROR(SA_ERR_DOMAIN,
                  "%s cannot step past tau = %.10g: every step takes the Zener model out of its "
                  "domain lambda > 0, xi > 0 (last accepted state lambda = %.12g, lambda' = %.6g, "
                  "xi = %.12g, load b2 = %.6g there); the step collapsed to %.3g with %ld RHS "
                  "calls outside the domain rejected (solver code %d). The load drives lambda out of "
                  "(0, inf) faster than a step resolves: lower |%s|",
                  hmsa_method_name(it->active), it->tlast, y[0], y[1], y[2],
                  hmsa_model_b2(it->m, it->tlast), h, it->domain_fails, rc_sun,
                  load_keys(it->m));
}

int hmsa_integrator_advance(HmsaIntegrator *it, double tout, double *yout) {
  SA_REQUIRE(it->live, SA_ERR_INTERNAL, "integrator used before reset");
  long nsteps = 0;
  int retries = 0;
  N_Vector ytmp = it->y;
  while (it->t < tout) {
    /* one step takes microseconds, but a stiff problem under erk needs millions of them per
     * output interval: polling here lets every caller answer a signal at once */
    if (sa_interrupted())
      return SA_ERROR(SA_ERR_INTERRUPTED, "interrupted at tau = %g", it->t);
    SA_REQUIRE(nsteps < it->o.max_steps, SA_ERR_NOT_CONVERGED,
               "%s needed more than %ld steps to reach tau = %g (now at %g)",
               hmsa_method_name(it->active), it->o.max_steps, tout, it->t);
    double tret = it->t, h = 0.0;
    int rc;
    if (it->active == HMSA_METHOD_ERK) {
      rc = ERKStepEvolve(it->erk, tout, ytmp, &tret, ARK_ONE_STEP);
      if (rc == ARK_UNREC_RHSFUNC_ERR || rc == ARK_FIRST_RHSFUNC_ERR) {
        /* a stage left the domain: restart from the last accepted state with a smaller step */
        double hl = 0.0;
        ERKStepGetCurrentStep(it->erk, &hl);
        if (!(hl > 0)) ERKStepGetLastStep(it->erk, &hl);
        double h0 = 0.25 * (hl > 0 ? hl : 1e-3 * it->T_ref);
        retries++;
        if (retries > 60 || h0 < 1e-14 * (1.0 + fabs(it->tlast))) return diagnose_domain(it, rc);
        N_VScale(1.0, it->ylast, it->y);
        SA_CHECK(start_solver(it, HMSA_METHOD_ERK, it->tlast, h0));
        continue;
      }
      ERKStepGetLastStep(it->erk, &h);
    } else if (it->active == HMSA_METHOD_DIRK) {
      rc = ARKStepEvolve(it->ark, tout, ytmp, &tret, ARK_ONE_STEP);
      ARKStepGetLastStep(it->ark, &h);
    } else {
      rc = CVode(it->cv, tout, ytmp, &tret, CV_ONE_STEP);
      CVodeGetLastStep(it->cv, &h);
    }
    if (rc < 0) {
      if (it->domain_fails > 0 && it->m->model == HMSA_PC) return diagnose_domain(it, rc);
      int code = (rc == ARK_TOO_CLOSE) ? SA_ERR_INPUT
               : (rc == ARK_ERR_FAILURE || rc == ARK_CONV_FAILURE) ? SA_ERR_STEP_TOO_SMALL
               : SA_ERR_NUMERICAL;
      return SA_ERROR(code, "%s failed at tau = %.10g with solver code %d (last step %g)",
                      hmsa_method_name(it->active), it->tlast, rc, h);
    }
    retries = 0;
    nsteps++;
    it->t = tret;
    /* stagnation: steps at the round-off level of tau make no progress (e.g. implicit methods
     * whose stages keep landing beyond the PC pole) */
    if (h < 1e-12 * (1.0 + fabs(tret))) {
      if (++it->tiny_run >= 100) {
        if (it->m->model == HMSA_PC) {
          const double *yl = N_VGetArrayPointer(ytmp);
          double lm2 = it->m->lambda_max * it->m->lambda_max, l = yl[0];
          double gap = 3.0 * lm2 - (2 * l * l + 1.0 / (l * l * l * l));
          if (it->domain_fails > 0 || gap < 1e-6 * 3.0 * lm2) {
            N_VScale(1.0, ytmp, it->ylast);
            it->tlast = tret;
            return diagnose_domain(it, 0);
          }
        }
        return SA_ERROR(SA_ERR_STEP_TOO_SMALL, "%s: 100 steps below 1e-12 (1 + tau) at tau = %.10g",
                        hmsa_method_name(it->active), tret);
      }
    } else {
      it->tiny_run = 0;
    }
    const double *yc = N_VGetArrayPointer(ytmp);
    for (int i = 0; i < it->n; i++)
      SA_REQUIRE(isfinite(yc[i]), SA_ERR_NAN, "state component %d not finite at tau = %g", i, tret);
    N_VScale(1.0, ytmp, it->ylast);
    it->tlast = tret;
    if (it->t >= tout) break; /* dense output at tout lives in this last step */
    if (it->o.method == HMSA_METHOD_AUTO && it->active == HMSA_METHOD_ERK) {
      int small = h < it->o.switch_ratio * it->T_ref;
      if (small) it->collapsed++;
      if (small && h * stiff_rate(it, tret, yc) >= 1.0) it->stiff_run++;
      else it->stiff_run = 0;
      if (it->stiff_run >= 50 || (it->collapsed >= it->o.switch_steps && stiff_rate(it, tret, yc) > 0)) {
        it->switched++;
        it->switch_tau = tret;
        SA_CHECK(start_solver(it, HMSA_METHOD_BDF, tret, 0.0));
      }
    }
  }
  SA_CHECK(get_dky(it, tout, it->yo));
  const double *p = N_VGetArrayPointer(it->yo);
  for (int i = 0; i < it->n; i++) yout[i] = p[i];
  return 0;
}

void hmsa_integrator_get_stats(const HmsaIntegrator *it, HmsaIntegratorStats *s) {
  HmsaIntegratorStats c;
  *s = it->base;
  if (it->live) {
    read_counters(it, &c);
    s->steps += c.steps;
    s->attempts += c.attempts;
    s->err_fails += c.err_fails;
    s->conv_fails += c.conv_fails;
    s->rhs_evals += c.rhs_evals;
    s->jac_evals += c.jac_evals;
    s->nli += c.nli;
    s->h_last = c.h_last;
  }
  s->domain_fails = it->domain_fails;
  s->switched = it->switched;
  s->switch_tau = it->switch_tau;
  s->active = it->active;
}
