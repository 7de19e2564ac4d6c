/* hmsa.c - the HMSA scene: case keys, validation, and the analyses of MODEL.md
 * (time histories, statics, Poincare section + Lyapunov exponent, frequency sweeps).
 *
 * A case may list several values for eta, S, b2, sigma, mu_c, mu_e, lambda_max; the scene runs
 * every combination relevant to the model (a "variant"), writing files NAME_TAG.csv/png where
 * TAG names the listed keys (no tag when every list has one value). summary.ini holds the
 * scalar results, in one [TAG] section per variant when there are several. */
#include "hmsa.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hmsa_analysis.h"
#include "hmsa_classify.h"
#include "hmsa_figure.h"
#include "sa_csv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_plot.h"

typedef struct {
  char model[SA_STR_MAX];
  char analysis[SA_STR_MAX];
  double c, beta;
  SaRealList eta, S, b2, sigma, mu_c, mu_e, lambda_max;
  char loading[SA_STR_MAX];
  double b_a, omega, b2_dc, b2_ac;
  double t_end, dt_out;
  char method[SA_STR_MAX];
  double rtol, atol, switch_ratio;
} HmsaParams;

typedef struct {
  double omega_min, omega_max;
  int n_omega;
  int continuation;
  int transient_periods;
  double transient_tau;
  int measure_periods, samples_per_period;
  int refine;
  double prominence;
} HmsaSweepParams;

typedef struct {
  int transient_periods, n_points;
  int lyapunov;
  double d0;
  int orbit_periods;
} HmsaPoincareParams;

#define P(field) offsetof(HmsaParams, field)
static const SaParam hmsa_params[] = {
    {"model", SA_PARAM_CHOICE, P(model), "-", "zener", 0, 0, 0, "zener|pc",
     "material model: Zener viscoelastic (Maxwell branch) or polymer chain (no dissipation)"},
    {"analysis", SA_PARAM_CHOICE, P(analysis), "-", "history", 0, 0, 0,
     "history|statics|poincare|sweep",
     "time history + phase plane, static equilibria, Poincare map + Lyapunov, frequency sweep"},
    {"c", SA_PARAM_REAL, P(c), "-", "1", 0, INFINITY, 0, NULL, "aspect parameter H^2/L^2"},
    {"beta", SA_PARAM_REAL, P(beta), "-", "2", 0, INFINITY, 0, NULL,
     "Maxwell-branch modulus / equilibrium modulus (Zener)"},
    {"eta", SA_PARAM_REAL_LIST, P(eta), "-", "50", 0, INFINITY, SA_MIN_OPEN, NULL,
     "dimensionless viscosity eta_bar = eta/(L sqrt(rho mu)) (Zener); list = variants"},
    {"S", SA_PARAM_REAL_LIST, P(S), "-", "0", -INFINITY, INFINITY, 0, NULL,
     "prestress sigma/mu (equal biaxial dead load); list = variants"},
    {"b2", SA_PARAM_REAL_LIST, P(b2), "-", "0.16", -INFINITY, INFINITY, 0, NULL,
     "signed magnetic load B_r B_a/(mu mu0) for loading = const (step at tau = 0); list = variants"},
    {"loading", SA_PARAM_CHOICE, P(loading), "-", "const", 0, 0, 0, "const|sq|lin",
     "b2(tau): const b2 | sq: sigma b_a^2 sin^2(omega tau) | lin: b2_dc + b2_ac sin(omega tau)"},
    {"b_a", SA_PARAM_REAL, P(b_a), "-", "0.4", 0, INFINITY, 0, NULL,
     "field amplitude b_a of the sq loading"},
    {"sigma", SA_PARAM_REAL_LIST, P(sigma), "-", "1", -1, 1, 0, NULL,
     "sign of the sq loading: +1 along the residual flux, -1 against it; list = variants"},
    {"omega", SA_PARAM_REAL, P(omega), "-", "2.13", 0, INFINITY, SA_MIN_OPEN, NULL,
     "forcing frequency Omega of the sq/lin loading"},
    {"b2_dc", SA_PARAM_REAL, P(b2_dc), "-", "0", -INFINITY, INFINITY, 0, NULL,
     "mean load of the lin loading"},
    {"b2_ac", SA_PARAM_REAL, P(b2_ac), "-", "0.16", -INFINITY, INFINITY, 0, NULL,
     "amplitude of the lin loading"},
    {"mu_c", SA_PARAM_REAL_LIST, P(mu_c), "-", "1", 0, INFINITY, 0, NULL,
     "polymer chain: crosslink modulus m_c = mu_c/mu_ref; list = variants"},
    {"mu_e", SA_PARAM_REAL_LIST, P(mu_e), "-", "0", 0, INFINITY, 0, NULL,
     "polymer chain: entanglement modulus m_e = mu_e/mu_ref; list = variants"},
    {"lambda_max", SA_PARAM_REAL_LIST, P(lambda_max), "-", "2", 1, INFINITY, SA_MIN_OPEN, NULL,
     "polymer chain: chain extensibility (I1 < 3 lambda_max^2); list = variants"},
    {"t_end", SA_PARAM_REAL, P(t_end), "-", "100", 0, INFINITY, SA_MIN_OPEN, NULL,
     "end of the time history (dimensionless time tau)"},
    {"dt_out", SA_PARAM_REAL, P(dt_out), "-", "0.01", 0, INFINITY, SA_MIN_OPEN, NULL,
     "output interval of the time history (dense output, not the step)"},
    {"method", SA_PARAM_CHOICE, P(method), "-", "auto", 0, 0, 0, "auto|erk|dirk|bdf",
     "integrator: Dormand-Prince 5(4) | ARKStep DIRK 5 | CVODE BDF; auto switches erk -> bdf when "
     "explicit steps collapse"},
    {"rtol", SA_PARAM_REAL, P(rtol), "-", "1e-9", 1e-14, 0.1, 0, NULL, "relative tolerance"},
    {"atol", SA_PARAM_REAL, P(atol), "-", "1e-11", 0, 1, SA_MIN_OPEN, NULL, "absolute tolerance"},
    {"switch_ratio", SA_PARAM_REAL, P(switch_ratio), "-", "1e-3", 0, 1, SA_MIN_OPEN, NULL,
     "auto: explicit step below switch_ratio * (forcing or natural period) while stability-bound "
     "switches to bdf"},
};
#undef P

#define P(field) offsetof(HmsaSweepParams, field)
static const SaParam hmsa_sweep_params[] = {
    {"omega_min", SA_PARAM_REAL, P(omega_min), "-", "0.5", 0, INFINITY, SA_MIN_OPEN, NULL,
     "lowest forcing frequency"},
    {"omega_max", SA_PARAM_REAL, P(omega_max), "-", "5", 0, INFINITY, SA_MIN_OPEN, NULL,
     "highest forcing frequency"},
    {"n_omega", SA_PARAM_INT, P(n_omega), "-", "91", 3, 100000, 0, NULL,
     "number of frequencies (uniform grid)"},
    {"continuation", SA_PARAM_BOOL, P(continuation), "-", "true", 0, 0, 0, NULL,
     "also sweep up and down, each frequency started from the previous final state"},
    {"transient_periods", SA_PARAM_INT, P(transient_periods), "-", "60", 1, 1000000, 0, NULL,
     "transient: at least this many periods"},
    {"transient_tau", SA_PARAM_REAL, P(transient_tau), "-", "400", 0, INFINITY, 0, NULL,
     "transient: at least this much tau"},
    {"measure_periods", SA_PARAM_INT, P(measure_periods), "-", "40", 1, 1000000, 0, NULL,
     "periods over which the amplitude (max - min)/2 is measured"},
    {"samples_per_period", SA_PARAM_INT, P(samples_per_period), "-", "128", 8, 100000, 0, NULL,
     "dense-output samples per period in the measurement"},
    {"refine", SA_PARAM_BOOL, P(refine), "-", "true", 0, 0, 0, NULL,
     "refine peaks by golden-section search on the from-rest amplitude"},
    {"prominence", SA_PARAM_REAL, P(prominence), "-", "0.05", 0, 1, 0, NULL,
     "peaks: minimum prominence relative to the amplitude range"},
};
#undef P

#define P(field) offsetof(HmsaPoincareParams, field)
static const SaParam hmsa_poincare_params[] = {
    {"transient_periods", SA_PARAM_INT, P(transient_periods), "-", "300", 0, 100000000, 0, NULL,
     "forcing periods skipped before sampling"},
    {"n_points", SA_PARAM_INT, P(n_points), "-", "300", 20, 10000000, 0, NULL,
     "Poincare samples (one per forcing period)"},
    {"lyapunov", SA_PARAM_BOOL, P(lyapunov), "-", "true", 0, 0, 0, NULL,
     "largest Lyapunov exponent (Benettin, two trajectories renormalised every period)"},
    {"d0", SA_PARAM_REAL, P(d0), "-", "1e-7", 0, 1e-2, SA_MIN_OPEN, NULL,
     "Benettin separation (Euclidean, state space)"},
    {"orbit_periods", SA_PARAM_INT, P(orbit_periods), "-", "20", 1, 100000, 0, NULL,
     "periods of the steady orbit written for the phase plane"},
};
#undef P

const SaParamTable hmsa_table = {"hmsa", "hmsa",
                                 "reduced-order dynamics of a hard-magnetic soft actuator",
                                 hmsa_params, SA_NPARAMS(hmsa_params)};
const SaParamTable hmsa_sweep_table = {"hmsa_sweep", "hmsa", "frequency sweep (analysis = sweep)",
                                       hmsa_sweep_params, SA_NPARAMS(hmsa_sweep_params)};
const SaParamTable hmsa_poincare_table = {"hmsa_poincare", "hmsa",
                                          "Poincare map and Lyapunov exponent (analysis = poincare)",
                                          hmsa_poincare_params, SA_NPARAMS(hmsa_poincare_params)};
static const SaParamTable *const hmsa_tables[] = {&hmsa_table, &hmsa_sweep_table,
                                                  &hmsa_poincare_table};

#define HMSA_MAX_VARIANTS 256

#define HMSA_MAX_DIMS 6

typedef struct {
  HmsaModel m;
  char tag[128];            /* file-name part, e.g. eta=5_S=0_b2=+0.16 ("" for one variant) */
  int idx[HMSA_MAX_DIMS];   /* index into each dimension's list */
  char plot_csv[256];       /* history: the CSV the figures read (decimated copy if long) */
  int ok;                   /* ran to the end */
} HmsaVariant;

typedef struct {
  HmsaParams p;
  HmsaSweepParams sw;
  HmsaPoincareParams pc;
  HmsaIntegratorOptions io;
  int ndim;                              /* lists relevant to the model and loading */
  const char *dim_name[HMSA_MAX_DIMS];   /* case key */
  const SaRealList *dim_list[HMSA_MAX_DIMS];
  int nvar;
  HmsaVariant var[HMSA_MAX_VARIANTS];
} HmsaScene;

/* ------------------------------------------------------------------ variants */

/* Signed keys carry an explicit sign in names and labels: b2=+0.16, sigma=-1. */
static int dim_signed(const char *key) { return !strcmp(key, "b2") || !strcmp(key, "sigma"); }

static void tag_add(char *tag, size_t n, const char *key, double v) {
  size_t k = strlen(tag);
  snprintf(tag + k, n - k, dim_signed(key) ? "%s%s=%+g" : "%s%s=%g", k ? "_" : "", key, v);
}

/* Legend text of key = v for the figures (UTF-8, gnuplot enhanced text). */
static void dim_label(char *buf, size_t n, const char *key, double v) {
  if (!strcmp(key, "eta")) snprintf(buf, n, "η = %g", v);
  else if (!strcmp(key, "S")) snprintf(buf, n, "S = %g", v);
  else if (!strcmp(key, "b2")) snprintf(buf, n, "b^2 = %+g", v);
  else if (!strcmp(key, "sigma"))
    snprintf(buf, n, "σ = %+g (%s B_r)", v, v > 0 ? "along" : "against");
  else if (!strcmp(key, "mu_c")) snprintf(buf, n, "μ_c = %g", v);
  else if (!strcmp(key, "mu_e")) snprintf(buf, n, "μ_e = %g", v);
  else if (!strcmp(key, "lambda_max")) snprintf(buf, n, "λ_{max} = %g", v);
  else snprintf(buf, n, "%s = %g", key, v);
}

static int build_variants(HmsaScene *s) {
  const HmsaParams *p = &s->p;
  int zener = !strcmp(p->model, "zener");
  HmsaLoading load = !strcmp(p->loading, "sq") ? HMSA_LOAD_SQ
                     : !strcmp(p->loading, "lin") ? HMSA_LOAD_LIN : HMSA_LOAD_CONST;
  /* the lists relevant to this model and loading, outermost first */
  const SaRealList *L[6];
  const char *name[6];
  int nl = 0;
  if (zener) { L[nl] = &p->eta; name[nl++] = "eta"; }
  else {
    L[nl] = &p->mu_c; name[nl++] = "mu_c";
    L[nl] = &p->mu_e; name[nl++] = "mu_e";
    L[nl] = &p->lambda_max; name[nl++] = "lambda_max";
  }
  L[nl] = &p->S; name[nl++] = "S";
  if (load == HMSA_LOAD_CONST) { L[nl] = &p->b2; name[nl++] = "b2"; }
  if (load == HMSA_LOAD_SQ) { L[nl] = &p->sigma; name[nl++] = "sigma"; }
  s->ndim = nl;
  for (int i = 0; i < nl; i++) s->dim_name[i] = name[i], s->dim_list[i] = L[i];
  long total = 1;
  for (int i = 0; i < nl; i++) total *= L[i]->n;
  SA_REQUIRE(total <= HMSA_MAX_VARIANTS, SA_ERR_INPUT,
             "[hmsa] the lists give %ld variants, at most %d are allowed", total, HMSA_MAX_VARIANTS);
  s->nvar = (int)total;
  for (long v = 0; v < total; v++) {
    HmsaVariant *var = &s->var[v];
    HmsaModel *m = &var->m;
    hmsa_model_default(m);
    m->model = zener ? HMSA_ZENER : HMSA_PC;
    m->c = p->c;
    m->beta = p->beta;
    m->loading = load;
    m->b_a = p->b_a;
    m->omega = p->omega;
    m->b2_dc = p->b2_dc;
    m->b2_ac = p->b2_ac;
    m->eta_bar = p->eta.v[0];
    m->mu_c = p->mu_c.v[0];
    m->mu_e = p->mu_e.v[0];
    m->lambda_max = p->lambda_max.v[0];
    m->S = p->S.v[0];
    m->b2 = p->b2.v[0];
    m->sgn = p->sigma.v[0];
    var->tag[0] = 0;
    long r = v;
    int idx[6];
    for (int i = nl - 1; i >= 0; i--) {
      idx[i] = (int)(r % L[i]->n);
      r /= L[i]->n;
    }
    for (int i = 0; i < nl; i++) {
      var->idx[i] = idx[i];
      double x = L[i]->v[idx[i]];
      if (L[i] == &p->eta) m->eta_bar = x;
      else if (L[i] == &p->mu_c) m->mu_c = x;
      else if (L[i] == &p->mu_e) m->mu_e = x;
      else if (L[i] == &p->lambda_max) m->lambda_max = x;
      else if (L[i] == &p->S) m->S = x;
      else if (L[i] == &p->b2) m->b2 = x;
      else if (L[i] == &p->sigma) m->sgn = x;
      if (L[i]->n > 1) tag_add(var->tag, sizeof var->tag, name[i], x);
    }
  }
  return 0;
}

/* ------------------------------------------------------------------ module interface */

/* Limits on the products of case keys that size an array or a loop, checked before the run:
 * each key alone may be inside its range while the product overflows an int (the samples of
 * one sweep point, 65536 x 65536 = 2^32, wrapped to 0 and gave zero amplitudes) or asks for
 * more memory than a worker should take. */
#define HMSA_MAX_MEASURE_SAMPLES 1e7  /* x 2 doubles per worker thread: 160 MB */
#define HMSA_MAX_TRANSIENT_PERIODS 1e6 /* as [hmsa_sweep] transient_periods' own range */
#define HMSA_SETTLING_DT 0.002          /* grid of hmsa_settling_time */
#define HMSA_MAX_SETTLING_POINTS 1e9    /* loop count of the settling-time pass */

static int check_sizes(const SaCase *c, const HmsaScene *s) {
  const HmsaParams *p = &s->p;
  const HmsaSweepParams *w = &s->sw;
  char where[SA_STR_MAX];
  if (!strcmp(p->analysis, "sweep")) {
    double nm = (double)w->measure_periods * (double)w->samples_per_period;
    SA_REQUIRE(nm <= HMSA_MAX_MEASURE_SAMPLES, SA_ERR_INPUT,
               "%s: [hmsa_sweep] measure_periods x samples_per_period = %d x %d = %.4g samples per "
               "frequency; at most %.0e are allowed (each sample keeps 2 doubles per worker "
               "thread: %.0f MB at the limit)",
               sa_case_origin(c, "hmsa_sweep", "samples_per_period", where), w->measure_periods,
               w->samples_per_period, nm, HMSA_MAX_MEASURE_SAMPLES,
               16.0 * HMSA_MAX_MEASURE_SAMPLES / 1e6);
    /* the transient runs at least transient_tau, i.e. this many periods at omega_max */
    double ntau = w->transient_tau * w->omega_max / (2.0 * HMSA_PI);
    SA_REQUIRE(ntau <= HMSA_MAX_TRANSIENT_PERIODS, SA_ERR_INPUT,
               "%s: [hmsa_sweep] transient_tau x omega_max / (2 pi) = %g x %g / (2 pi) = %.4g "
               "transient periods; at most %.0e are allowed (the limit of transient_periods)",
               sa_case_origin(c, "hmsa_sweep", "transient_tau", where), w->transient_tau,
               w->omega_max, ntau, HMSA_MAX_TRANSIENT_PERIODS);
  }
  /* the settling time of a Zener step response is found on a grid of 0.002 up to t_end */
  if (!strcmp(p->analysis, "history") && !strcmp(p->model, "zener") &&
      !strcmp(p->loading, "const")) {
    double npt = p->t_end / HMSA_SETTLING_DT;
    SA_REQUIRE(npt <= HMSA_MAX_SETTLING_POINTS, SA_ERR_INPUT,
               "%s: [hmsa] t_end / %g = %.4g points of the settling-time grid; at most %.0e are "
               "allowed (t_end <= %g)", sa_case_origin(c, "hmsa", "t_end", where),
               HMSA_SETTLING_DT, npt, HMSA_MAX_SETTLING_POINTS,
               HMSA_MAX_SETTLING_POINTS * HMSA_SETTLING_DT);
  }
  return 0;
}

static int hmsa_check(const SaCase *c, void **out) {
  *out = NULL;
  HmsaScene *s;
  SA_CALLOC(s, 1);
  int rc = sa_params_load(&hmsa_table, c, &s->p);
  if (!rc) rc = sa_params_load(&hmsa_sweep_table, c, &s->sw);
  if (!rc) rc = sa_params_load(&hmsa_poincare_table, c, &s->pc);
  if (rc) { free(s); return sa_error_push(rc, __func__, __FILE__, __LINE__); }
  const HmsaParams *p = &s->p;
  char where[SA_STR_MAX];
  /* A check between two keys points at the one the case gives and marks a default as such:
   * a conflict with a default is still the user's line (sa_case_where falls back to the file). */
#define SET(sec, key) sa_case_is_set(c, sec, key)
#define DEF(sec, key) (SET(sec, key) ? "" : " (default)")
  for (int i = 0; i < p->sigma.n; i++)
    if (fabs(fabs(p->sigma.v[i]) - 1.0) > 0) {
      rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] sigma: %g must be +1 or -1 (sign of the sq load)",
                    sa_case_where(c, "hmsa", "sigma", where), p->sigma.v[i]);
      goto fail;
    }
  if (!strcmp(p->model, "pc")) {
    for (int i = 0; i < p->mu_c.n; i++)
      for (int j = 0; j < p->mu_e.n; j++)
        if (p->mu_c.v[i] + p->mu_e.v[j] <= 0) {
          rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] mu_c = %g%s with mu_e = %g%s leaves no elastic "
                        "stiffness (mu_c + mu_e must be > 0)",
                        sa_case_where(c, "hmsa", SET("hmsa", "mu_c") ? "mu_c" : "mu_e", where),
                        p->mu_c.v[i], DEF("hmsa", "mu_c"), p->mu_e.v[j], DEF("hmsa", "mu_e"));
          goto fail;
        }
  }
  int periodic = strcmp(p->loading, "const") != 0;
  if ((!strcmp(p->analysis, "poincare") || !strcmp(p->analysis, "sweep")) && !periodic) {
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] analysis = %s needs a periodic loading (sq or lin), not "
                  "loading = %s%s", sa_case_where(c, "hmsa", SET("hmsa", "loading") ? "loading" : "analysis", where),
                  p->analysis, p->loading, DEF("hmsa", "loading"));
    goto fail;
  }
  if (!(s->sw.omega_max > s->sw.omega_min)) {
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa_sweep] omega_max = %g%s must exceed omega_min = %g%s",
                  sa_case_where(c, "hmsa_sweep", SET("hmsa_sweep", "omega_max") ? "omega_max" : "omega_min", where),
                  s->sw.omega_max, DEF("hmsa_sweep", "omega_max"), s->sw.omega_min, DEF("hmsa_sweep", "omega_min"));
    goto fail;
  }
  if (p->dt_out > p->t_end) {
    if (SET("hmsa", "dt_out") || !SET("hmsa", "t_end"))
      rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] dt_out = %g exceeds t_end = %g%s",
                    sa_case_where(c, "hmsa", "dt_out", where), p->dt_out, p->t_end, DEF("hmsa", "t_end"));
    else
      rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] t_end = %g is below the default dt_out = %g (set dt_out too)",
                    sa_case_where(c, "hmsa", "t_end", where), p->t_end, p->dt_out);
    goto fail;
  }
  if (p->t_end / p->dt_out > 5e7) {
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] t_end = %g%s / dt_out = %g%s = %g rows is too many (at most 5e7)",
                  sa_case_where(c, "hmsa", SET("hmsa", "dt_out") ? "dt_out" : "t_end", where), p->t_end,
                  DEF("hmsa", "t_end"), p->dt_out, DEF("hmsa", "dt_out"), p->t_end / p->dt_out);
    goto fail;
  }
#undef SET
#undef DEF
  rc = check_sizes(c, s);
  if (!rc) rc = build_variants(s);
  if (rc) goto fail;
  hmsa_integrator_options_default(&s->io);
  s->io.method = !strcmp(p->method, "erk") ? HMSA_METHOD_ERK
                 : !strcmp(p->method, "dirk") ? HMSA_METHOD_DIRK
                 : !strcmp(p->method, "bdf") ? HMSA_METHOD_BDF : HMSA_METHOD_AUTO;
  s->io.rtol = p->rtol;
  s->io.atol = p->atol;
  s->io.switch_ratio = p->switch_ratio;
  *out = s;
  return 0;
fail:
  free(s);
  return rc;
}

static void hmsa_write_resolved(const void *scene, FILE *f) {
  const HmsaScene *s = scene;
  sa_params_write(&hmsa_table, &s->p, f);
  fprintf(f, "\n");
  sa_params_write(&hmsa_sweep_table, &s->sw, f);
  fprintf(f, "\n");
  sa_params_write(&hmsa_poincare_table, &s->pc, f);
}

static void hmsa_destroy(void **scene) {
  if (!scene) return;
  free(*scene);
  *scene = NULL;
}

/* ------------------------------------------------------------------ output helpers */

static void file_name(char *buf, size_t n, const char *stem, const char *tag, const char *ext) {
  snprintf(buf, n, "%s%s%s.%s", stem, tag[0] ? "_" : "", tag, ext);
}

typedef struct {
  FILE *f; /* summary stream */
} Summary;

static void sum_real(Summary *S, const char *key, double v) { fprintf(S->f, "%s = %.10g\n", key, v); }
static void sum_int(Summary *S, const char *key, long v) { fprintf(S->f, "%s = %ld\n", key, v); }
static void sum_str(Summary *S, const char *key, const char *v) { fprintf(S->f, "%s = %s\n", key, v); }

static void sum_stats(Summary *S, const HmsaIntegrator *it, double seconds) {
  HmsaIntegratorStats st;
  hmsa_integrator_get_stats(it, &st);
  sum_str(S, "integrator", hmsa_method_name(st.active));
  sum_int(S, "steps", st.steps);
  sum_int(S, "rejected_steps", st.attempts - st.steps);
  sum_int(S, "rhs_evals", st.rhs_evals);
  sum_int(S, "jac_evals", st.jac_evals);
  sum_int(S, "domain_rejections", st.domain_fails);
  if (st.switched) sum_real(S, "switched_to_bdf_at_tau", st.switch_tau);
  sum_real(S, "integration_seconds", seconds);
}

/* Statics at the (mean) load: all roots with stability, limit points and frequencies. */
static int write_statics(Summary *S, const HmsaModel *m, HmsaEquilibrium *eq0) {
  double b2 = hmsa_model_b2_mean(m);
  HmsaEquilibrium eq[HMSA_MAX_ROOTS];
  int n;
  SA_CHECK(hmsa_static_solve(m, b2, eq, &n));
  fprintf(S->f, "static_b2 = %.10g\nstatic_lambda3 = ", b2);
  for (int i = 0; i < n; i++) fprintf(S->f, "%s%.10g", i ? ", " : "", eq[i].lambda3);
  fprintf(S->f, "\nstatic_stable = ");
  for (int i = 0; i < n; i++) fprintf(S->f, "%s%d", i ? ", " : "", eq[i].stable);
  fprintf(S->f, "\nstatic_limit_point = ");
  for (int i = 0; i < n; i++) fprintf(S->f, "%s%d", i ? ", " : "", eq[i].limit_point);
  fprintf(S->f, "\n");
  double llp[HMSA_MAX_ROOTS], slp[HMSA_MAX_ROOTS];
  int nlp;
  SA_CHECK(hmsa_static_limit_points(m, b2, llp, slp, &nlp));
  fprintf(S->f, "limit_point_lambda3 = ");
  for (int i = 0; i < nlp; i++) fprintf(S->f, "%s%.10g", i ? ", " : "", 1.0 / (llp[i] * llp[i]));
  fprintf(S->f, "\nlimit_point_S = ");
  for (int i = 0; i < nlp; i++) fprintf(S->f, "%s%.10g", i ? ", " : "", slp[i]);
  fprintf(S->f, "\n");
  /* frequencies of the stable equilibrium closest to the rest state */
  int best = -1;
  for (int i = 0; i < n; i++)
    if (eq[i].stable && (best < 0 || fabs(eq[i].lambda - 1) < fabs(eq[best].lambda - 1))) best = i;
  if (best >= 0) {
    sum_real(S, "omega_relaxed", eq[best].omega_r);
    sum_real(S, "omega_frozen", eq[best].omega_u);
    sum_real(S, "omega_damped", eq[best].omega_d);
    sum_real(S, "zeta", eq[best].zeta);
    if (m->model == HMSA_ZENER) sum_real(S, "creep_rate", eq[best].creep);
    if (eq0) *eq0 = eq[best];
  } else if (eq0) {
    memset(eq0, 0, sizeof *eq0);
  }
  return 0;
}

static int open_summary(const SaRun *run, SaFile **sf) {
  char path[SA_STR_MAX];
  SA_CHECK(sa_run_path(run, "summary.ini", path));
  SA_CHECK(sa_file_open(path, sf));
  return 0;
}

/* ------------------------------------------------------------------ figure texts */

/* Appends ", " + text to buf. */
static void join(char *buf, size_t n, const char *text) {
  size_t k = strlen(buf);
  if (text[0]) snprintf(buf + k, n - k, "%s%s", k ? ", " : "", text);
}

/* The parameters common to every variant of the scene, for figure titles. */
static void scene_title(const HmsaScene *s, char *buf, size_t n) {
  const HmsaModel *m = &s->var[0].m;
  char t[160];
  buf[0] = 0;
  int statics = !strcmp(s->p.analysis, "statics");
  if (statics) snprintf(t, sizeof t, "%s", m->model == HMSA_ZENER ? "Zener" : "polymer chain");
  else if (m->model == HMSA_ZENER) snprintf(t, sizeof t, "Zener (β = %g, c = %g)", m->beta, m->c);
  else snprintf(t, sizeof t, "polymer chain (c = %g)", m->c);
  join(buf, n, t);
  for (int d = 0; d < s->ndim; d++)
    if (s->dim_list[d]->n == 1 && !(statics && !strcmp(s->dim_name[d], "eta"))) {
      dim_label(t, sizeof t, s->dim_name[d], s->dim_list[d]->v[0]);
      join(buf, n, t);
    }
  int sweep = !strcmp(s->p.analysis, "sweep");
  if (m->loading == HMSA_LOAD_CONST) {
    if (strcmp(s->p.analysis, "statics")) join(buf, n, "step load at τ = 0");
  } else if (m->loading == HMSA_LOAD_SQ) {
    snprintf(t, sizeof t, "b^2 = σ b_a^2 sin^2(Ωτ), b_a = %g", m->b_a);
    join(buf, n, t);
  } else {
    snprintf(t, sizeof t, "b^2 = %g %c %g sin(Ωτ)", m->b2_dc, m->b2_ac < 0 ? '-' : '+',
             fabs(m->b2_ac));
    join(buf, n, t);
  }
  if (m->loading != HMSA_LOAD_CONST && !sweep) {
    snprintf(t, sizeof t, "Ω = %g", m->omega);
    join(buf, n, t);
  }
}

/* The listed (multi-valued) parameters of a variant, except dimension `skip` (-1: none). */
static void variant_text(const HmsaScene *s, const HmsaVariant *v, int skip, char *buf, size_t n) {
  buf[0] = 0;
  for (int d = 0; d < s->ndim; d++) {
    if (d == skip || s->dim_list[d]->n == 1) continue;
    char t[96];
    dim_label(t, sizeof t, s->dim_name[d], s->dim_list[d]->v[v->idx[d]]);
    join(buf, n, t);
  }
}

/* Renders a figure into the run folder; plots are optional, a failure is only logged. */
static void figure_write(const SaRun *run, const char *png, const HmsaFigure *f) {
  char pp[SA_STR_MAX];
  if (sa_run_path(run, png, pp) || hmsa_figure_render(pp, f)) sa_error_clear();
}

/* Overlay layout: the curves of a panel differ in dimension cd (the outermost listed one), the
 * panels in the other listed dimensions: two of them span rows x columns, one or more than two
 * are laid out three (or two, for four panels) to a row. */
typedef struct {
  int cd;                    /* curve dimension, -1: one curve per panel */
  int npd, pd[HMSA_MAX_DIMS];
  int rows, cols, npanels;
} Layout;

static int layout_make(const HmsaScene *s, int cd, Layout *L) {
  memset(L, 0, sizeof *L);
  L->cd = cd;
  L->npanels = 1;
  for (int d = 0; d < s->ndim; d++)
    if (s->dim_list[d]->n > 1 && d != cd) {
      L->pd[L->npd++] = d;
      L->npanels *= s->dim_list[d]->n;
    }
  if (L->npanels > HMSA_FIG_MAX_PANELS) return -1;
  if (L->npd == 2 && s->dim_list[L->pd[1]]->n <= 4) {
    L->rows = s->dim_list[L->pd[0]]->n;
    L->cols = s->dim_list[L->pd[1]]->n;
  } else {
    L->cols = L->npanels <= 3 ? L->npanels : L->npanels == 4 ? 2 : 3;
    L->rows = (L->npanels + L->cols - 1) / L->cols;
  }
  return 0;
}

static int layout_panel(const HmsaScene *s, const Layout *L, const HmsaVariant *v) {
  int p = 0;
  for (int i = 0; i < L->npd; i++) p = p * s->dim_list[L->pd[i]]->n + v->idx[L->pd[i]];
  return p;
}

/* The first listed dimension, the one the curves of an overlay differ in (-1: none). */
static int curve_dim(const HmsaScene *s) {
  for (int d = 0; d < s->ndim; d++)
    if (s->dim_list[d]->n > 1) return d;
  return -1;
}

/* Overlay figure skeleton: title, panel titles and one legend entry per curve value. */
static int overlay_begin(const HmsaScene *s, const Layout *L, HmsaFigure *f, HmsaCurveKind kind) {
  hmsa_figure_init(f);
  scene_title(s, f->title, sizeof f->title);
  f->rows = L->rows, f->cols = L->cols, f->npanels = L->npanels;
  for (int i = 0; i < s->nvar; i++) {
    const HmsaVariant *v = &s->var[i];
    HmsaPanel *P = &f->panel[layout_panel(s, L, v)];
    if (!P->title[0]) variant_text(s, v, L->cd, P->title, sizeof P->title);
    if (L->cd >= 0) {
      char t[96];
      dim_label(t, sizeof t, s->dim_name[L->cd], s->dim_list[L->cd]->v[v->idx[L->cd]]);
      hmsa_figure_legend(f, t, v->idx[L->cd], kind);
    }
  }
  return 0;
}

static int curve_color(const Layout *L, const HmsaVariant *v) { return L->cd >= 0 ? v->idx[L->cd] : 0; }

/* ------------------------------------------------------------------ history */

static int run_history(const HmsaScene *s, HmsaVariant *v, const SaRun *run, Summary *S) {
  const HmsaModel *m = &v->m;
  int zener = m->model == HMSA_ZENER;
  HmsaEquilibrium eq;
  SA_CHECK(write_statics(S, m, &eq));
  char csv[256], png[256], path[SA_STR_MAX];
  file_name(csv, sizeof csv, "history", v->tag, "csv");
  SA_CHECK(sa_run_path(run, csv, path));
  const char *names[] = {"tau", "lambda", "dlambda_dtau", "lambda3", "dlambda3_dtau", "xi"};
  const char *units[] = {"-", "-", "-", "-", "-", "-"};
  SaCsv *t;
  SA_CHECK(sa_csv_open(path, zener ? 6 : 5, names, units, &t));
  long N = (long)floor(s->p.t_end / s->p.dt_out + 1e-9);
  /* a long history is plotted from a decimated copy (extremes of lambda3 and dlambda3/dtau per
   * bin of ~half a pixel column kept): gnuplot needs minutes for 1e6 rows */
  snprintf(v->plot_csv, sizeof v->plot_csv, "%s", csv);
  SaCsv *td = NULL;
  HmsaDecimator *dec = NULL;
  int rc = 0;
  if (run->params.plots && N + 1 > HMSA_PLOT_MAX_ROWS) {
    char dpath[SA_STR_MAX];
    snprintf(v->plot_csv, sizeof v->plot_csv, "history%s%s_decimated.csv", v->tag[0] ? "_" : "",
             v->tag);
    rc = sa_run_path(run, v->plot_csv, dpath);
    if (!rc) rc = sa_csv_open(dpath, zener ? 6 : 5, names, units, &td);
    if (!rc)
      rc = hmsa_decimator_create(N + 1, zener ? 6 : 5, HMSA_PLOT_BINS, (1u << 3) | (1u << 4), td,
                                 &dec);
    if (rc) {
      if (td) sa_csv_abort(&td);
      sa_csv_abort(&t);
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
  }
  HmsaIntegrator *it;
  rc = hmsa_integrator_create(m, &s->io, &it);
  if (rc) {
    sa_csv_abort(&t);
    if (td) sa_csv_abort(&td);
    hmsa_decimator_destroy(&dec);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  double y[HMSA_NEQ_MAX];
  hmsa_model_rest(m, y);
  rc = hmsa_integrator_reset(it, 0.0, y);
  double T0, U0;
  hmsa_model_energy(m, y, hmsa_model_b2(m, 0.0), &T0, &U0);
  double l3min = 1, l3max = 1, t0 = sa_time_now(), diss = 0.0, dprev = 0.0, tprev = 0.0;
  double row[6];
  long k;
  for (k = 0; !rc && k <= N; k++) {
    double tau = k * s->p.dt_out;
    if (k > 0) rc = hmsa_integrator_advance(it, tau, y);
    if (rc) break;
    /* every row: the check is a flag read; with large steps many rows come from dense output
     * (the integrator polls per step) */
    if (sa_interrupted()) { rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted"); break; }
    row[0] = tau, row[1] = y[0], row[2] = y[1], row[3] = hmsa_lambda3(y), row[4] = hmsa_dlambda3(y);
    if (zener) row[5] = y[2];
    rc = sa_csv_row(t, row);
    if (!rc && dec) rc = hmsa_decimator_push(dec, row);
    l3min = fmin(l3min, row[3]);
    l3max = fmax(l3max, row[3]);
    double d = hmsa_model_dissipation(m, y, 0.0);
    if (k > 0) diss += 0.5 * (d + dprev) * (tau - tprev);
    dprev = d, tprev = tau;
  }
  double secs = sa_time_now() - t0;
  /* keep the rows computed so far, also after a failure or an interruption */
  int rc2 = sa_csv_commit(&t);
  if (!rc) rc = rc2;
  if (dec) {
    rc2 = hmsa_decimator_finish(dec);
    if (!rc2) sum_int(S, "plot_rows", hmsa_decimator_kept(dec));
    if (!rc2) rc2 = sa_csv_commit(&td); else sa_csv_abort(&td);
    hmsa_decimator_destroy(&dec);
    if (!rc) rc = rc2;
  }
  sum_real(S, "tau_end", (k - 1) * s->p.dt_out);
  sum_real(S, "lambda3_min", l3min);
  sum_real(S, "lambda3_max", l3max);
  sum_real(S, "lambda3_end", hmsa_lambda3(y));
  sum_stats(S, it, secs);
  if (m->loading == HMSA_LOAD_CONST) {
    double T1, U1;
    if (!hmsa_model_energy(m, y, m->b2, &T1, &U1)) {
      sum_real(S, "energy_start", T0 + U0);
      sum_real(S, "energy_end", T1 + U1);
      if (zener) sum_real(S, "energy_dissipated", diss);
      sum_real(S, "energy_balance_error", T1 + U1 + diss - (T0 + U0));
    }
  }
  hmsa_integrator_destroy(&it);
  if (rc) {
    sum_str(S, "failure", sa_error_message());
    return rc;
  }
  if (zener && m->loading == HMSA_LOAD_CONST && eq.lambda3 > 0 && eq.lambda3 != 1.0) {
    double ts;
    SA_CHECK(hmsa_settling_time(m, &s->io, eq.lambda3, s->p.t_end, &ts));
    sum_real(S, "settling_time", ts);
  }
  v->ok = 1;
  if (run->params.plots) {
    HmsaFigure f;
    for (int phase = 0; phase < 2; phase++) {
      hmsa_figure_init(&f);
      scene_title(s, f.title, sizeof f.title);
      variant_text(s, v, -1, f.panel[0].title, sizeof f.panel[0].title);
      snprintf(f.xlabel, sizeof f.xlabel, "%s", phase ? "λ_3" : "τ");
      snprintf(f.ylabel, sizeof f.ylabel, "%s", phase ? "dλ_3/dτ" : "λ_3");
      hmsa_figure_curve(&f, 0, v->plot_csv, phase ? "4:5" : "1:4", 0, HMSA_CURVE_LINE);
      file_name(png, sizeof png, phase ? "phase" : "history", v->tag, "png");
      figure_write(run, png, &f);
    }
  }
  return 0;
}

/* ------------------------------------------------------------------ statics scene */

/* equilibria_TAG.csv: the equilibria at the variant's S (kind 0) and the limit points of the
 * path (kind 1, K_r = 0). */
static int write_equilibria(const HmsaModel *m, const char *tag, const SaRun *run) {
  double b2 = hmsa_model_b2_mean(m);
  HmsaEquilibrium eq[HMSA_MAX_ROOTS];
  double llp[HMSA_MAX_ROOTS], slp[HMSA_MAX_ROOTS];
  int n, nlp;
  SA_CHECK(hmsa_static_solve(m, b2, eq, &n));
  SA_CHECK(hmsa_static_limit_points(m, b2, llp, slp, &nlp));
  char csv[256], path[SA_STR_MAX];
  file_name(csv, sizeof csv, "equilibria", tag, "csv");
  SA_CHECK(sa_run_path(run, csv, path));
  const char *names[] = {"lambda", "lambda3", "S", "K_r", "stable", "kind"};
  const char *units[] = {"-", "-", "-", "-", "1 stable", "0 equilibrium/1 limit point"};
  SaCsv *t;
  SA_CHECK(sa_csv_open(path, 6, names, units, &t));
  int rc = 0;
  for (int i = 0; !rc && i < n; i++) {
    double row[6] = {eq[i].lambda, eq[i].lambda3, m->S, eq[i].K_r, eq[i].stable, 0};
    rc = sa_csv_row(t, row);
  }
  for (int i = 0; !rc && i < nlp; i++) {
    double row[6] = {llp[i], 1.0 / (llp[i] * llp[i]), slp[i], 0, 0, 1};
    rc = sa_csv_row(t, row);
  }
  if (!rc) rc = sa_csv_commit(&t); else sa_csv_abort(&t);
  return rc;
}

/* Axis window of the statics figures: every equilibrium and limit point of the variants
 * listed, the rest state, with a margin (the path itself runs to lambda3 = 25). */
static void statics_window(const HmsaScene *s, int only, HmsaFigure *f) {
  double xmax = 1.2, ymin = 0.0, ymax = 1.0;
  for (int i = 0; i < s->nvar; i++) {
    if (only >= 0 && i != only) continue;
    const HmsaModel *m = &s->var[i].m;
    double b2 = hmsa_model_b2_mean(m), llp[HMSA_MAX_ROOTS], slp[HMSA_MAX_ROOTS];
    HmsaEquilibrium eq[HMSA_MAX_ROOTS];
    int n = 0, nlp = 0;
    if (hmsa_static_solve(m, b2, eq, &n)) { sa_error_clear(); n = 0; }
    if (hmsa_static_limit_points(m, b2, llp, slp, &nlp)) { sa_error_clear(); nlp = 0; }
    for (int k = 0; k < n; k++) xmax = fmax(xmax, eq[k].lambda3);
    ymin = fmin(ymin, m->S), ymax = fmax(ymax, m->S);
    for (int k = 0; k < nlp; k++) {
      xmax = fmax(xmax, 1.0 / (llp[k] * llp[k]));
      ymin = fmin(ymin, slp[k]), ymax = fmax(ymax, slp[k]);
    }
  }
  f->xr[0] = 0.0, f->xr[1] = 1.25 * xmax;
  double pad = 0.25 * (ymax - ymin) + 0.5;
  f->yr[0] = ymin - pad, f->yr[1] = ymax + pad;
}

/* Path (stable solid, unstable dashed), equilibria (filled stable, open unstable) and limit
 * points (crosses) of one variant into panel 0 of f, in colour c. */
static void statics_curves(HmsaFigure *f, const char *path_csv, const char *eq_csv, int c) {
  hmsa_figure_curve(f, 0, path_csv, "2:($5==1?$3:1/0)", c, HMSA_CURVE_LINE);
  hmsa_figure_curve(f, 0, path_csv, "2:($5==0?$3:1/0)", c, HMSA_CURVE_DASH);
  hmsa_figure_curve(f, 0, eq_csv, "2:($6==1?$3:1/0)", c, HMSA_CURVE_MARK);
  hmsa_figure_curve(f, 0, eq_csv, "2:($6==0&&$5==1?$3:1/0)", c, HMSA_CURVE_POINTS);
  hmsa_figure_curve(f, 0, eq_csv, "2:($6==0&&$5==0?$3:1/0)", c, HMSA_CURVE_OPEN);
}

static void statics_legend(HmsaFigure *f) {
  hmsa_figure_legend(f, "stable (K_r > 0)", 6, HMSA_CURVE_LINE);
  hmsa_figure_legend(f, "unstable", 6, HMSA_CURVE_DASH);
  hmsa_figure_legend(f, "equilibrium, stable", 6, HMSA_CURVE_POINTS);
  hmsa_figure_legend(f, "equilibrium, unstable", 6, HMSA_CURVE_OPEN);
  hmsa_figure_legend(f, "limit point", 6, HMSA_CURVE_MARK);
}

static int run_statics(const HmsaScene *s, HmsaVariant *v, const SaRun *run, Summary *S) {
  const HmsaModel *m = &v->m;
  SA_CHECK(write_statics(S, m, NULL));
  /* the relaxed equilibrium path in the prestress: S(lambda) = F_r + S at the mean load */
  double b2 = hmsa_model_b2_mean(m), lo = 0.2, hi = 5.0;
  if (m->model == HMSA_PC) SA_CHECK(hmsa_model_pc_domain(m, &lo, &hi));
  char csv[256], png[256], path[SA_STR_MAX];
  file_name(csv, sizeof csv, "statics", v->tag, "csv");
  SA_CHECK(sa_run_path(run, csv, path));
  const char *names[] = {"lambda", "lambda3", "S", "K_r", "stable"};
  const char *units[] = {"-", "-", "-", "-", "-"};
  SaCsv *t;
  SA_CHECK(sa_csv_open(path, 5, names, units, &t));
  const int N = 2000;
  for (int i = 1; i < N; i++) {
    double l = lo + (hi - lo) * i / N, F, K;
    if (hmsa_static_force(m, l, b2, &F, &K)) continue;
    double row[5] = {l, 1.0 / (l * l), F + m->S, K, K > 0};
    int rc = sa_csv_row(t, row);
    if (rc) { sa_csv_abort(&t); return sa_error_push(rc, __func__, __FILE__, __LINE__); }
  }
  SA_CHECK(sa_csv_commit(&t));
  SA_CHECK(write_equilibria(m, v->tag, run));
  v->ok = 1;
  if (run->params.plots) {
    char eqcsv[256];
    file_name(eqcsv, sizeof eqcsv, "equilibria", v->tag, "csv");
    HmsaFigure f;
    hmsa_figure_init(&f);
    snprintf(f.title, sizeof f.title, "relaxed equilibria: ");
    scene_title(s, f.title + strlen(f.title), sizeof f.title - strlen(f.title));
    variant_text(s, v, -1, f.panel[0].title, sizeof f.panel[0].title);
    snprintf(f.xlabel, sizeof f.xlabel, "λ_3");
    snprintf(f.ylabel, sizeof f.ylabel, "prestress S");
    statics_window(s, (int)(v - s->var), &f);
    statics_curves(&f, csv, eqcsv, 0);
    statics_legend(&f);
    file_name(png, sizeof png, "statics", v->tag, "png");
    figure_write(run, png, &f);
  }
  return 0;
}

/* ------------------------------------------------------------------ poincare scene */

static void poincare_figure(const HmsaScene *s, HmsaFigure *f) {
  hmsa_figure_init(f);
  snprintf(f->title, sizeof f->title, "steady orbit and Poincaré section: ");
  scene_title(s, f->title + strlen(f->title), sizeof f->title - strlen(f->title));
  snprintf(f->xlabel, sizeof f->xlabel, "λ_3");
  snprintf(f->ylabel, sizeof f->ylabel, "dλ_3/dτ");
}

/* orbit (last periods) in colour c, section points in black */
static void poincare_curves(HmsaFigure *f, int p, const HmsaVariant *v, int c) {
  char ocsv[256], pcsv[256];
  file_name(ocsv, sizeof ocsv, "orbit", v->tag, "csv");
  file_name(pcsv, sizeof pcsv, "poincare", v->tag, "csv");
  hmsa_figure_curve(f, p, ocsv, "4:5", c, HMSA_CURVE_THIN);
  hmsa_figure_curve(f, p, pcsv, "5:6", 6, HMSA_CURVE_DOTS);
  hmsa_figure_legend(f, "Poincaré section, τ = 2πn/Ω", 6, HMSA_CURVE_DOTS);
}

static int run_poincare(const HmsaScene *s, HmsaVariant *v, const SaRun *run, Summary *S,
                        SaProgress *prog) {
  const HmsaModel *m = &v->m;
  int n = hmsa_model_neq(m), zener = m->model == HMSA_ZENER;
  SA_CHECK(write_statics(S, m, NULL));
  int np = s->pc.n_points;
  double *x = calloc((size_t)np * n, sizeof *x);
  if (!x) return SA_ERROR(SA_ERR_MEMORY, "Poincare samples");
  double y0[HMSA_NEQ_MAX], lyap = NAN, t0 = sa_time_now();
  hmsa_model_rest(m, y0);
  int rc = hmsa_poincare(m, &s->io, y0, s->pc.transient_periods, np, s->pc.d0, x,
                         s->pc.lyapunov ? &lyap : NULL, prog);
  double T = hmsa_model_period(m);
  char csv[256], png[256], path[SA_STR_MAX];
  if (!rc) {
    file_name(csv, sizeof csv, "poincare", v->tag, "csv");
    rc = sa_run_path(run, csv, path);
    const char *names[] = {"n", "tau", "lambda", "dlambda_dtau", "lambda3", "dlambda3_dtau", "xi"};
    const char *units[] = {"-", "-", "-", "-", "-", "-", "-"};
    SaCsv *t = NULL;
    if (!rc) rc = sa_csv_open(path, zener ? 7 : 6, names, units, &t);
    for (int j = 0; !rc && j < np; j++) {
      const double *y = x + (size_t)j * n;
      double row[7] = {s->pc.transient_periods + j + 1, (s->pc.transient_periods + j + 1) * T,
                       y[0], y[1], hmsa_lambda3(y), hmsa_dlambda3(y), zener ? y[2] : 0};
      rc = sa_csv_row(t, row);
    }
    if (!rc) rc = sa_csv_commit(&t); else sa_csv_abort(&t);
  }
  if (!rc) {
    HmsaClassifyResult cr;
    rc = hmsa_poincare_classify(np, n, x, s->pc.lyapunov ? lyap : NAN, NULL, &cr);
    if (!rc) {
      char cls[64];
      if (cr.kind == HMSA_ORBIT_PERIODIC) snprintf(cls, sizeof cls, "period-%d", cr.period);
      else snprintf(cls, sizeof cls, "%s", hmsa_orbit_kind_name(cr.kind));
      sum_str(S, "classification", cls);
      sum_real(S, "poincare_mismatch", cr.mismatch);
      if (s->pc.lyapunov) {
        sum_real(S, "lyapunov_max", lyap / T);
        sum_real(S, "lyapunov_per_period", lyap);
      }
      if (isfinite(cr.lyap_data)) sum_real(S, "lyapunov_data_per_period", cr.lyap_data);
      if (isfinite(cr.dim_corr)) sum_real(S, "correlation_dimension", cr.dim_corr);
    }
  }
  /* steady orbit for the phase plane: orbit_periods periods from the last sample */
  if (!rc) {
    HmsaIntegrator *it = NULL;
    rc = hmsa_integrator_create(m, &s->io, &it);
    double tau0 = (s->pc.transient_periods + np) * T;
    if (!rc) rc = hmsa_integrator_reset(it, tau0, x + (size_t)(np - 1) * n);
    file_name(csv, sizeof csv, "orbit", v->tag, "csv");
    SaCsv *t = NULL;
    const char *names[] = {"tau", "lambda", "dlambda_dtau", "lambda3", "dlambda3_dtau", "xi"};
    const char *units[] = {"-", "-", "-", "-", "-", "-"};
    if (!rc) rc = sa_run_path(run, csv, path);
    if (!rc) rc = sa_csv_open(path, zener ? 6 : 5, names, units, &t);
    int per = 256, N = s->pc.orbit_periods * per;
    double y[HMSA_NEQ_MAX];
    for (int i = 0; i < n; i++) y[i] = x[(size_t)(np - 1) * n + i];
    for (int k = 0; !rc && k <= N; k++) {
      double tau = tau0 + (double)k * T / per;
      if (sa_interrupted()) rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted");
      if (!rc && k > 0) rc = hmsa_integrator_advance(it, tau, y);
      double row[6] = {tau, y[0], y[1], hmsa_lambda3(y), hmsa_dlambda3(y), zener ? y[2] : 0};
      if (!rc) rc = sa_csv_row(t, row);
    }
    if (!rc) rc = sa_csv_commit(&t); else sa_csv_abort(&t);
    if (it) sum_stats(S, it, sa_time_now() - t0);
    hmsa_integrator_destroy(&it);
  }
  free(x);
  if (rc) {
    sum_str(S, "failure", sa_error_message());
    return rc;
  }
  if (run->params.plots) {
    HmsaFigure f;
    poincare_figure(s, &f);
    variant_text(s, v, -1, f.panel[0].title, sizeof f.panel[0].title);
    char t[96];
    snprintf(t, sizeof t, "steady orbit, last %d periods", s->pc.orbit_periods);
    hmsa_figure_legend(&f, t, 0, HMSA_CURVE_THIN);
    poincare_curves(&f, 0, v, 0);
    file_name(png, sizeof png, "poincare", v->tag, "png");
    figure_write(run, png, &f);
  }
  v->ok = 1;
  return 0;
}

/* ------------------------------------------------------------------ sweep scene */

static void sweep_figure(const HmsaScene *s, HmsaFigure *f, int inplane) {
  hmsa_figure_init(f);
  snprintf(f->title, sizeof f->title, "steady amplitude: ");
  scene_title(s, f->title + strlen(f->title), sizeof f->title - strlen(f->title));
  snprintf(f->xlabel, sizeof f->xlabel, "forcing frequency Ω");
  snprintf(f->ylabel, sizeof f->ylabel, "%s", inplane ? "a = (max λ - min λ)/2" : "a_3 = (max λ_3 - min λ_3)/2");
  f->yr[0] = 0.0;
}

typedef struct {
  HmsaModel m;
  HmsaIntegrator *it;
  const HmsaSteadyOptions *so;
  double last_a;
} PeakCtx;

static int peak_amplitude(double omega, double *amp, void *ctx) {
  PeakCtx *pc = ctx;
  pc->m.omega = omega;
  double y0[HMSA_NEQ_MAX];
  hmsa_model_rest(&pc->m, y0);
  HmsaSteady st;
  int rc = hmsa_steady_amplitude(pc->it, &pc->m, pc->so, y0, &st);
  if (rc) return rc;
  *amp = st.a3;
  pc->last_a = st.a;
  return 0;
}

static int run_sweep(const HmsaScene *s, HmsaVariant *v, const SaRun *run, Summary *S) {
  const HmsaModel *m = &v->m;
  HmsaEquilibrium eq;
  SA_CHECK(write_statics(S, m, &eq));
  const HmsaSweepParams *w = &s->sw;
  int n = w->n_omega;
  HmsaSteadyOptions so = {w->transient_periods, w->transient_tau, w->measure_periods,
                          w->samples_per_period};
  double *buf = calloc((size_t)n * 7, sizeof *buf);
  int *status = calloc((size_t)n, sizeof *status);
  if (!buf || !status) { free(buf); free(status); return SA_ERROR(SA_ERR_MEMORY, "sweep arrays"); }
  double *om = buf, *a3 = buf + n, *a = buf + 2 * n, *ua3 = buf + 3 * n, *ua = buf + 4 * n;
  double *da3 = buf + 5 * n, *da = buf + 6 * n;
  for (int i = 0; i < n; i++) {
    om[i] = w->omega_min + (w->omega_max - w->omega_min) * i / (n - 1);
    ua3[i] = ua[i] = da3[i] = da[i] = NAN;
  }
  SaProgress *prog = NULL;
  char label[160];
  snprintf(label, sizeof label, "hmsa sweep %s", v->tag);
  if (sa_progress_start(label, (long)n * (w->continuation ? 3 : 1), &prog)) sa_error_clear();
  double t0 = sa_time_now();
  int rc = hmsa_sweep_rest(m, &s->io, &so, n, om, run->threads, prog, a3, a, status);
  if (!rc && w->continuation)
    rc = hmsa_sweep_continuation(m, &s->io, &so, n, om, run->threads, prog, ua3, ua, da3, da);
  sa_progress_finish(&prog);
  sa_timing_add("hmsa sweep", sa_time_now() - t0);
  /* write what was computed, also after an interruption */
  char csv[256], csv2[256], png[256], path[SA_STR_MAX];
  const char *names[] = {"omega", "amplitude", "branch"};
  const char *units[] = {"-", "-", "0 rest/1 up/2 down"};
  for (int pass = 0; pass < 2; pass++) {
    const char *stem = pass ? "sweep_inplane" : "sweep";
    file_name(pass ? csv2 : csv, sizeof csv, stem, v->tag, "csv");
    SaCsv *t;
    int r2 = sa_run_path(run, pass ? csv2 : csv, path);
    if (!r2) r2 = sa_csv_open(path, 3, names, units, &t);
    for (int b = 0; !r2 && b < 3; b++) {
      const double *amp = b == 0 ? (pass ? a : a3) : b == 1 ? (pass ? ua : ua3) : (pass ? da : da3);
      for (int i = 0; !r2 && i < n; i++) {
        if (!isfinite(amp[i])) continue;
        double row[3] = {om[i], amp[i], b};
        r2 = sa_csv_row(t, row);
      }
    }
    if (!r2) r2 = sa_csv_commit(&t); else sa_csv_abort(&t);
    if (r2 && !rc) rc = r2;
  }
  if (rc) {
    sum_str(S, "failure", sa_error_message());
    free(buf);
    free(status);
    return rc;
  }
  /* peaks of the from-rest sweep, refined by golden section on the from-rest amplitude */
  PeakCtx pc = {.m = *m, .it = NULL, .so = &so, .last_a = NAN};
  HmsaPeakParams pp = hmsa_peak_params_default();
  pp.prominence_rel = w->prominence;
  HmsaPeak peaks[16];
  int npk = 0;
  double omega_p = m->loading == HMSA_LOAD_SQ ? 0.5 * eq.omega_d : eq.omega_d;
  rc = hmsa_integrator_create(&pc.m, &s->io, &pc.it);
  if (!rc)
    rc = hmsa_peaks_find(n, om, a3, &pp, w->refine ? peak_amplitude : NULL, &pc, -1.0, 16, peaks,
                         &npk);
  /* the in-plane amplitude at the primary (largest) peak */
  int prim = -1;
  for (int i = 0; i < npk; i++)
    if (prim < 0 || peaks[i].amp > peaks[prim].amp) prim = i;
  double a_peak = NAN;
  if (!rc && prim >= 0) {
    double amp;
    rc = peak_amplitude(peaks[prim].omega, &amp, &pc);
    a_peak = pc.last_a;
  }
  hmsa_integrator_destroy(&pc.it);
  if (rc) {
    sum_str(S, "failure", sa_error_message());
    free(buf);
    free(status);
    return rc;
  }
  sum_real(S, "sweep_seconds", sa_time_now() - t0);
  {
    /* peaks_TAG.csv: the refined peaks of the from-rest sweep, for the figures */
    char pcsv[256], ppath[SA_STR_MAX];
    const char *pn[] = {"omega", "amplitude", "primary"}, *pu[] = {"-", "-", "1 primary"};
    SaCsv *t = NULL;
    file_name(pcsv, sizeof pcsv, "peaks", v->tag, "csv");
    int r2 = sa_run_path(run, pcsv, ppath);
    if (!r2) r2 = sa_csv_open(ppath, 3, pn, pu, &t);
    for (int i = 0; !r2 && i < npk; i++) {
      double row[3] = {peaks[i].omega, peaks[i].amp, i == prim};
      r2 = sa_csv_row(t, row);
    }
    if (!r2) r2 = sa_csv_commit(&t); else if (t) sa_csv_abort(&t);
    if (r2) { free(buf); free(status); return sa_error_push(r2, __func__, __FILE__, __LINE__); }
  }
  sum_real(S, "omega_primary_estimate", omega_p);
  if (prim >= 0) {
    sum_real(S, "peak_omega", peaks[prim].omega);
    sum_real(S, "peak_amplitude", peaks[prim].amp);
    sum_real(S, "peak_amplitude_inplane", a_peak);
  }
  fprintf(S->f, "peaks_omega = ");
  for (int i = 0; i < npk; i++) fprintf(S->f, "%s%.8g", i ? ", " : "", peaks[i].omega);
  fprintf(S->f, "\npeaks_amplitude = ");
  for (int i = 0; i < npk; i++) fprintf(S->f, "%s%.8g", i ? ", " : "", peaks[i].amp);
  fprintf(S->f, "\npeaks_kind = ");
  for (int i = 0; i < npk; i++) {
    HmsaPeakKind kind;
    int order;
    hmsa_peak_label(peaks[i].omega, prim >= 0 ? peaks[prim].omega : omega_p, &pp, &kind, &order,
                    NULL);
    if (kind == HMSA_PEAK_PRIMARY || kind == HMSA_PEAK_OTHER)
      fprintf(S->f, "%s%s", i ? ", " : "", hmsa_peak_kind_name(kind));
    else
      fprintf(S->f, "%s%s-%d", i ? ", " : "", hmsa_peak_kind_name(kind), order);
  }
  fprintf(S->f, "\n");
  if (w->continuation) {
    int iu = -1, id = -1;
    double hyst = 0.0;
    for (int i = 0; i < n; i++) {
      if (isfinite(ua3[i]) && (iu < 0 || ua3[i] > ua3[iu])) iu = i;
      if (isfinite(da3[i]) && (id < 0 || da3[i] > da3[id])) id = i;
      if (isfinite(ua3[i]) && isfinite(da3[i])) hyst = fmax(hyst, fabs(ua3[i] - da3[i]));
    }
    if (iu >= 0) sum_real(S, "peak_omega_up", om[iu]), sum_real(S, "peak_amplitude_up", ua3[iu]);
    if (id >= 0) sum_real(S, "peak_omega_down", om[id]), sum_real(S, "peak_amplitude_down", da3[id]);
    sum_real(S, "hysteresis_max_difference", hyst);
  }
  free(buf);
  free(status);
  v->ok = 1;
  if (run->params.plots) {
    for (int pass = 0; pass < 2; pass++) {
      HmsaFigure f;
      sweep_figure(s, &f, pass);
      variant_text(s, v, -1, f.panel[0].title, sizeof f.panel[0].title);
      const char *c = pass ? csv2 : csv;
      hmsa_figure_curve(&f, 0, c, "1:($3==0?$2:1/0)", 0, HMSA_CURVE_LINEPOINTS);
      hmsa_figure_legend(&f, "from rest", 0, HMSA_CURVE_LINEPOINTS);
      if (!pass) {
        char pcsv[256];
        file_name(pcsv, sizeof pcsv, "peaks", v->tag, "csv");
        hmsa_figure_curve(&f, 0, pcsv, "1:2", 6, HMSA_CURVE_MARK);
        hmsa_figure_legend(&f, "peak (golden section)", 6, HMSA_CURVE_MARK);
      }
      if (w->continuation) {
        hmsa_figure_curve(&f, 0, c, "1:($3==1?$2:1/0)", 1, HMSA_CURVE_LINE);
        hmsa_figure_curve(&f, 0, c, "1:($3==2?$2:1/0)", 2, HMSA_CURVE_DASH);
        hmsa_figure_legend(&f, "continuation, Ω increasing", 1, HMSA_CURVE_LINE);
        hmsa_figure_legend(&f, "continuation, Ω decreasing", 2, HMSA_CURVE_DASH);
      }
      file_name(png, sizeof png, pass ? "sweep_inplane" : "sweep", v->tag, "png");
      figure_write(run, png, &f);
    }
  }
  return 0;
}

/* ------------------------------------------------------------------ run */

/* Histories under a step load: the relaxed equilibrium lambda3 of each panel, dotted, where
 * every curve of the panel has the same one (the curve key does not change the statics). */
static void history_reference(const HmsaScene *s, const Layout *L, HmsaFigure *f) {
  if (s->var[0].m.loading != HMSA_LOAD_CONST) return;
  double ref[HMSA_FIG_MAX_PANELS];
  int state[HMSA_FIG_MAX_PANELS] = {0}; /* 0 unset, 1 one value, 2 differs or none */
  for (int i = 0; i < s->nvar; i++) {
    const HmsaVariant *v = &s->var[i];
    int p = layout_panel(s, L, v);
    HmsaEquilibrium eq[HMSA_MAX_ROOTS];
    int n, best = -1;
    if (hmsa_static_solve(&v->m, v->m.b2, eq, &n)) { sa_error_clear(); n = 0; }
    for (int k = 0; k < n; k++)
      if (eq[k].stable && (best < 0 || fabs(eq[k].lambda - 1) < fabs(eq[best].lambda - 1))) best = k;
    if (best < 0) state[p] = 2;
    else if (state[p] == 0) ref[p] = eq[best].lambda3, state[p] = 1;
    else if (state[p] == 1 && fabs(ref[p] - eq[best].lambda3) > 1e-12) state[p] = 2;
  }
  for (int i = 0; i < s->nvar; i++) {
    const HmsaVariant *v = &s->var[i];
    int p = layout_panel(s, L, v);
    if (state[p] != 1 || !v->ok) continue;
    char u[64];
    snprintf(u, sizeof u, "1:(%.12g)", ref[p]);
    hmsa_figure_curve(f, p, v->plot_csv, u, 6, HMSA_CURVE_REF);
    state[p] = 3;
    hmsa_figure_legend(f, "relaxed equilibrium", 6, HMSA_CURVE_REF);
  }
}

/* Figures with every variant (issue 15): overlay_*.png, one per quantity; the curves of a panel
 * differ in the first listed key, the panels in the others (see Layout). */
static void write_overlays(const HmsaScene *s, const SaRun *run) {
  HmsaFigure f;
  Layout L;
  if (!strcmp(s->p.analysis, "statics")) {
    /* the path does not depend on S: one curve per b2, the equilibria of every S on it */
    hmsa_figure_init(&f);
    snprintf(f.title, sizeof f.title, "relaxed equilibria: ");
    scene_title(s, f.title + strlen(f.title), sizeof f.title - strlen(f.title));
    snprintf(f.xlabel, sizeof f.xlabel, "λ_3");
    snprintf(f.ylabel, sizeof f.ylabel, "prestress S");
    statics_window(s, -1, &f);
    int bdim = -1;
    for (int d = 0; d < s->ndim; d++)
      if (!strcmp(s->dim_name[d], "b2")) bdim = d;
    char ptitle[HMSA_FIG_TEXT] = "";
    for (int d = 0; d < s->ndim; d++)
      if (d != bdim && s->dim_list[d]->n > 1 && strcmp(s->dim_name[d], "S")) bdim = -2;
    if (bdim == -2) return; /* other listed keys change the path: per-variant figures only */
    for (int i = 0; i < s->nvar; i++) {
      const HmsaVariant *v = &s->var[i];
      int c = bdim >= 0 ? v->idx[bdim] : 0;
      char path_csv[256], eq_csv[256], t[96];
      file_name(path_csv, sizeof path_csv, "statics", v->tag, "csv");
      file_name(eq_csv, sizeof eq_csv, "equilibria", v->tag, "csv");
      statics_curves(&f, path_csv, eq_csv, c);
      if (bdim >= 0) {
        dim_label(t, sizeof t, "b2", s->dim_list[bdim]->v[v->idx[bdim]]);
        hmsa_figure_legend(&f, t, c, HMSA_CURVE_LINE);
      }
    }
    for (int d = 0; d < s->ndim; d++)
      if (!strcmp(s->dim_name[d], "S") && s->dim_list[d]->n > 1) {
        snprintf(ptitle, sizeof ptitle, "equilibria at S = ");
        for (int k = 0; k < s->dim_list[d]->n; k++) {
          size_t n = strlen(ptitle);
          snprintf(ptitle + n, sizeof ptitle - n, "%s%g", k ? ", " : "", s->dim_list[d]->v[k]);
        }
      }
    snprintf(f.panel[0].title, sizeof f.panel[0].title, "%s", ptitle);
    statics_legend(&f);
    figure_write(run, "overlay_statics.png", &f);
    return;
  }
  if (layout_make(s, curve_dim(s), &L)) {
    sa_log(SA_LOG_INFO, "hmsa", "more than %d panels: no overlay figures", HMSA_FIG_MAX_PANELS);
    return;
  }
  if (!strcmp(s->p.analysis, "history")) {
    for (int phase = 0; phase < 2; phase++) {
      overlay_begin(s, &L, &f, HMSA_CURVE_LINE);
      snprintf(f.xlabel, sizeof f.xlabel, "%s", phase ? "λ_3" : "τ");
      snprintf(f.ylabel, sizeof f.ylabel, "%s", phase ? "dλ_3/dτ" : "λ_3");
      /* phase planes: the least damped (last) curve underneath */
      for (int k = 0; k < s->nvar; k++) {
        const HmsaVariant *v = &s->var[phase ? s->nvar - 1 - k : k];
        if (v->ok)
          hmsa_figure_curve(&f, layout_panel(s, &L, v), v->plot_csv, phase ? "4:5" : "1:4",
                            curve_color(&L, v), HMSA_CURVE_LINE);
      }
      if (!phase) history_reference(s, &L, &f);
      if (!phase && s->var[0].m.model == HMSA_PC) {
        /* no dissipation: the orbit repeats, a few periods compare amplitude and frequency */
        double Tmax = 0.0;
        for (int i = 0; i < s->nvar; i++) {
          HmsaEquilibrium eq[HMSA_MAX_ROOTS];
          int n;
          if (hmsa_static_solve(&s->var[i].m, s->var[i].m.b2, eq, &n)) { sa_error_clear(); continue; }
          for (int k = 0; k < n; k++)
            if (eq[k].stable && eq[k].omega_r > 0) Tmax = fmax(Tmax, 2.0 * HMSA_PI / eq[k].omega_r);
        }
        if (Tmax > 0 && 3.0 * Tmax < s->p.t_end) {
          f.xr[0] = 0.0, f.xr[1] = 3.0 * Tmax;
          size_t k = strlen(f.title);
          snprintf(f.title + k, sizeof f.title - k, ", τ ≤ %.3g shown (of %g)", 3.0 * Tmax, s->p.t_end);
        }
      }
      figure_write(run, phase ? "overlay_phase.png" : "overlay_history.png", &f);
    }
  } else if (!strcmp(s->p.analysis, "poincare")) {
    poincare_figure(s, &f);
    f.rows = L.rows, f.cols = L.cols, f.npanels = L.npanels;
    for (int i = 0; i < s->nvar; i++) {
      const HmsaVariant *v = &s->var[i];
      int p = layout_panel(s, &L, v);
      if (!f.panel[p].title[0]) variant_text(s, v, L.cd, f.panel[p].title, sizeof f.panel[p].title);
      char t[96];
      dim_label(t, sizeof t, s->dim_name[L.cd], s->dim_list[L.cd]->v[v->idx[L.cd]]);
      hmsa_figure_legend(&f, t, curve_color(&L, v), HMSA_CURVE_LINE);
      if (v->ok) poincare_curves(&f, p, v, curve_color(&L, v));
    }
    figure_write(run, "overlay_poincare.png", &f);
  } else {
    for (int pass = 0; pass < 2; pass++) {
      HmsaFigure g;
      sweep_figure(s, &g, pass);
      overlay_begin(s, &L, &f, HMSA_CURVE_LINEPOINTS);
      memcpy(f.title, g.title, sizeof f.title);
      memcpy(f.xlabel, g.xlabel, sizeof f.xlabel);
      memcpy(f.ylabel, g.ylabel, sizeof f.ylabel);
      f.yr[0] = 0.0;
      snprintf(f.title + strlen(f.title), sizeof f.title - strlen(f.title), ", from rest");
      for (int i = 0; i < s->nvar; i++) {
        const HmsaVariant *v = &s->var[i];
        char c[256];
        file_name(c, sizeof c, pass ? "sweep_inplane" : "sweep", v->tag, "csv");
        if (!v->ok) continue;
        hmsa_figure_curve(&f, layout_panel(s, &L, v), c, "1:($3==0?$2:1/0)", curve_color(&L, v),
                          HMSA_CURVE_LINEPOINTS);
        if (!pass) {
          file_name(c, sizeof c, "peaks", v->tag, "csv");
          hmsa_figure_curve(&f, layout_panel(s, &L, v), c, "1:2", 6, HMSA_CURVE_MARK);
          hmsa_figure_legend(&f, "peak (golden section)", 6, HMSA_CURVE_MARK);
        }
      }
      figure_write(run, pass ? "overlay_sweep_inplane.png" : "overlay_sweep.png", &f);
    }
  }
}

static int hmsa_run(void *scene, SaRun *run) {
  HmsaScene *s = scene;
  SaFile *sf = NULL;
  SA_CHECK(open_summary(run, &sf));
  Summary S = {sa_file_stream(sf)};
  fprintf(S.f, "; softact hmsa summary: analysis = %s, model = %s, loading = %s\n",
          s->p.analysis, s->p.model, s->p.loading);
  fprintf(S.f, "variants = %d\n", s->nvar);
  SaProgress *prog = NULL;
  int is_poincare = !strcmp(s->p.analysis, "poincare");
  if (is_poincare) {
    long total = (long)s->nvar * (s->pc.transient_periods + s->pc.n_points);
    if (sa_progress_start("hmsa poincare", total, &prog)) sa_error_clear();
  } else if (!strcmp(s->p.analysis, "history") && s->nvar > 1) {
    if (sa_progress_start("hmsa variants", s->nvar, &prog)) sa_error_clear();
  }
  int rc = 0;
  for (int i = 0; i < s->nvar && !rc; i++) {
    HmsaVariant *v = &s->var[i];
    if (s->nvar > 1) fprintf(S.f, "\n[%s]\n", v->tag);
    double t0 = sa_time_now();
    if (!strcmp(s->p.analysis, "history")) rc = run_history(s, v, run, &S);
    else if (!strcmp(s->p.analysis, "statics")) rc = run_statics(s, v, run, &S);
    else if (is_poincare) rc = run_poincare(s, v, run, &S, prog);
    else rc = run_sweep(s, v, run, &S);
    sa_timing_add("hmsa", sa_time_now() - t0);
    if (!is_poincare && prog) sa_progress_add(prog, 1);
    if (rc == 0 && sa_interrupted()) rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted");
    if (!rc) sa_log(SA_LOG_INFO, "hmsa", "variant %d/%d %s done (%.2f s)", i + 1, s->nvar,
                    v->tag[0] ? v->tag : "(single)", sa_time_now() - t0);
  }
  sa_progress_finish(&prog);
  if (!rc && s->nvar > 1 && run->params.plots) write_overlays(s, run);
  /* the summary keeps what was computed, also after a failure or an interruption */
  int rc2 = sa_file_commit(&sf);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  return rc2;
}

const SaModule hmsa_module = {
    .name = "hmsa",
    .trigger = "hmsa",
    .help = "reduced-order hard-magnetic soft actuator dynamics (Zener / polymer chain)",
    .tables = hmsa_tables,
    .ntables = 3,
    .check = hmsa_check,
    .write_resolved = hmsa_write_resolved,
    .run = hmsa_run,
    .destroy = hmsa_destroy,
};
