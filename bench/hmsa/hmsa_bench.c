/* hmsa_bench.c - work-precision study of softact's HMSA integrators (hmsa/hmsa_integrate.h).
 *
 * Protocol (the same as bench/hmsa/hmsa_protocol.m on the Octave side): Zener model, c = 1,
 * beta = 2, S = 0, `sq` loading b2 = sgn b_a^2 sin^2(Omega tau) with b_a = 0.4, sgn = -1; start
 * at rest, integrate n_trans forcing periods of transient, then n_meas periods sampled at 128
 * points per period from the integrator's dense output; a3 = (max lambda3 - min lambda3)/2,
 * a = (max lambda - min lambda)/2 (docs/hmsa_model.md section 7). Defaults 140 + 40 = 180
 * periods. atol = 1e-2 rtol throughout.
 *
 *   hmsa_bench wp ETA OMEGA OUT.csv [options]
 *       For each method and rtol: median wall time of the protocol over --reps runs, solver
 *       statistics, final state, a3, and the errors against a reference run (ERK Dormand-Prince
 *       at rtol 1e-13; its own error is bounded by comparing it with ERK at 1e-12 and with the
 *       implicit methods at 1e-12, written as comment lines).
 *   hmsa_bench sweep OUT.csv [options]
 *       The frequency sweep: --n frequencies on [--wlo, --whi], each from rest; per method and
 *       rtol the median wall time of the whole sweep and max over omega of |a3 - a3_ref|. The
 *       per-omega reference amplitudes are written to OUT.csv.ref.csv.
 * Options: --reps R (3), --methods erk,dirk,bdf,auto (erk,dirk,bdf), --rtols 1e-3,...
 *   (1e-3 .. 1e-10 by decades), --trans N (140), --meas N (40), --eta E (sweep: 50),
 *   --n N (26), --wlo W (1.5), --whi W (2.75), --ref-rtol R (1e-13), --ref-check 0|1 (1: wp
 *   bounds the reference's error with the 1e-12 runs).
 * Timing: wall clock (sa_time_now) and CPU time of the process (CLOCK_PROCESS_CPUTIME_ID: on a
 * shared machine it is the robust measure), integrator creation included, output excluded. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hmsa_classify.h"
#include "hmsa_integrate.h"
#include "hmsa_model.h"
#include "sa_error.h"
#include "sa_log.h"

#define MAX_LIST 32
#define N_PER 128

typedef struct {
  int reps, n_trans, n_meas, n_omega;
  int n_methods, n_rtols;
  HmsaMethod methods[MAX_LIST];
  double rtols[MAX_LIST];
  int ref_check;
  double eta, w_lo, w_hi, ref_rtol;
} BenchOptions;

#define MAX_POINCARE 256

typedef struct {
  double a3, a, y[HMSA_NEQ_MAX];
  int n_pc;                          /* Poincare samples (one per period of the measurement) */
  double pc[MAX_POINCARE * HMSA_NEQ_MAX];
} Outcome;

static const double PI = 3.14159265358979323846;

static double cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct {
  double wall, cpu;
} Timing;

static void model_setup(HmsaModel *m, double eta, double omega) {
  hmsa_model_default(m);
  m->model = HMSA_ZENER;
  m->c = 1.0;
  m->beta = 2.0;
  m->eta_bar = eta;
  m->S = 0.0;
  m->loading = HMSA_LOAD_SQ;
  m->b_a = 0.4;
  m->sgn = -1.0;
  m->omega = omega;
}

/* One protocol run on an existing integrator (reset to rest at tau = 0). */
static int protocol(HmsaIntegrator *it, const HmsaModel *m, int n_trans, int n_meas, Outcome *out) {
  double y[HMSA_NEQ_MAX];
  hmsa_model_rest(m, y);
  SA_CHECK(hmsa_integrator_reset(it, 0.0, y));
  double T = 2.0 * PI / m->omega, t0 = n_trans * T;
  SA_CHECK(hmsa_integrator_advance(it, t0, y));
  double lmin = y[0], lmax = y[0];
  out->n_pc = 0;
  for (int j = 0; j <= n_meas * N_PER; j++) {
    if (j > 0) SA_CHECK(hmsa_integrator_advance(it, t0 + j * (T / N_PER), y));
    lmin = fmin(lmin, y[0]), lmax = fmax(lmax, y[0]);
    if (j % N_PER == 0 && out->n_pc < MAX_POINCARE) {
      memcpy(out->pc + HMSA_NEQ_MAX * out->n_pc, y, HMSA_NEQ_MAX * sizeof *y);
      out->n_pc++;
    }
  }
  /* lambda3 = lambda^-2 is monotone in lambda > 0: its extremes are at lambda's. */
  out->a3 = 0.5 * (1.0 / (lmin * lmin) - 1.0 / (lmax * lmax));
  out->a = 0.5 * (lmax - lmin);
  memcpy(out->y, y, sizeof out->y);
  return 0;
}

static int run_once(const HmsaModel *m, HmsaMethod method, double rtol, int n_trans, int n_meas,
                    Outcome *out, HmsaIntegratorStats *st, Timing *tm) {
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.method = method;
  o.rtol = rtol;
  o.atol = 1e-2 * rtol;
  double t = sa_time_now(), c = cpu_now();
  HmsaIntegrator *it = NULL;
  SA_CHECK(hmsa_integrator_create(m, &o, &it));
  int rc = protocol(it, m, n_trans, n_meas, out);
  tm->wall = sa_time_now() - t;
  tm->cpu = cpu_now() - c;
  if (st) hmsa_integrator_get_stats(it, st);
  hmsa_integrator_destroy(&it);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  return 0;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static double state_err(const double *y, const double *yref) {
  double e = 0;
  for (int i = 0; i < 3; i++) e = fmax(e, fabs(y[i] - yref[i]));
  return e;
}

static int cmd_wp(double eta, double omega, const char *path, const BenchOptions *bo) {
  HmsaModel m;
  model_setup(&m, eta, omega);
  static Outcome ref, chk;
  Timing sec;
  HmsaIntegratorStats st;
  sa_log(SA_LOG_INFO, "bench", "wp eta %g omega %g: reference erk rtol %g", eta, omega, bo->ref_rtol);
  SA_CHECK(run_once(&m, HMSA_METHOD_ERK, bo->ref_rtol, bo->n_trans, bo->n_meas, &ref, &st, &sec));
  FILE *f = fopen(path, "w");
  SA_REQUIRE(f, SA_ERR_IO, "cannot open %s", path);
  fprintf(f, "# hmsa_bench wp: eta_bar %g omega %g, %d + %d periods, atol = 1e-2 rtol\n", eta,
          omega, bo->n_trans, bo->n_meas);
  fprintf(f, "# reference erk rtol %g: %.3f s, %ld steps\n", bo->ref_rtol, sec.wall, st.steps);
  HmsaClassifyResult cls;
  if (ref.n_pc >= 4 && hmsa_poincare_classify(ref.n_pc, HMSA_NEQ_MAX, ref.pc, NAN, NULL, &cls) == 0)
    fprintf(f, "# reference Poincare section (%d samples): %s, period %d, mismatch %.1e\n", ref.n_pc,
            hmsa_orbit_kind_name(cls.kind), cls.period, cls.mismatch);
  sa_error_clear();
  /* Bound on the reference's own error: the same run at 1e-12 with each method. */
  HmsaMethod chk_m[3] = {HMSA_METHOD_ERK, HMSA_METHOD_DIRK, HMSA_METHOD_BDF};
  for (int q = 0; q < (bo->ref_check ? 3 : 0); q++) {
    int rc = run_once(&m, chk_m[q], 1e-12, bo->n_trans, bo->n_meas, &chk, &st, &sec);
    if (rc) {
      fprintf(f, "# ref_check %s rtol 1e-12: failed (%s)\n", hmsa_method_name(chk_m[q]),
              sa_error_string(rc));
      sa_error_clear();
      continue;
    }
    fprintf(f, "# ref_check %s rtol 1e-12: err_state %.3e err_a3 %.3e (%.3f s, %ld steps)\n",
            hmsa_method_name(chk_m[q]), state_err(chk.y, ref.y), fabs(chk.a3 - ref.a3), sec.wall,
            st.steps);
  }
  fprintf(f, "method,eta,omega,rtol,atol,seconds,seconds_min,seconds_max,reps,steps,attempts,"
             "err_fails,conv_fails,rhs_evals,jac_evals,a3,a,lambda,dlambda,xi,err_state,err_a3,cpu,"
             "cpu_min,cpu_max\n");
  fprintf(f, "reference,%.17g,%.17g,%.3g,%.3g,,,,,,,,,,,%.17g,%.17g,%.17g,%.17g,%.17g,0,0,,,\n", eta,
          omega, bo->ref_rtol, 1e-2 * bo->ref_rtol, ref.a3, ref.a, ref.y[0], ref.y[1], ref.y[2]);
  fflush(f);
  for (int q = 0; q < bo->n_methods; q++)
    for (int r = 0; r < bo->n_rtols; r++) {
      double t[MAX_LIST], c[MAX_LIST];
      static Outcome out;
      int rc = 0;
      for (int k = 0; k < bo->reps && !rc; k++) {
        rc = run_once(&m, bo->methods[q], bo->rtols[r], bo->n_trans, bo->n_meas, &out, &st, &sec);
        t[k] = sec.wall, c[k] = sec.cpu;
      }
      if (rc) {
        sa_log(SA_LOG_WARN, "bench", "%s rtol %g failed: %s", hmsa_method_name(bo->methods[q]),
               bo->rtols[r], sa_error_message());
        fprintf(f, "# %s rtol %g failed: %s\n", hmsa_method_name(bo->methods[q]), bo->rtols[r],
                sa_error_message());
        sa_error_clear();
        continue;
      }
      double tmin = t[0], tmax = t[0], cmin = c[0], cmax = c[0];
      for (int k = 1; k < bo->reps; k++) {
        tmin = fmin(tmin, t[k]), tmax = fmax(tmax, t[k]);
        cmin = fmin(cmin, c[k]), cmax = fmax(cmax, c[k]);
      }
      double tmed = median(t, bo->reps), cmed = median(c, bo->reps);
      fprintf(f, "%s,%.17g,%.17g,%.3g,%.3g,%.6f,%.6f,%.6f,%d,%ld,%ld,%ld,%ld,%ld,%ld,%.17g,%.17g,"
                 "%.17g,%.17g,%.17g,%.3e,%.3e,%.6f,%.6f,%.6f\n",
              hmsa_method_name(bo->methods[q]), eta, omega, bo->rtols[r], 1e-2 * bo->rtols[r], tmed,
              tmin, tmax, bo->reps, st.steps, st.attempts, st.err_fails, st.conv_fails,
              st.rhs_evals, st.jac_evals, out.a3, out.a, out.y[0], out.y[1], out.y[2],
              state_err(out.y, ref.y), fabs(out.a3 - ref.a3), cmed, cmin, cmax);
      fflush(f);
      sa_log(SA_LOG_INFO, "bench", "%-4s rtol %.0e: %.4f s (cpu %.4f), %ld steps, err_state %.2e, "
             "err_a3 %.2e", hmsa_method_name(bo->methods[q]), bo->rtols[r], tmed, cmed, st.steps,
             state_err(out.y, ref.y), fabs(out.a3 - ref.a3));
    }
  fclose(f);
  return 0;
}

typedef struct {
  HmsaModel *m;
  HmsaIntegrator *it;
  const BenchOptions *bo;
} PeakCtx;

static int peak_amp(double omega, double *amp, void *ctx) {
  PeakCtx *pc = ctx;
  pc->m->omega = omega;
  Outcome out;
  SA_CHECK(protocol(pc->it, pc->m, pc->bo->n_trans, pc->bo->n_meas, &out));
  *amp = out.a3;
  return 0;
}

/* Peaks of the reference sweep, refined by golden-section search with ERK at rtol 1e-10
 * (error in a3 ~1e-10, far below the golden bracket's effect), labelled against the highest. */
static int sweep_peaks(const BenchOptions *bo, const double *ref, FILE *f) {
  int n = bo->n_omega;
  if (n < 3) return 0;
  double *w = calloc((size_t)n, sizeof *w);
  if (!w) return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %d frequencies", n);
  for (int i = 0; i < n; i++) w[i] = bo->w_lo + (bo->w_hi - bo->w_lo) * i / (n - 1);
  HmsaModel m;
  model_setup(&m, bo->eta, bo->w_lo);
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.method = HMSA_METHOD_ERK;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  HmsaIntegrator *it = NULL;
  int rc = hmsa_integrator_create(&m, &o, &it);
  HmsaPeak pk[8];
  int np = 0;
  if (!rc) {
    PeakCtx ctx = {&m, it, bo};
    rc = hmsa_peaks_find(n, w, ref, NULL, peak_amp, &ctx, 0.0, 8, pk, &np);
  }
  hmsa_integrator_destroy(&it);
  free(w);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  for (int q = 0; q < np; q++)
    fprintf(f, "# peak omega_grid %.4f a3_grid %.6f -> omega %.5f a3 %.8f (%s, %d evaluations, %s "
               "order %d, prominence %.2e)\n",
            pk[q].omega_grid, pk[q].amp_grid, pk[q].omega, pk[q].amp,
            pk[q].refined ? "refined" : "not refined", pk[q].n_evals,
            hmsa_peak_kind_name(pk[q].kind), pk[q].order, pk[q].prominence);
  return 0;
}

/* The whole sweep with one integrator (omega changed between resets); a3[i] [out]. */
static int sweep_once(HmsaMethod method, double rtol, const BenchOptions *bo, double *a3,
                      Timing *tm, long *steps) {
  HmsaModel m;
  model_setup(&m, bo->eta, bo->w_lo);
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.method = method;
  o.rtol = rtol;
  o.atol = 1e-2 * rtol;
  double t = sa_time_now(), c = cpu_now();
  HmsaIntegrator *it = NULL;
  SA_CHECK(hmsa_integrator_create(&m, &o, &it));
  int rc = 0;
  static Outcome out;
  for (int i = 0; i < bo->n_omega && !rc; i++) {
    m.omega = bo->n_omega > 1 ? bo->w_lo + (bo->w_hi - bo->w_lo) * i / (bo->n_omega - 1) : bo->w_lo;
    rc = protocol(it, &m, bo->n_trans, bo->n_meas, &out);
    a3[i] = out.a3;
  }
  tm->wall = sa_time_now() - t;
  tm->cpu = cpu_now() - c;
  HmsaIntegratorStats st;
  hmsa_integrator_get_stats(it, &st);
  *steps = st.steps;
  hmsa_integrator_destroy(&it);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  return 0;
}

static int cmd_sweep(const char *path, const BenchOptions *bo) {
  int n = bo->n_omega;
  double *ref = calloc((size_t)n, sizeof *ref), *a3 = calloc((size_t)n, sizeof *a3);
  if (!ref || !a3) {
    free(ref), free(a3);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %d amplitudes", n);
  }
  Timing sec;
  long steps;
  sa_log(SA_LOG_INFO, "bench", "sweep: reference erk rtol %g", bo->ref_rtol);
  int rc = sweep_once(HMSA_METHOD_ERK, bo->ref_rtol, bo, ref, &sec, &steps);
  char rpath[1024];
  snprintf(rpath, sizeof rpath, "%s.ref.csv", path);
  FILE *fr = rc ? NULL : fopen(rpath, "w");
  FILE *f = rc ? NULL : fopen(path, "w");
  if (rc || !fr || !f) {
    if (fr) fclose(fr);
    if (f) fclose(f);
    free(ref), free(a3);
    if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
    return SA_ERROR(SA_ERR_IO, "cannot open %s or %s", path, rpath);
  }
  fprintf(fr, "# reference sweep: erk rtol %g, %.3f s, %ld steps\nomega,a3\n", bo->ref_rtol,
          sec.wall, steps);
  for (int i = 0; i < n; i++)
    fprintf(fr, "%.17g,%.17g\n",
            n > 1 ? bo->w_lo + (bo->w_hi - bo->w_lo) * i / (n - 1) : bo->w_lo, ref[i]);
  rc = sweep_peaks(bo, ref, fr);
  fclose(fr);
  if (rc) {
    fclose(f);
    free(ref), free(a3);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  fprintf(f, "# hmsa_bench sweep: eta_bar %g, %d frequencies on [%g, %g], %d + %d periods each\n",
          bo->eta, n, bo->w_lo, bo->w_hi, bo->n_trans, bo->n_meas);
  fprintf(f, "method,rtol,atol,seconds,seconds_min,seconds_max,reps,steps,err_a3_max,cpu,cpu_min,"
             "cpu_max\n");
  for (int q = 0; q < bo->n_methods; q++)
    for (int r = 0; r < bo->n_rtols; r++) {
      double t[MAX_LIST], c[MAX_LIST];
      for (int k = 0; k < bo->reps && !rc; k++) {
        rc = sweep_once(bo->methods[q], bo->rtols[r], bo, a3, &sec, &steps);
        t[k] = sec.wall, c[k] = sec.cpu;
      }
      if (rc) {
        fprintf(f, "# %s rtol %g failed: %s\n", hmsa_method_name(bo->methods[q]), bo->rtols[r],
                sa_error_message());
        sa_error_clear();
        rc = 0;
        continue;
      }
      double err = 0;
      for (int i = 0; i < n; i++) err = fmax(err, fabs(a3[i] - ref[i]));
      double tmin = t[0], tmax = t[0], cmin = c[0], cmax = c[0];
      for (int k = 1; k < bo->reps; k++) {
        tmin = fmin(tmin, t[k]), tmax = fmax(tmax, t[k]);
        cmin = fmin(cmin, c[k]), cmax = fmax(cmax, c[k]);
      }
      double tmed = median(t, bo->reps), cmed = median(c, bo->reps);
      fprintf(f, "%s,%.3g,%.3g,%.6f,%.6f,%.6f,%d,%ld,%.3e,%.6f,%.6f,%.6f\n",
              hmsa_method_name(bo->methods[q]), bo->rtols[r], 1e-2 * bo->rtols[r], tmed, tmin, tmax,
              bo->reps, steps, err, cmed, cmin, cmax);
      fflush(f);
      sa_log(SA_LOG_INFO, "bench", "sweep %-4s rtol %.0e: %.4f s (cpu %.4f), err_a3_max %.2e",
             hmsa_method_name(bo->methods[q]), bo->rtols[r], tmed, cmed, err);
    }
  fclose(f);
  free(ref), free(a3);
  return 0;
}

static int parse_methods(const char *s, BenchOptions *bo) {
  bo->n_methods = 0;
  char buf[256];
  snprintf(buf, sizeof buf, "%s", s);
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    SA_REQUIRE(bo->n_methods < MAX_LIST, SA_ERR_INPUT, "too many methods");
    HmsaMethod mm;
    if (!strcmp(tok, "erk")) mm = HMSA_METHOD_ERK;
    else if (!strcmp(tok, "dirk")) mm = HMSA_METHOD_DIRK;
    else if (!strcmp(tok, "bdf")) mm = HMSA_METHOD_BDF;
    else if (!strcmp(tok, "auto")) mm = HMSA_METHOD_AUTO;
    else return SA_ERROR(SA_ERR_INPUT, "unknown method '%s' (erk, dirk, bdf, auto)", tok);
    bo->methods[bo->n_methods++] = mm;
  }
  return 0;
}

static int parse_rtols(const char *s, BenchOptions *bo) {
  bo->n_rtols = 0;
  char buf[512];
  snprintf(buf, sizeof buf, "%s", s);
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    SA_REQUIRE(bo->n_rtols < MAX_LIST, SA_ERR_INPUT, "too many tolerances");
    char *end;
    double v = strtod(tok, &end);
    SA_REQUIRE(*end == 0 && v > 0 && v < 1, SA_ERR_INPUT, "bad tolerance '%s'", tok);
    bo->rtols[bo->n_rtols++] = v;
  }
  return 0;
}

static int parse_options(int argc, char **argv, int first, BenchOptions *bo) {
  for (int i = first; i < argc; i += 2) {
    SA_REQUIRE(i + 1 < argc, SA_ERR_INPUT, "option %s needs a value", argv[i]);
    const char *k = argv[i], *v = argv[i + 1];
    if (!strcmp(k, "--reps")) bo->reps = atoi(v);
    else if (!strcmp(k, "--trans")) bo->n_trans = atoi(v);
    else if (!strcmp(k, "--meas")) bo->n_meas = atoi(v);
    else if (!strcmp(k, "--n")) bo->n_omega = atoi(v);
    else if (!strcmp(k, "--eta")) bo->eta = atof(v);
    else if (!strcmp(k, "--wlo")) bo->w_lo = atof(v);
    else if (!strcmp(k, "--whi")) bo->w_hi = atof(v);
    else if (!strcmp(k, "--ref-rtol")) bo->ref_rtol = atof(v);
    else if (!strcmp(k, "--ref-check")) bo->ref_check = atoi(v);
    else if (!strcmp(k, "--methods")) SA_CHECK(parse_methods(v, bo));
    else if (!strcmp(k, "--rtols")) SA_CHECK(parse_rtols(v, bo));
    else return SA_ERROR(SA_ERR_INPUT, "unknown option %s", k);
  }
  SA_REQUIRE(bo->reps >= 1 && bo->reps <= MAX_LIST, SA_ERR_INPUT, "--reps %d out of 1..%d", bo->reps,
             MAX_LIST);
  SA_REQUIRE(bo->n_trans >= 0 && bo->n_meas >= 1 && bo->n_omega >= 1, SA_ERR_INPUT,
             "bad period or frequency counts");
  SA_REQUIRE(bo->eta > 0 && bo->w_lo > 0 && bo->w_hi >= bo->w_lo && bo->ref_rtol > 0, SA_ERR_INPUT,
             "bad eta, frequency range or reference tolerance");
  return 0;
}

static int run(int argc, char **argv) {
  BenchOptions bo = {.reps = 3, .n_trans = 140, .n_meas = 40, .n_omega = 26, .eta = 50,
                     .w_lo = 1.5, .w_hi = 2.75, .ref_rtol = 1e-13, .ref_check = 1};
  SA_CHECK(parse_methods("erk,dirk,bdf", &bo));
  SA_CHECK(parse_rtols("1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10", &bo));
  if (argc >= 5 && !strcmp(argv[1], "wp")) {
    SA_CHECK(parse_options(argc, argv, 5, &bo));
    SA_CHECK(cmd_wp(atof(argv[2]), atof(argv[3]), argv[4], &bo));
    return 0;
  }
  if (argc >= 3 && !strcmp(argv[1], "sweep")) {
    SA_CHECK(parse_options(argc, argv, 3, &bo));
    SA_CHECK(cmd_sweep(argv[2], &bo));
    return 0;
  }
  fprintf(stderr, "usage: hmsa_bench wp ETA OMEGA OUT.csv [options]\n"
                  "       hmsa_bench sweep OUT.csv [options]\n"
                  "options: --reps --methods --rtols --trans --meas --eta --n --wlo --whi --ref-rtol\n"
                  "         --ref-check\n");
  return SA_ERR_INPUT;
}

int main(int argc, char **argv) {
  int rc = run(argc, argv);
  if (rc) sa_error_print();
  return sa_error_exit_status(rc);
}
