/* hmsa_classify.c - Poincare-section classification and peak finding (see hmsa_classify.h).
 *
 * Periodicity: the smallest k <= max_period with max_n ||x_{n+k} - x_n||_inf <= atol + rtol s,
 * s = max_n ||x_n||_inf, is the period.
 *
 * Lyapunov exponent from data (Rosenstein, Collins & De Luca, Physica D 65 (1993) 117): each
 * sample i gets its nearest neighbour j (in coordinates scaled to unit range); the mean of
 * ln ||x_{i+m} - x_{j+m}|| over i grows like lambda m until the separation saturates at the
 * size of the attractor; lambda is the least-squares slope over m = 0 .. M before saturation.
 * On an invariant closed curve the map is conjugate to a rotation, separations stay bounded and
 * the slope is ~ 0; on a chaotic attractor it is the largest exponent.
 *
 * Correlation dimension (Grassberger & Procaccia, PRL 50 (1983) 346): D2 = ln(C2/C1)/ln(r2/r1)
 * with C the fraction of pairs closer than r, at the 1 % and 10 % quantiles of the pair
 * distances.
 *
 * Prominence is the topographic one (as in scipy.signal.peak_prominences): from the peak walk
 * left and right until a higher sample or the end; the base on each side is the minimum passed;
 * prominence = peak - max(left base, right base). */
#include "hmsa_classify.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sa_error.h"

/* ---------------------------------------------------------------- Poincare section */

HmsaClassifyParams hmsa_classify_params_default(void) {
  return (HmsaClassifyParams){
      .max_period = 16, .rtol = 1e-4, .atol = 1e-10, .lyap_tol = 1e-2, .lyap_tol_data = 0.1};
}

const char *hmsa_orbit_kind_name(HmsaOrbitKind kind) {
  switch (kind) {
  case HMSA_ORBIT_PERIODIC: return "periodic";
  case HMSA_ORBIT_QUASIPERIODIC: return "quasi-periodic";
  case HMSA_ORBIT_CHAOTIC: return "chaotic";
  case HMSA_ORBIT_UNKNOWN: break;
  }
  return "unknown";
}

static int check_samples(int N, int d, const double *x, int nmin) {
  SA_REQUIRE(x && d >= 1, SA_ERR_INPUT, "no samples (x = %p, d = %d)", (const void *)x, d);
  SA_REQUIRE(N >= nmin, SA_ERR_INPUT, "%d samples, need at least %d", N, nmin);
  for (long i = 0; i < (long)N * d; i++)
    SA_REQUIRE(isfinite(x[i]), SA_ERR_NAN, "sample %ld component %ld is not finite", i / d, i % d);
  return 0;
}

static double dist_inf(int d, const double *a, const double *b) {
  double m = 0;
  for (int j = 0; j < d; j++) m = fmax(m, fabs(a[j] - b[j]));
  return m;
}

/* Euclidean distance after scaling component j by w[j]. */
static double dist_w(int d, const double *a, const double *b, const double *w) {
  double s = 0;
  for (int j = 0; j < d; j++) {
    double t = (a[j] - b[j]) * w[j];
    s += t * t;
  }
  return sqrt(s);
}

/* w[j] = 1 / range of component j (1 where the range is 0). */
static int range_weights(int N, int d, const double *x, double **w_out) {
  double *w;
  SA_CALLOC(w, d);
  for (int j = 0; j < d; j++) {
    double lo = x[j], hi = x[j];
    for (int n = 1; n < N; n++) {
      lo = fmin(lo, x[(long)n * d + j]);
      hi = fmax(hi, x[(long)n * d + j]);
    }
    w[j] = hi > lo ? 1.0 / (hi - lo) : 1.0;
  }
  *w_out = w;
  return 0;
}

int hmsa_poincare_lyapunov_estimate(int N, int d, const double *x, double *lyap) {
  SA_CHECK(check_samples(N, d, x, 20));
  SA_REQUIRE(lyap, SA_ERR_INPUT, "lyap is NULL");
  /* M iterates followed: enough for a fit, few enough that most reference points remain. */
  int M = N / 10 < 8 ? N / 10 : 8;
  int Nref = N - M;
  double *w = NULL, *sum = NULL;
  int *cnt = NULL;
  SA_CHECK(range_weights(N, d, x, &w));
  sum = calloc((size_t)M + 1, sizeof *sum);
  cnt = calloc((size_t)M + 1, sizeof *cnt);
  if (!sum || !cnt) {
    free(w), free(sum), free(cnt);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %d doubles", 2 * (M + 1));
  }
  /* Floor for log(0): separations below it carry no information about divergence. */
  const double floor_d = 1e-300;
  for (int i = 0; i < Nref; i++) {
    int jbest = -1;
    double dbest = INFINITY;
    for (int j = 0; j < Nref; j++) {
      if (j == i) continue;
      double dij = dist_w(d, x + (long)i * d, x + (long)j * d, w);
      if (dij > 0 && dij < dbest) dbest = dij, jbest = j;
    }
    if (jbest < 0) continue; /* every other sample coincides with this one */
    for (int m = 0; m <= M; m++) {
      double dm = dist_w(d, x + (long)(i + m) * d, x + (long)(jbest + m) * d, w);
      sum[m] += log(fmax(dm, floor_d));
      cnt[m]++;
    }
  }
  double lam = 0;
  if (cnt[0] > 0) {
    /* Fit only while the mean separation is well below the attractor size (ln 1 = 0 in the
     * scaled coordinates): stop at the first m whose mean log separation exceeds ln 0.1. */
    int mfit = M;
    for (int m = 1; m <= M; m++)
      if (sum[m] / cnt[m] > log(0.1)) {
        mfit = m;
        break;
      }
    if (mfit < 1) mfit = 1;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int k = mfit + 1;
    for (int m = 0; m <= mfit; m++) {
      double y = sum[m] / cnt[m];
      sx += m, sy += y, sxx += (double)m * m, sxy += m * y;
    }
    lam = (k * sxy - sx * sy) / (k * sxx - sx * sx);
  }
  free(w), free(sum), free(cnt);
  *lyap = lam;
  return 0;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int hmsa_poincare_dimension(int N, int d, const double *x, double *dim) {
  SA_CHECK(check_samples(N, d, x, 20));
  SA_REQUIRE(dim, SA_ERR_INPUT, "dim is NULL");
  /* O(N^2) pairs: subsample to at most 2000 points (2e6 pairs). */
  int stride = N > 2000 ? (N + 1999) / 2000 : 1;
  int Ns = (N + stride - 1) / stride;
  long np = (long)Ns * (Ns - 1) / 2;
  double *w = NULL, *dd = NULL;
  SA_CHECK(range_weights(N, d, x, &w));
  dd = malloc((size_t)np * sizeof *dd);
  if (!dd) {
    free(w);
    return SA_ERROR(SA_ERR_MEMORY, "cannot allocate %ld pair distances", np);
  }
  long k = 0;
  for (int a = 0; a < Ns; a++)
    for (int b = a + 1; b < Ns; b++)
      dd[k++] = dist_w(d, x + (long)a * stride * d, x + (long)b * stride * d, w);
  qsort(dd, (size_t)np, sizeof *dd, cmp_double);
  double r1 = dd[(long)(0.01 * (np - 1))], r2 = dd[(long)(0.10 * (np - 1))];
  free(w), free(dd);
  /* Points repeated exactly (periodic orbit) have r1 = 0: dimension 0. */
  *dim = (r1 > 0 && r2 > r1) ? log(10.0) / log(r2 / r1) : 0.0;
  return 0;
}

int hmsa_poincare_classify(int N, int d, const double *x, double lyap, const HmsaClassifyParams *p,
                           HmsaClassifyResult *res) {
  HmsaClassifyParams def = hmsa_classify_params_default();
  if (!p) p = &def;
  SA_REQUIRE(res, SA_ERR_INPUT, "res is NULL");
  SA_CHECK(check_samples(N, d, x, 4));
  SA_REQUIRE(p->max_period >= 1 && p->rtol >= 0 && p->atol >= 0 && p->lyap_tol >= 0 &&
                 p->lyap_tol_data >= 0,
             SA_ERR_INPUT, "bad classification parameters (max_period %d, rtol %g, atol %g)",
             p->max_period, p->rtol, p->atol);
  *res = (HmsaClassifyResult){.kind = HMSA_ORBIT_UNKNOWN, .mismatch = INFINITY, .lyap = NAN,
                              .lyap_data = NAN, .dim_corr = NAN};

  double scale = 0;
  for (long i = 0; i < (long)N * d; i++) scale = fmax(scale, fabs(x[i]));
  double tol = p->atol + p->rtol * scale;
  double s = scale > 0 ? scale : 1.0;

  /* Each of the k cycle points must be compared at least once: 2k <= N. */
  int kmax = p->max_period < N / 2 ? p->max_period : N / 2;
  for (int k = 1; k <= kmax; k++) {
    double mis = 0;
    for (int n = 0; n + k < N; n++)
      mis = fmax(mis, dist_inf(d, x + (long)n * d, x + (long)(n + k) * d));
    if (mis / s < res->mismatch) res->mismatch = mis / s, res->mismatch_k = k;
    if (mis <= tol) {
      res->kind = HMSA_ORBIT_PERIODIC;
      res->period = k;
      res->mismatch = mis / s;
      res->mismatch_k = k;
      return 0;
    }
  }

  double lt = p->lyap_tol;
  if (N >= 20) {
    SA_CHECK(hmsa_poincare_lyapunov_estimate(N, d, x, &res->lyap_data));
    SA_CHECK(hmsa_poincare_dimension(N, d, x, &res->dim_corr));
  }
  if (isfinite(lyap)) {
    res->lyap = lyap;
  } else if (isfinite(res->lyap_data)) {
    res->lyap = res->lyap_data;
    lt = p->lyap_tol_data;
  } else {
    return 0; /* too few samples to estimate anything */
  }
  if (res->lyap > lt)
    res->kind = HMSA_ORBIT_CHAOTIC;
  else if (res->lyap >= -lt)
    res->kind = HMSA_ORBIT_QUASIPERIODIC;
  /* else: contracting but not repeating - transient not over, or period > max_period. */
  return 0;
}

/* ---------------------------------------------------------------- peaks */

HmsaPeakParams hmsa_peak_params_default(void) {
  return (HmsaPeakParams){.prominence_rel = 0.05, .prominence_abs = 0, .xtol = 1e-3,
                          .max_evals = 40, .label_rtol = 0.1, .max_order = 4};
}

const char *hmsa_peak_kind_name(HmsaPeakKind kind) {
  switch (kind) {
  case HMSA_PEAK_PRIMARY: return "primary";
  case HMSA_PEAK_SUPERHARMONIC: return "superharmonic";
  case HMSA_PEAK_SUBHARMONIC: return "subharmonic";
  case HMSA_PEAK_OTHER: break;
  }
  return "other";
}

void hmsa_peak_label(double omega, double omega_p, const HmsaPeakParams *p, HmsaPeakKind *kind,
                     int *order, double *ratio) {
  HmsaPeakParams def = hmsa_peak_params_default();
  if (!p) p = &def;
  HmsaPeakKind kd = HMSA_PEAK_OTHER;
  int od = 0;
  double r = omega_p > 0 ? omega / omega_p : NAN;
  if (isfinite(r)) {
    /* The closest candidate ratio in relative terms wins. */
    double best = INFINITY;
    for (int n = 1; n <= (p->max_order > 1 ? p->max_order : 1); n++) {
      double cand[2] = {n, 1.0 / n};
      for (int c = 0; c < (n == 1 ? 1 : 2); c++) {
        double e = fabs(r - cand[c]) / cand[c];
        if (e <= p->label_rtol && e < best) {
          best = e;
          od = n;
          kd = n == 1 ? HMSA_PEAK_PRIMARY : (c == 0 ? HMSA_PEAK_SUBHARMONIC : HMSA_PEAK_SUPERHARMONIC);
        }
      }
    }
  }
  if (kind) *kind = kd;
  if (order) *order = od;
  if (ratio) *ratio = r;
}

int hmsa_golden_max(HmsaAmplitudeFn fn, void *ctx, double a, double b, double xtol, int max_evals,
                    double *x_best, double *f_best, int *n_evals) {
  SA_REQUIRE(fn && x_best && f_best, SA_ERR_INPUT, "golden-section: NULL argument");
  SA_REQUIRE(isfinite(a) && isfinite(b) && a < b, SA_ERR_INPUT,
             "golden-section: bad bracket [%g, %g]", a, b);
  SA_REQUIRE(max_evals >= 2, SA_ERR_INPUT, "golden-section: max_evals %d < 2", max_evals);
  const double g = 0.5 * (sqrt(5.0) - 1.0); /* 0.618..., the golden-ratio conjugate */
  double c = b - g * (b - a), e = a + g * (b - a), fc, fe;
  int ne = 0;
  SA_CHECK(fn(c, &fc, ctx));
  ne++;
  SA_CHECK(fn(e, &fe, ctx));
  ne++;
  double xb = fc >= fe ? c : e, fb = fmax(fc, fe);
  while (b - a > xtol && ne < max_evals) {
    if (fc >= fe) { /* maximum in [a, e] */
      b = e, e = c, fe = fc;
      c = b - g * (b - a);
      SA_CHECK(fn(c, &fc, ctx));
      ne++;
      if (fc > fb) fb = fc, xb = c;
    } else { /* maximum in [c, b] */
      a = c, c = e, fc = fe;
      e = a + g * (b - a);
      SA_CHECK(fn(e, &fe, ctx));
      ne++;
      if (fe > fb) fb = fe, xb = e;
    }
  }
  *x_best = xb;
  *f_best = fb;
  if (n_evals) *n_evals = ne;
  return 0;
}

static int cmp_peak_prominence(const void *a, const void *b) {
  double x = ((const HmsaPeak *)a)->prominence, y = ((const HmsaPeak *)b)->prominence;
  return (x < y) - (x > y); /* descending */
}

static int cmp_peak_omega(const void *a, const void *b) {
  double x = ((const HmsaPeak *)a)->omega_grid, y = ((const HmsaPeak *)b)->omega_grid;
  return (x > y) - (x < y);
}

int hmsa_peaks_find(int n, const double *omega, const double *amp, const HmsaPeakParams *p,
                    HmsaAmplitudeFn fn, void *ctx, double omega_p, int cap, HmsaPeak *peaks,
                    int *n_peaks) {
  HmsaPeakParams def = hmsa_peak_params_default();
  if (!p) p = &def;
  SA_REQUIRE(omega && amp && n_peaks && (peaks || cap == 0), SA_ERR_INPUT, "peaks: NULL argument");
  SA_REQUIRE(n >= 3, SA_ERR_INPUT, "peaks: %d samples, need at least 3", n);
  SA_REQUIRE(cap >= 0, SA_ERR_INPUT, "peaks: negative capacity %d", cap);
  SA_REQUIRE(p->prominence_rel >= 0 && p->prominence_abs >= 0 && p->xtol > 0 && p->max_evals >= 2 &&
                 p->label_rtol >= 0,
             SA_ERR_INPUT, "peaks: bad parameters");
  double lo = amp[0], hi = amp[0];
  for (int i = 0; i < n; i++) {
    SA_REQUIRE(isfinite(omega[i]) && isfinite(amp[i]), SA_ERR_NAN,
               "peaks: sample %d (%g, %g) is not finite", i, omega[i], amp[i]);
    SA_REQUIRE(i == 0 || omega[i] > omega[i - 1], SA_ERR_INPUT,
               "peaks: omega not strictly increasing at %d", i);
    lo = fmin(lo, amp[i]), hi = fmax(hi, amp[i]);
  }
  *n_peaks = 0;
  double pmin = p->prominence_abs + p->prominence_rel * (hi - lo);

  HmsaPeak *cand;
  SA_CALLOC(cand, n);
  int nc = 0;
  for (int i = 1; i < n - 1;) {
    /* A plateau a[i] == ... == a[r] counts once, at its middle, if both sides descend. */
    int r = i;
    while (r + 1 < n - 1 && amp[r + 1] == amp[i]) r++;
    if (amp[i] > amp[i - 1] && r + 1 < n && amp[i] > amp[r + 1]) {
      int m = (i + r) / 2;
      double lmin = amp[i], rmin = amp[i];
      for (int k = i - 1; k >= 0 && amp[k] <= amp[i]; k--) lmin = fmin(lmin, amp[k]);
      for (int k = r + 1; k < n && amp[k] <= amp[i]; k++) rmin = fmin(rmin, amp[k]);
      double prom = amp[i] - fmax(lmin, rmin);
      if (prom >= pmin && prom > 0)
        cand[nc++] = (HmsaPeak){.index = m, .omega_grid = omega[m], .amp_grid = amp[m],
                                .omega = omega[m], .amp = amp[m], .prominence = prom};
    }
    i = r + 1;
  }
  if (nc > cap) {
    qsort(cand, (size_t)nc, sizeof *cand, cmp_peak_prominence);
    nc = cap;
  }
  qsort(cand, (size_t)nc, sizeof *cand, cmp_peak_omega);

  for (int q = 0; q < nc && fn; q++) {
    HmsaPeak *pk = &cand[q];
    double a = omega[pk->index - 1], b = omega[pk->index + 1], xb, fb;
    int ne = 0;
    int rc = hmsa_golden_max(fn, ctx, a, b, p->xtol * (b - a), p->max_evals, &xb, &fb, &ne);
    pk->n_evals = ne;
    if (rc < 0) {
      free(cand);
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
    if (rc > 0) {
      pk->refine_status = rc;
      sa_error_clear();
      continue;
    }
    pk->refined = 1;
    /* The grid sample is an evaluation too: keep the better of the two. */
    if (fb > pk->amp_grid) pk->omega = xb, pk->amp = fb;
  }

  if (!(omega_p > 0) && nc > 0) {
    int ib = 0;
    for (int q = 1; q < nc; q++)
      if (cand[q].amp > cand[ib].amp) ib = q;
    omega_p = cand[ib].omega;
  }
  for (int q = 0; q < nc; q++)
    hmsa_peak_label(cand[q].omega, omega_p, p, &cand[q].kind, &cand[q].order, &cand[q].ratio);
  if (nc > 0) memcpy(peaks, cand, (size_t)nc * sizeof *cand);
  *n_peaks = nc;
  free(cand);
  return 0;
}
