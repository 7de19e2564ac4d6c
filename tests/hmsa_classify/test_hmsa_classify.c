/* test_hmsa_classify.c - Poincare-section classification and peak finding against synthetic
 * data with known answers:
 *   - logistic map x -> r x (1 - x): r = 3.2 has a stable 2-cycle (the period-doubling of the
 *     fixed point happens at r = 3, the next one at 1 + sqrt(6) = 3.449); r = 3.835 lies in the
 *     period-3 window (1 + sqrt(8) = 3.8284 .. 3.8415); r = 4 is chaotic with Lyapunov exponent
 *     exactly ln 2 (conjugate to the tent map).
 *   - a hand-made period-3 sequence in 3-D, with perturbations below and above the tolerance.
 *   - an irrational rotation, on a circle and on a non-uniformly parametrised ellipse (smoothly
 *     conjugate to the rotation, so quasi-periodic with exponent 0).
 *   - the Henon map (a = 1.4, b = 0.3): chaotic, largest exponent 0.42 (Sprott, Chaos and
 *     Time-Series Analysis, 2003, table of exponents).
 *   - Lorentzians h / (1 + ((w - w0)/g)^2), whose maximum is exactly at w0.
 * Silent on success; prints what differed and exits 1 on failure. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hmsa_classify.h"
#include "sa_error.h"

static const double PI = 3.14159265358979323846;
static int n_fail = 0;

#define EXPECT(cond, ...)                                                                   \
  do {                                                                                      \
    if (!(cond)) {                                                                          \
      fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                                       \
      fprintf(stderr, __VA_ARGS__);                                                         \
      fprintf(stderr, "\n");                                                                \
      n_fail++;                                                                             \
    }                                                                                       \
  } while (0)

static int close_to(double a, double b, double atol, double rtol) {
  return fabs(a - b) <= atol + rtol * fabs(b);
}

/* Start at 0.3, not 0.5: at r = 4, 0.5 -> 1 -> 0 lands exactly on the unstable fixed point. */
static void logistic(double r, int transient, int N, double *x) {
  double v = 0.3;
  for (int i = 0; i < transient; i++) v = r * v * (1 - v);
  for (int i = 0; i < N; i++) {
    x[i] = v;
    v = r * v * (1 - v);
  }
}

static void classify(int N, int d, const double *x, double lyap, HmsaClassifyResult *res) {
  int rc = hmsa_poincare_classify(N, d, x, lyap, NULL, res);
  if (rc) {
    sa_error_print();
    EXPECT(0, "hmsa_poincare_classify returned %d", rc);
  }
}

static void test_periodic(void) {
  enum { N = 200 };
  static double x[3 * N];
  HmsaClassifyResult res;

  /* Constant: period 1. */
  for (int i = 0; i < N; i++) x[i] = 0.7;
  classify(N, 1, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_PERIODIC && res.period == 1, "constant: %s k=%d",
         hmsa_orbit_kind_name(res.kind), res.period);

  /* Logistic r = 3.2: period 2. The 2-cycle multiplier is 4 + 2r - r^2 = 0.16, so 2000
   * iterates converge to rounding. */
  logistic(3.2, 2000, N, x);
  classify(N, 1, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_PERIODIC && res.period == 2, "logistic 3.2: %s k=%d",
         hmsa_orbit_kind_name(res.kind), res.period);

  /* Logistic r = 3.835: period 3. */
  logistic(3.835, 5000, N, x);
  classify(N, 1, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_PERIODIC && res.period == 3, "logistic 3.835: %s k=%d",
         hmsa_orbit_kind_name(res.kind), res.period);

  /* Hand-made 3-D period-3 cycle; noise 1e-7 relative to scale 2 is far below rtol = 1e-4. */
  const double cyc[3][3] = {{1.0, 0.1, 2.0}, {1.2, -0.1, 1.9}, {0.9, 0.0, 2.0}};
  for (int i = 0; i < N; i++)
    for (int j = 0; j < 3; j++) x[3 * i + j] = cyc[i % 3][j] + 1e-7 * sin(1.7 * i + j);
  classify(N, 3, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_PERIODIC && res.period == 3, "3-D cycle: %s k=%d mismatch %g",
         hmsa_orbit_kind_name(res.kind), res.period, res.mismatch);
  /* Period 6 = the 3-cycle with an alternating offset of 0.05 on one component. */
  for (int i = 0; i < N; i++) x[3 * i + 1] += (i % 2 ? 0.05 : 0.0);
  classify(N, 3, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_PERIODIC && res.period == 6, "3-D 6-cycle: %s k=%d",
         hmsa_orbit_kind_name(res.kind), res.period);
  /* Noise 1e-2 (relative 5e-3 > rtol): not periodic; the caller's exponent -0.5 says the
   * orbit still contracts, so the answer must be "unknown", not quasi-periodic. */
  unsigned lcg = 12345u; /* pseudo-random noise: no hidden period of its own */
  for (int i = 0; i < N; i++)
    for (int j = 0; j < 3; j++) {
      lcg = 1664525u * lcg + 1013904223u;
      x[3 * i + j] = cyc[i % 3][j] + 1e-2 * ((double)lcg / 4294967296.0 - 0.5);
    }
  classify(N, 3, x, -0.5, &res);
  EXPECT(res.kind == HMSA_ORBIT_UNKNOWN && res.period == 0, "noisy cycle: %s k=%d",
         hmsa_orbit_kind_name(res.kind), res.period);
  EXPECT(res.mismatch_k % 3 == 0, "noisy cycle: best k %d, not a multiple of 3", res.mismatch_k);

  /* A period above max_period with too few samples per period is not reported as periodic. */
  for (int i = 0; i < N; i++) x[i] = (double)(i % 20);
  classify(N, 1, x, -1.0, &res);
  EXPECT(res.kind == HMSA_ORBIT_UNKNOWN, "period 20 > 16: %s k=%d", hmsa_orbit_kind_name(res.kind),
         res.period);
}

static void test_quasiperiodic(void) {
  enum { N = 600 };
  static double x[3 * N];
  HmsaClassifyResult res;
  const double alpha = 0.5 * (sqrt(5.0) - 1.0); /* most irrational rotation number */

  /* Unit circle at height 0.5. */
  for (int i = 0; i < N; i++) {
    double th = 2 * PI * alpha * i;
    x[3 * i] = cos(th), x[3 * i + 1] = sin(th), x[3 * i + 2] = 0.5;
  }
  classify(N, 3, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_QUASIPERIODIC, "circle: %s (lyap_data %g)",
         hmsa_orbit_kind_name(res.kind), res.lyap_data);
  /* Rotation preserves distances exactly: the estimate is 0 to rounding. */
  EXPECT(fabs(res.lyap_data) < 1e-6, "circle: data exponent %g, expected 0", res.lyap_data);
  /* A curve has dimension 1; with 600 points the 1 %..10 % quantile range is in the linear
   * regime of C(r) to within the arc/chord difference (~5 %). */
  EXPECT(close_to(res.dim_corr, 1.0, 0.1, 0), "circle: dimension %g, expected 1", res.dim_corr);
  classify(N, 3, x, 0.0, &res);
  EXPECT(res.kind == HMSA_ORBIT_QUASIPERIODIC, "circle, caller exponent 0: %s",
         hmsa_orbit_kind_name(res.kind));

  /* Ellipse, non-uniform parametrisation phi = th + 0.3 sin th: still a rotation in th. */
  for (int i = 0; i < N; i++) {
    double th = 2 * PI * alpha * i, ph = th + 0.3 * sin(th);
    x[3 * i] = 1.0 + 0.2 * cos(ph), x[3 * i + 1] = 0.05 * sin(ph), x[3 * i + 2] = 1.0 + 0.01 * cos(ph);
  }
  classify(N, 3, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_QUASIPERIODIC, "ellipse: %s (lyap_data %g)",
         hmsa_orbit_kind_name(res.kind), res.lyap_data);
  EXPECT(close_to(res.dim_corr, 1.0, 0.15, 0), "ellipse: dimension %g, expected 1", res.dim_corr);
}

static void test_chaotic(void) {
  enum { N = 1000 };
  static double x[2 * N];
  HmsaClassifyResult res;

  /* Logistic r = 4: exponent ln 2. The nearest-neighbour estimate is coarse: the test asks for
   * ln 2 within 35 %, which still separates it clearly from 0 (data tolerance 0.1). */
  logistic(4.0, 100, N, x);
  classify(N, 1, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_CHAOTIC, "logistic 4: %s", hmsa_orbit_kind_name(res.kind));
  EXPECT(close_to(res.lyap_data, log(2.0), 0, 0.35), "logistic 4: data exponent %g, expected %g",
         res.lyap_data, log(2.0));
  classify(N, 1, x, log(2.0), &res);
  EXPECT(res.kind == HMSA_ORBIT_CHAOTIC && res.lyap == log(2.0), "logistic 4, caller exponent: %s",
         hmsa_orbit_kind_name(res.kind));
  /* A caller's exponent ~ 0 on non-repeating data means quasi-periodic (the caller is trusted). */
  classify(N, 1, x, 0.005, &res);
  EXPECT(res.kind == HMSA_ORBIT_QUASIPERIODIC, "caller exponent 0.005: %s",
         hmsa_orbit_kind_name(res.kind));

  /* Henon map: exponent 0.419; same 35 % allowance. */
  double u = 0.1, v = 0.1;
  for (int i = 0; i < 1000; i++) {
    double un = 1 - 1.4 * u * u + v;
    v = 0.3 * u, u = un;
  }
  for (int i = 0; i < N; i++) {
    x[2 * i] = u, x[2 * i + 1] = v;
    double un = 1 - 1.4 * u * u + v;
    v = 0.3 * u, u = un;
  }
  classify(N, 2, x, NAN, &res);
  EXPECT(res.kind == HMSA_ORBIT_CHAOTIC, "henon: %s", hmsa_orbit_kind_name(res.kind));
  EXPECT(close_to(res.lyap_data, 0.419, 0, 0.35), "henon: data exponent %g, expected 0.419",
         res.lyap_data);
  /* Henon attractor: correlation dimension 1.21 (Grassberger & Procaccia 1983); a coarse
   * two-radius estimate on 1000 points: between the curve (1) and the plane (2). */
  EXPECT(res.dim_corr > 1.0 && res.dim_corr < 1.5, "henon: dimension %g", res.dim_corr);

  /* Bad input. */
  x[5] = NAN;
  EXPECT(hmsa_poincare_classify(N, 1, x, NAN, NULL, &res) == SA_ERR_NAN, "NaN sample accepted");
  EXPECT(hmsa_poincare_classify(2, 1, x, NAN, NULL, &res) == SA_ERR_INPUT, "N = 2 accepted");
  sa_error_clear();
}

/* ---------------------------------------------------------------- peaks */

typedef struct {
  int n;
  double w0[5], h[5], g[5];
  int n_calls;
  int fail_code;   /* returned for omega inside [fail_lo, fail_hi] */
  double fail_lo, fail_hi;
} Curve;

static double curve_eval(const Curve *c, double w) {
  double s = 0;
  for (int k = 0; k < c->n; k++) {
    double u = (w - c->w0[k]) / c->g[k];
    s += c->h[k] / (1 + u * u);
  }
  return s;
}

/* d/dw of the sum of Lorentzians, analytic. */
static double curve_slope(const Curve *c, double w) {
  double s = 0;
  for (int k = 0; k < c->n; k++) {
    double u = (w - c->w0[k]) / c->g[k];
    s += -2 * c->h[k] * u / (c->g[k] * (1 + u * u) * (1 + u * u));
  }
  return s;
}

/* The maximum of the sum near w0[k]: root of the slope by bisection on w0 -+ g/2 (inside it
 * the peak's own slope dominates the tails of the others, so the slope changes sign once). */
static double curve_argmax(const Curve *c, int k) {
  double lo = c->w0[k] - 0.5 * c->g[k], hi = c->w0[k] + 0.5 * c->g[k];
  for (int it = 0; it < 200 && hi - lo > 1e-15; it++) {
    double m = 0.5 * (lo + hi);
    if (curve_slope(c, m) > 0) lo = m;
    else hi = m;
  }
  return 0.5 * (lo + hi);
}

static int curve_fn(double omega, double *amp, void *ctx) {
  Curve *c = ctx;
  c->n_calls++;
  if (c->fail_code && omega >= c->fail_lo && omega <= c->fail_hi)
    return SA_ERROR(c->fail_code, "synthetic failure at omega = %g", omega);
  *amp = curve_eval(c, omega);
  return 0;
}

static void sample(const Curve *c, int n, double w_lo, double w_hi, double *w, double *a) {
  for (int i = 0; i < n; i++) {
    w[i] = w_lo + (w_hi - w_lo) * i / (n - 1);
    a[i] = curve_eval(c, w[i]);
  }
}

static void test_golden(void) {
  /* Single Lorentzian at w0 = 2.1234 (not a grid point), width 0.05. */
  Curve c = {.n = 1, .w0 = {2.1234}, .h = {1.0}, .g = {0.05}};
  double xb, fb;
  int ne;
  int rc = hmsa_golden_max(curve_fn, &c, 2.0, 2.3, 1e-9, 100, &xb, &fb, &ne);
  EXPECT(rc == 0, "golden returned %d", rc);
  /* Near the maximum f = 1 - u^2, so f is flat to rounding (1e-16) within |w - w0| ~ g 1e-8:
   * the location is determined to ~ 1e-9, checked with margin 1e-7. */
  EXPECT(close_to(xb, 2.1234, 1e-7, 0), "golden: max at %.10f, expected 2.1234", xb);
  EXPECT(close_to(fb, 1.0, 1e-12, 0), "golden: max value %.15f, expected 1", fb);
  EXPECT(ne == c.n_calls && ne <= 100, "golden: %d evaluations reported, %d made", ne, c.n_calls);
}

static void test_peaks(void) {
  /* Primary at w0, superharmonic at w0/2, subharmonic at 2 w0, a peak at 1.6 w0 that has no
   * simple ratio, and a bump too small to count (prominence 0.01 < 5 % of the range ~ 1). The
   * tails of the others move each maximum by up to ~3e-5 (slope of the tails / curvature
   * 2 h / g^2 of the peak): the reference locations are the roots of the analytic slope. */
  const double w0 = 2.1234;
  Curve c = {.n = 5,
             .w0 = {w0, w0 / 2, 2 * w0, 1.6 * w0, 3.9},
             .h = {1.0, 0.2, 0.1, 0.3, 0.01},
             .g = {0.05, 0.05, 0.05, 0.05, 0.05}};
  enum { NG = 201 };
  double w[NG], a[NG];
  sample(&c, NG, 0.5, 5.5, w, a); /* spacing 0.025 = g / 2 resolves every peak */
  HmsaPeak pk[8];
  int np = 0;
  HmsaPeakParams p = hmsa_peak_params_default();
  p.xtol = 1e-6;
  p.max_evals = 60;
  int rc = hmsa_peaks_find(NG, w, a, &p, curve_fn, &c, 2.1, 8, pk, &np);
  EXPECT(rc == 0, "peaks returned %d", rc);
  EXPECT(np == 4, "found %d peaks, expected 4", np);
  if (np == 4) {
    const double want_w[4] = {curve_argmax(&c, 1), curve_argmax(&c, 0), curve_argmax(&c, 3),
                              curve_argmax(&c, 2)};
    const HmsaPeakKind want_k[4] = {HMSA_PEAK_SUPERHARMONIC, HMSA_PEAK_PRIMARY, HMSA_PEAK_OTHER,
                                    HMSA_PEAK_SUBHARMONIC};
    const int want_o[4] = {2, 1, 0, 2};
    for (int q = 0; q < 4; q++) {
      /* 1e-7: golden bracket 1e-6 x 0.05 = 5e-8 (the flat top adds ~1e-9). */
      EXPECT(close_to(pk[q].omega, want_w[q], 1e-7, 0), "peak %d at %.8f, expected %.8f", q,
             pk[q].omega, want_w[q]);
      EXPECT(pk[q].kind == want_k[q] && pk[q].order == want_o[q], "peak %d: %s order %d", q,
             hmsa_peak_kind_name(pk[q].kind), pk[q].order);
      EXPECT(pk[q].refined == 1 && pk[q].amp >= pk[q].amp_grid, "peak %d not refined", q);
    }
  }

  /* omega_p unknown: the highest peak is primary. Capacity 2 keeps the 2 most prominent. */
  c.n_calls = 0;
  rc = hmsa_peaks_find(NG, w, a, &p, curve_fn, &c, 0.0, 2, pk, &np);
  EXPECT(rc == 0 && np == 2, "cap 2: rc %d, %d peaks", rc, np);
  if (np == 2) {
    EXPECT(close_to(pk[0].omega, w0, 1e-5, 0) && pk[0].kind == HMSA_PEAK_PRIMARY,
           "cap 2: first peak %g %s", pk[0].omega, hmsa_peak_kind_name(pk[0].kind));
    EXPECT(close_to(pk[1].omega, 1.6 * w0, 1e-5, 0) && pk[1].kind == HMSA_PEAK_OTHER,
           "cap 2: second peak %g %s", pk[1].omega, hmsa_peak_kind_name(pk[1].kind));
  }

  /* No callback: grid maxima only. */
  rc = hmsa_peaks_find(NG, w, a, &p, NULL, NULL, w0, 8, pk, &np);
  EXPECT(rc == 0 && np == 4 && !pk[1].refined && pk[1].omega == pk[1].omega_grid,
         "no callback: rc %d, %d peaks", rc, np);

  /* Recoverable failure near the primary: that peak stays unrefined, the others are refined. */
  c.fail_code = SA_ERR_NOT_CONVERGED, c.fail_lo = 2.0, c.fail_hi = 2.3;
  rc = hmsa_peaks_find(NG, w, a, &p, curve_fn, &c, w0, 8, pk, &np);
  EXPECT(rc == 0 && np == 4, "recoverable failure: rc %d, %d peaks", rc, np);
  if (np == 4) {
    EXPECT(!pk[1].refined && pk[1].refine_status == SA_ERR_NOT_CONVERGED,
           "recoverable failure: primary refined %d status %d", pk[1].refined, pk[1].refine_status);
    EXPECT(pk[0].refined && pk[3].refined, "recoverable failure: others not refined");
    /* Labels still work from the grid location (2.125 vs w0: ratio within 10 %). */
    EXPECT(pk[1].kind == HMSA_PEAK_PRIMARY, "recoverable failure: primary labelled %s",
           hmsa_peak_kind_name(pk[1].kind));
  }
  /* Fatal failure: propagated. */
  c.fail_code = SA_ERR_IO;
  rc = hmsa_peaks_find(NG, w, a, &p, curve_fn, &c, w0, 8, pk, &np);
  EXPECT(rc == SA_ERR_IO, "fatal failure: rc %d, expected %d", rc, SA_ERR_IO);
  sa_error_clear();

  /* Monotone curve: no interior maximum. */
  for (int i = 0; i < NG; i++) a[i] = w[i];
  rc = hmsa_peaks_find(NG, w, a, &p, NULL, NULL, w0, 8, pk, &np);
  EXPECT(rc == 0 && np == 0, "monotone: rc %d, %d peaks", rc, np);

  /* Labelling: third-order ratios. */
  HmsaPeakKind k;
  int o;
  hmsa_peak_label(3.0 * 2.0 * 1.02, 2.0, NULL, &k, &o, NULL);
  EXPECT(k == HMSA_PEAK_SUBHARMONIC && o == 3, "label 3.06: %s %d", hmsa_peak_kind_name(k), o);
  hmsa_peak_label(2.0 / 3.0 * 0.97, 2.0, NULL, &k, &o, NULL);
  EXPECT(k == HMSA_PEAK_SUPERHARMONIC && o == 3, "label 1/3: %s %d", hmsa_peak_kind_name(k), o);
}

int main(void) {
  test_periodic();
  test_quasiperiodic();
  test_chaotic();
  test_golden();
  test_peaks();
  if (n_fail) fprintf(stderr, "%d check(s) failed\n", n_fail);
  return n_fail ? 1 : 0;
}
