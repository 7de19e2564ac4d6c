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

typedef struct {
  HmsaModel m;
  char tag[128];
} HmsaVariant;

typedef struct {
  HmsaParams p;
  HmsaSweepParams sw;
  HmsaPoincareParams pc;
  HmsaIntegratorOptions io;
  int nvar;
  HmsaVariant var[HMSA_MAX_VARIANTS];
} HmsaScene;

/* ------------------------------------------------------------------ variants */

static void tag_add(char *tag, size_t n, const char *key, double v) {
  size_t k = strlen(tag);
  char num[48];
  snprintf(num, sizeof num, "%g", v);
  for (char *s = num; *s; s++)
    if (*s == '-') *s = 'm'; /* file-name friendly: b2m0.16 */
  snprintf(tag + k, n - k, "%s%s%s", k ? "_" : "", key, num);
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
  for (int i = 0; i < p->sigma.n; i++)
    if (fabs(fabs(p->sigma.v[i]) - 1.0) > 0) {
      rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] sigma: %g must be +1 or -1 (sign of the sq load)",
                    sa_case_origin(c, "hmsa", "sigma", where), p->sigma.v[i]);
      goto fail;
    }
  if (!strcmp(p->model, "pc")) {
    for (int i = 0; i < p->mu_c.n; i++)
      for (int j = 0; j < p->mu_e.n; j++)
        if (p->mu_c.v[i] + p->mu_e.v[j] <= 0) {
          rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] mu_c = mu_e = 0 leaves no elastic stiffness",
                        sa_case_origin(c, "hmsa", "mu_c", where));
          goto fail;
        }
  }
  int periodic = strcmp(p->loading, "const") != 0;
  if ((!strcmp(p->analysis, "poincare") || !strcmp(p->analysis, "sweep")) && !periodic) {
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] analysis = %s needs a periodic loading (sq or lin)",
                  sa_case_origin(c, "hmsa", "loading", where), p->analysis);
    goto fail;
  }
  if (!(s->sw.omega_max > s->sw.omega_min)) {
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa_sweep] omega_max = %g must exceed omega_min = %g",
                  sa_case_origin(c, "hmsa_sweep", "omega_max", where), s->sw.omega_max,
                  s->sw.omega_min);
    goto fail;
  }
  if (p->dt_out > p->t_end) {
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] dt_out = %g exceeds t_end = %g",
                  sa_case_origin(c, "hmsa", "dt_out", where), p->dt_out, p->t_end);
    goto fail;
  }
  if (p->t_end / p->dt_out > 5e7) {
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [hmsa] t_end/dt_out = %g rows is too many",
                  sa_case_origin(c, "hmsa", "dt_out", where), p->t_end / p->dt_out);
    goto fail;
  }
  rc = build_variants(s);
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

static int plot_xy(const SaRun *run, const char *png, const char *csv, int xc, int yc,
                   const char *title, const char *xl, const char *yl, const char *style) {
  if (!run->params.plots) return 0;
  char pp[SA_STR_MAX], cp[SA_STR_MAX];
  SA_CHECK(sa_run_path(run, png, pp));
  SA_CHECK(sa_run_path(run, csv, cp));
  SaPlotSeries s = {cp, xc, yc, title, style};
  SaPlotAxes ax = {title, xl, yl, 0, 0, 0, 0};
  if (sa_plot_lines(pp, &ax, 1, &s)) sa_error_clear(); /* plots are optional */
  return 0;
}

/* ------------------------------------------------------------------ history */

static int run_history(const HmsaScene *s, const HmsaVariant *v, const SaRun *run, Summary *S) {
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
  HmsaIntegrator *it;
  int rc = hmsa_integrator_create(m, &s->io, &it);
  if (rc) { sa_csv_abort(&t); return sa_error_push(rc, __func__, __FILE__, __LINE__); }
  double y[HMSA_NEQ_MAX];
  hmsa_model_rest(m, y);
  rc = hmsa_integrator_reset(it, 0.0, y);
  long N = (long)floor(s->p.t_end / s->p.dt_out + 1e-9);
  double T0, U0;
  hmsa_model_energy(m, y, hmsa_model_b2(m, 0.0), &T0, &U0);
  double l3min = 1, l3max = 1, t0 = sa_time_now(), diss = 0.0, dprev = 0.0, tprev = 0.0;
  double row[6];
  long k;
  for (k = 0; !rc && k <= N; k++) {
    double tau = k * s->p.dt_out;
    if (k > 0) rc = hmsa_integrator_advance(it, tau, y);
    if (rc) break;
    if (k % 1000 == 0 && sa_interrupted()) { rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted"); break; }
    row[0] = tau, row[1] = y[0], row[2] = y[1], row[3] = hmsa_lambda3(y), row[4] = hmsa_dlambda3(y);
    if (zener) row[5] = y[2];
    rc = sa_csv_row(t, row);
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
  char title[256];
  snprintf(title, sizeof title, "lambda3 %s", v->tag);
  file_name(png, sizeof png, "history", v->tag, "png");
  SA_CHECK(plot_xy(run, png, csv, 1, 4, title, "tau", "lambda3", "lines"));
  file_name(png, sizeof png, "phase", v->tag, "png");
  snprintf(title, sizeof title, "phase plane %s", v->tag);
  SA_CHECK(plot_xy(run, png, csv, 4, 5, title, "lambda3", "dlambda3/dtau", "lines"));
  return 0;
}

/* ------------------------------------------------------------------ statics scene */

static int run_statics(const HmsaScene *s, const HmsaVariant *v, const SaRun *run, Summary *S) {
  (void)s;
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
  file_name(png, sizeof png, "statics", v->tag, "png");
  SA_CHECK(plot_xy(run, png, csv, 2, 3, "relaxed equilibria: prestress against lambda3",
                   "lambda3", "S", "lines"));
  return 0;
}

/* ------------------------------------------------------------------ poincare scene */

static int run_poincare(const HmsaScene *s, const HmsaVariant *v, const SaRun *run, Summary *S,
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
      if (k > 0) rc = hmsa_integrator_advance(it, tau, y);
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
    char pp[SA_STR_MAX], body[2048], pcsv[256], ocsv[256];
    file_name(png, sizeof png, "poincare", v->tag, "png");
    file_name(pcsv, sizeof pcsv, "poincare", v->tag, "csv");
    file_name(ocsv, sizeof ocsv, "orbit", v->tag, "csv");
    SA_CHECK(sa_run_path(run, png, pp));
    snprintf(body, sizeof body,
             "set datafile separator ','\nset key top right\nset title 'Poincare map %s'\n"
             "set xlabel 'lambda3'\nset ylabel 'dlambda3/dtau'\n"
             "plot '%s' using 4:5 with lines lc rgb '#a0a0a0' title 'steady orbit', "
             "'%s' using 5:6 with points pt 7 ps 0.6 lc rgb '#d01010' title 'tau = n 2pi/Omega'\n",
             v->tag, ocsv, pcsv);
    if (sa_plot_script(pp, body)) sa_error_clear();
  }
  return 0;
}

/* ------------------------------------------------------------------ sweep scene */

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

static int run_sweep(const HmsaScene *s, const HmsaVariant *v, const SaRun *run, Summary *S) {
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
  if (run->params.plots) {
    char ppath[SA_STR_MAX], body[2048];
    for (int pass = 0; pass < 2; pass++) {
      file_name(png, sizeof png, pass ? "sweep_inplane" : "sweep", v->tag, "png");
      SA_CHECK(sa_run_path(run, png, ppath));
      const char *c = pass ? csv2 : csv;
      int k = snprintf(body, sizeof body,
                       "set datafile separator ','\nset key top right\nset title 'steady amplitude %s'\n"
                       "set xlabel 'Omega'\nset ylabel '%s'\n"
                       "plot '%s' using 1:($3==0?$2:1/0) with linespoints pt 7 ps 0.5 title 'from rest'",
                       v->tag, pass ? "a (lambda)" : "a3 (lambda3)", c);
      if (w->continuation && k > 0 && (size_t)k < sizeof body)
        k += snprintf(body + k, sizeof body - (size_t)k,
                      ", '%s' using 1:($3==1?$2:1/0) with lines title 'continuation up', "
                      "'%s' using 1:($3==2?$2:1/0) with lines dt 2 title 'continuation down'",
                      c, c);
      if (k > 0 && (size_t)k + 2 < sizeof body) strcat(body, "\n");
      if (sa_plot_script(ppath, body)) sa_error_clear();
    }
  }
  return 0;
}

/* ------------------------------------------------------------------ run */

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
    const HmsaVariant *v = &s->var[i];
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
