/* hmsa_analysis.c - steady amplitude, settling time, Poincare section with Benettin's largest
 * Lyapunov exponent, and frequency sweeps (MODEL.md section 7). */
#include "hmsa_analysis.h"

#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"
#include "sa_log.h"

void hmsa_steady_options_default(HmsaSteadyOptions *o) {
  o->transient_periods = 60;
  o->transient_tau = 400.0;
  o->measure_periods = 40;
  o->samples_per_period = 128;
}

/* Extreme of samples f[0..n) refined by the parabola through the best sample and its
 * neighbours (sign = +1 max, -1 min). */
static double refined_extreme(const double *f, int n, double sign) {
  int b = 0;
  for (int i = 1; i < n; i++)
    if (sign * f[i] > sign * f[b]) b = i;
  if (b == 0 || b == n - 1) return f[b];
  double f0 = f[b - 1], f1 = f[b], f2 = f[b + 1];
  double den = f0 - 2.0 * f1 + f2;
  if (!(sign * den < 0)) return f1;
  return f1 - (f0 - f2) * (f0 - f2) / (8.0 * den);
}

int hmsa_steady_amplitude(HmsaIntegrator *it, const HmsaModel *m, const HmsaSteadyOptions *o,
                          const double *y0, HmsaSteady *out) {
  double T = hmsa_model_period(m);
  SA_REQUIRE(T > 0, SA_ERR_INPUT, "steady amplitude needs a periodic load with omega > 0");
  /* the products are checked with the case (hmsa.c); a caller that skipped that gets an
   * error, not a wrapped int */
  SA_REQUIRE(o->samples_per_period > 0 && o->measure_periods > 0 &&
                 (long long)o->measure_periods * o->samples_per_period < INT_MAX / 2,
             SA_ERR_INPUT, "steady amplitude: %d measure periods x %d samples per period do not fit",
             o->measure_periods, o->samples_per_period);
  SA_REQUIRE(o->transient_tau / T < INT_MAX / 2 - o->measure_periods, SA_ERR_INPUT,
             "steady amplitude: transient_tau = %g is %g periods", o->transient_tau,
             o->transient_tau / T);
  int ntr = o->transient_periods;
  int ntau = (int)ceil(o->transient_tau / T - 1e-12);
  if (ntau > ntr) ntr = ntau;
  int sp = o->samples_per_period, nm = o->measure_periods * sp;
  int n = hmsa_model_neq(m);
  double y[HMSA_NEQ_MAX];
  SA_CHECK(hmsa_integrator_reset(it, 0.0, y0));
  for (int p = 1; p <= ntr; p++) {
    if (sa_interrupted()) return SA_ERROR(SA_ERR_INTERRUPTED, "interrupted");
    SA_CHECK(hmsa_integrator_advance(it, p * T, y));
  }
  double *l3 = malloc(sizeof(double) * (size_t)(2 * (nm + 1)));
  if (!l3) return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %d samples", nm);
  double *lv = l3 + nm + 1;
  l3[0] = hmsa_lambda3(y);
  lv[0] = y[0];
  int rc = 0;
  for (int j = 1; j <= nm; j++) {
    if (sa_interrupted()) { rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted"); break; }
    /* every period end is computed as an integer multiple of T (no drift of the phase) */
    double t = (j % sp == 0) ? (ntr + j / sp) * T : ntr * T + (double)j * T / sp;
    rc = hmsa_integrator_advance(it, t, y);
    if (rc) { rc = sa_error_push(rc, __func__, __FILE__, __LINE__); break; }
    l3[j] = hmsa_lambda3(y);
    lv[j] = y[0];
  }
  if (!rc) {
    out->l3_max = refined_extreme(l3, nm + 1, 1.0);
    out->l3_min = refined_extreme(l3, nm + 1, -1.0);
    out->l_max = refined_extreme(lv, nm + 1, 1.0);
    out->l_min = refined_extreme(lv, nm + 1, -1.0);
    out->a3 = 0.5 * (out->l3_max - out->l3_min);
    out->a = 0.5 * (out->l_max - out->l_min);
    for (int i = 0; i < n; i++) out->y_end[i] = y[i];
    out->tau_end = (ntr + o->measure_periods) * T;
  }
  free(l3);
  return rc;
}

int hmsa_settling_time(const HmsaModel *m, const HmsaIntegratorOptions *io, double lambda3_eq,
                       double t_end, double *tau_s) {
  const double dt = 0.002;
  double tol = 0.01 * fabs(lambda3_eq - 1.0);
  int n = hmsa_model_neq(m);
  HmsaIntegrator *it;
  SA_CHECK(hmsa_integrator_create(m, io, &it));
  double y[HMSA_NEQ_MAX], y_out[HMSA_NEQ_MAX], t_out = 0.0;
  hmsa_model_rest(m, y);
  for (int i = 0; i < n; i++) y_out[i] = y[i];
  int rc = hmsa_integrator_reset(it, 0.0, y);
  long N = (long)ceil(t_end / dt);
  int outside_seen = 0;
  for (long k = 1; !rc && k <= N; k++) {
    double t = k * dt;
    /* a large step serves many grid points from dense output without stepping (and polling) */
    if (sa_interrupted()) { rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted"); break; }
    rc = hmsa_integrator_advance(it, t, y);
    if (rc) break;
    if (fabs(hmsa_lambda3(y) - lambda3_eq) > tol) {
      outside_seen = 1;
      t_out = t;
      for (int i = 0; i < n; i++) y_out[i] = y[i];
    }
  }
  if (rc) {
    hmsa_integrator_destroy(&it);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  if (!outside_seen || t_out >= N * dt - 0.5 * dt) {
    *tau_s = outside_seen ? -1.0 : 0.0;
    hmsa_integrator_destroy(&it);
    return 0;
  }
  /* last exit lies in (t_out, t_out + dt): bisection on g = |l3 - eq| - tol */
  double a = t_out, b = t_out + dt;
  for (int iter = 0; iter < 40 && !rc; iter++) {
    double c = 0.5 * (a + b);
    rc = hmsa_integrator_reset(it, t_out, y_out);
    if (!rc) rc = hmsa_integrator_advance(it, c, y);
    if (rc) break;
    if (fabs(hmsa_lambda3(y) - lambda3_eq) > tol) a = c; else b = c;
  }
  hmsa_integrator_destroy(&it);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  *tau_s = 0.5 * (a + b);
  return 0;
}

int hmsa_poincare(const HmsaModel *m, const HmsaIntegratorOptions *io, const double *y0,
                  int n_transient, int n_points, double d0, double *x, double *lyap,
                  SaProgress *progress) {
  double T = hmsa_model_period(m);
  SA_REQUIRE(T > 0, SA_ERR_INPUT, "a Poincare section needs a periodic load with omega > 0");
  int n = hmsa_model_neq(m);
  HmsaIntegrator *it = NULL, *it2 = NULL;
  int rc = hmsa_integrator_create(m, io, &it);
  if (!rc && lyap) rc = hmsa_integrator_create(m, io, &it2);
  double y[HMSA_NEQ_MAX], z[HMSA_NEQ_MAX];
  for (int i = 0; i < n; i++) y[i] = y0[i];
  if (!rc) rc = hmsa_integrator_reset(it, 0.0, y);
  for (int p = 1; !rc && p <= n_transient; p++) {
    if (sa_interrupted()) rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted");
    else rc = hmsa_integrator_advance(it, p * T, y);
    if (progress) sa_progress_add(progress, 1);
  }
  double sum = 0.0;
  int nsum = 0, skip = n_points / 5 < 20 ? n_points / 5 : 20;
  double e = d0 / sqrt((double)n);
  if (!rc && lyap) {
    for (int i = 0; i < n; i++) z[i] = y[i] + e;
    rc = hmsa_integrator_reset(it2, n_transient * T, z);
  }
  for (int j = 1; !rc && j <= n_points; j++) {
    double t = (n_transient + j) * T;
    if (sa_interrupted()) { rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted"); break; }
    rc = hmsa_integrator_advance(it, t, y);
    if (rc) break;
    for (int i = 0; i < n; i++) x[(size_t)(j - 1) * n + i] = y[i];
    if (lyap) {
      rc = hmsa_integrator_advance(it2, t, z);
      if (rc) break;
      double d = 0.0;
      for (int i = 0; i < n; i++) d += (z[i] - y[i]) * (z[i] - y[i]);
      d = sqrt(d);
      if (!(d > 0)) d = 1e-300;
      if (j > skip) { sum += log(d / d0); nsum++; }
      for (int i = 0; i < n; i++) z[i] = y[i] + (d0 / d) * (z[i] - y[i]);
      rc = hmsa_integrator_reset(it2, t, z);
    }
    if (progress) sa_progress_add(progress, 1);
  }
  if (!rc && lyap) *lyap = nsum > 0 ? sum / nsum : NAN;
  hmsa_integrator_destroy(&it);
  hmsa_integrator_destroy(&it2);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  return 0;
}

/* ------------------------------------------------------------------ sweeps */

typedef struct {
  const HmsaModel *m;
  const HmsaIntegratorOptions *io;
  const HmsaSteadyOptions *so;
  int n;
  const double *omega;
  double *a3, *a;
  int *status;
  SaProgress *progress;
  pthread_mutex_t lock;
  int next;
  int fatal;
} SweepJob;

static void *sweep_worker(void *arg) {
  SweepJob *job = arg;
  HmsaModel m = *job->m;
  HmsaIntegrator *it = NULL;
  int rc = hmsa_integrator_create(&m, job->io, &it);
  if (rc) {
    pthread_mutex_lock(&job->lock);
    job->fatal = rc;
    pthread_mutex_unlock(&job->lock);
    sa_error_clear();
    return NULL;
  }
  double y0[HMSA_NEQ_MAX];
  for (;;) {
    pthread_mutex_lock(&job->lock);
    int i = (job->fatal || sa_interrupted()) ? job->n : job->next++;
    pthread_mutex_unlock(&job->lock);
    if (i >= job->n) break;
    m.omega = job->omega[i];
    hmsa_model_rest(&m, y0);
    HmsaSteady st;
    rc = hmsa_steady_amplitude(it, &m, job->so, y0, &st);
    if (rc) {
      if (rc != SA_ERR_INTERRUPTED)
        sa_log(SA_LOG_WARN, "hmsa", "sweep omega = %g failed: %s", m.omega, sa_error_message());
      sa_error_clear();
      job->status[i] = rc;
      job->a3[i] = job->a[i] = NAN;
    } else {
      job->status[i] = 0;
      job->a3[i] = st.a3;
      job->a[i] = st.a;
    }
    if (job->progress) sa_progress_add(job->progress, 1);
  }
  hmsa_integrator_destroy(&it);
  return NULL;
}

int hmsa_sweep_rest(const HmsaModel *m, const HmsaIntegratorOptions *io,
                    const HmsaSteadyOptions *so, int n, const double *omega, int threads,
                    SaProgress *progress, double *a3, double *a, int *status) {
  SweepJob job = {.m = m, .io = io, .so = so, .n = n, .omega = omega, .a3 = a3, .a = a,
                  .status = status, .progress = progress, .next = 0, .fatal = 0};
  for (int i = 0; i < n; i++) {
    status[i] = SA_ERR_INTERRUPTED;
    a3[i] = a[i] = NAN;
  }
  pthread_mutex_init(&job.lock, NULL);
  if (threads < 1) threads = 1;
  if (threads > n) threads = n;
  pthread_t *tid = calloc((size_t)threads, sizeof *tid);
  if (!tid) return SA_ERROR(SA_ERR_MEMORY, "thread table");
  int started = 0;
  for (int t = 1; t < threads; t++)
    if (pthread_create(&tid[started], NULL, sweep_worker, &job) == 0) started++;
  sweep_worker(&job); /* the calling thread works too */
  for (int t = 0; t < started; t++) pthread_join(tid[t], NULL);
  free(tid);
  pthread_mutex_destroy(&job.lock);
  if (job.fatal) return SA_ERROR(job.fatal, "sweep worker could not start");
  if (sa_interrupted()) return SA_ERROR(SA_ERR_INTERRUPTED, "sweep interrupted");
  return 0;
}

typedef struct {
  const HmsaModel *m;
  const HmsaIntegratorOptions *io;
  const HmsaSteadyOptions *so;
  int n, dir;
  const double *omega;
  double *a3, *a;
  SaProgress *progress;
  int rc;
} ContJob;

static void *cont_worker(void *arg) {
  ContJob *job = arg;
  HmsaModel m = *job->m;
  HmsaIntegrator *it = NULL;
  job->rc = hmsa_integrator_create(&m, job->io, &it);
  if (job->rc) { sa_error_clear(); return NULL; }
  double y[HMSA_NEQ_MAX];
  hmsa_model_rest(&m, y);
  for (int k = 0; k < job->n; k++) {
    int i = job->dir > 0 ? k : job->n - 1 - k;
    job->a3[i] = job->a[i] = NAN;
    if (sa_interrupted()) { job->rc = SA_ERR_INTERRUPTED; continue; }
    m.omega = job->omega[i];
    HmsaSteady st;
    int rc = hmsa_steady_amplitude(it, &m, job->so, y, &st);
    if (rc) {
      if (rc != SA_ERR_INTERRUPTED)
        sa_log(SA_LOG_WARN, "hmsa", "continuation omega = %g failed (%s); restarting from rest",
               m.omega, sa_error_message());
      sa_error_clear();
      hmsa_model_rest(&m, y);
    } else {
      job->a3[i] = st.a3;
      job->a[i] = st.a;
      for (int j = 0; j < HMSA_NEQ_MAX; j++) y[j] = st.y_end[j];
    }
    if (job->progress) sa_progress_add(job->progress, 1);
  }
  hmsa_integrator_destroy(&it);
  return NULL;
}

int hmsa_sweep_continuation(const HmsaModel *m, const HmsaIntegratorOptions *io,
                            const HmsaSteadyOptions *so, int n, const double *omega, int threads,
                            SaProgress *progress, double *up_a3, double *up_a, double *down_a3,
                            double *down_a) {
  ContJob up = {m, io, so, n, +1, omega, up_a3, up_a, progress, 0};
  ContJob dn = {m, io, so, n, -1, omega, down_a3, down_a, progress, 0};
  pthread_t tid;
  int two = threads >= 2 && pthread_create(&tid, NULL, cont_worker, &dn) == 0;
  cont_worker(&up);
  if (two) pthread_join(tid, NULL);
  else cont_worker(&dn);
  if (sa_interrupted()) return SA_ERROR(SA_ERR_INTERRUPTED, "continuation interrupted");
  if (up.rc) return SA_ERROR(up.rc, "continuation (up) could not start");
  if (dn.rc) return SA_ERROR(dn.rc, "continuation (down) could not start");
  return 0;
}
