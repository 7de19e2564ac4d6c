/* test_hmsa_accuracy - every integrator's error tracks its tolerance (issue 15, item 2).
 *
 * Non-stiff case of the work-precision benchmark (docs/hmsa_benchmark.md): Zener, c = 1,
 * beta = 2, eta_bar = 50, S = 0, sq loading b_a = 0.4, sgn = -1, Omega = 2.13, from rest, 20
 * forcing periods sampled 128 times a period from the dense output (the benchmark protocol).
 * Reference: Dormand-Prince (erk) at rtol 1e-13, atol 1e-15, a different method whose own error
 * at that tolerance is ~1e-13 (erk at rtol r ends within 0.5 r of it). For each of erk, dirk
 * and bdf and rtol 1e-7 .. 1e-10 (atol 1e-2 rtol), the largest error over the samples of the
 * last forcing period, max norm of (lambda, lambda', xi), must stay within 100 rtol (global
 * error of a lightly damped oscillation after 20 periods). Measured at this setting (rtol 1e-7,
 * 1e-8, 1e-9, 1e-10): erk 0.5 0.4 0.5 0.5 rtol; bdf 21 25 41 65; dirk with the Hermite
 * interpolant 26 22 20 55; dirk with ARKODE's Lagrange interpolant (before issue 15) 540 600
 * 490 830, although its steps are as accurate as with Hermite.
 *
 * Stiff side of the same choice: at eta_bar = 1e-4 (Maxwell relaxation rate 2.4e5 against
 * oscillations at ~4) dirk's dense output must keep xi on the slow manifold: the energy balance
 * E(tau) + int_0^tau D = E(0) (MODEL.md section 5, D from the sampled state, composite Simpson
 * with dtau = 0.005) holds within 1e-5 (measured 7e-7 with the Lagrange interpolant there; the
 * Hermite interpolant gives ~5). */
#include <stdlib.h>
#include <string.h>

#include "hmsa_integrate.h"
#include "hmsa_test.h"

#define NPER 20
#define NSUB 128

static void model_nonstiff(HmsaModel *m) {
  hmsa_model_default(m);
  m->model = HMSA_ZENER;
  m->c = 1, m->beta = 2, m->eta_bar = 50, m->S = 0;
  m->loading = HMSA_LOAD_SQ, m->b_a = 0.4, m->sgn = -1, m->omega = 2.13;
}

/* samples of the last period: out[k * 3 + i], k = 0..NSUB */
static int run(const HmsaModel *m, HmsaMethod method, double rtol, double atol, double *out) {
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.method = method, o.rtol = rtol, o.atol = atol;
  HmsaIntegrator *it;
  SA_CHECK(hmsa_integrator_create(m, &o, &it));
  double y[3], T = 2.0 * HMSA_PI / m->omega;
  hmsa_model_rest(m, y);
  int rc = hmsa_integrator_reset(it, 0.0, y);
  for (int k = 1; !rc && k <= NPER * NSUB; k++) {
    rc = hmsa_integrator_advance(it, k * T / NSUB, y);
    int j = k - (NPER - 1) * NSUB;
    if (!rc && j >= 0) memcpy(out + 3 * j, y, sizeof y);
  }
  hmsa_integrator_destroy(&it);
  return rc;
}

static double energy(const HmsaModel *m, const double *y) {
  double T, U;
  if (hmsa_model_energy(m, y, m->b2, &T, &U)) return NAN;
  return T + U;
}

int main(void) {
  HmsaModel m;
  model_nonstiff(&m);
  static double ref[3 * (NSUB + 1)], y[3 * (NSUB + 1)];
  OK(run(&m, HMSA_METHOD_ERK, 1e-13, 1e-15, ref));
  const HmsaMethod methods[] = {HMSA_METHOD_ERK, HMSA_METHOD_DIRK, HMSA_METHOD_BDF};
  for (int q = 0; q < 3; q++)
    for (double rtol = 1e-7; rtol > 0.5e-10; rtol *= 0.1) {
      OK(run(&m, methods[q], rtol, 1e-2 * rtol, y));
      double err = 0;
      for (int k = 0; k < 3 * (NSUB + 1); k++) err = fmax(err, fabs(y[k] - ref[k]));
      char what[96];
      snprintf(what, sizeof what, "%s rtol %.0e: max error over the last period",
               hmsa_method_name(methods[q]), rtol);
      CLOSE(err, 0, 100 * rtol, 0, what);
    }

  /* stiff: dirk's dense output keeps the energy balance */
  HmsaModel s;
  hmsa_model_default(&s);
  s.eta_bar = 1e-4, s.S = 0, s.b2 = 0.16;
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.method = HMSA_METHOD_DIRK, o.rtol = 1e-8, o.atol = 1e-10;
  HmsaIntegrator *it;
  OK(hmsa_integrator_create(&s, &o, &it));
  double x[3];
  hmsa_model_rest(&s, x);
  OK(hmsa_integrator_reset(it, 0, x));
  double E0 = energy(&s, x), dt = 0.005, sum = hmsa_model_dissipation(&s, x, s.b2), bal = 0;
  for (long k = 1; k <= 2000; k++) {
    int rc = hmsa_integrator_advance(it, k * dt, x);
    if (rc) { hmsa_integrator_destroy(&it); OK(rc); }
    double D = hmsa_model_dissipation(&s, x, s.b2);
    if (k % 2 == 0) {
      bal = fmax(bal, fabs(energy(&s, x) + (sum + D) * dt / 3 - E0));
      sum += 2 * D;
    } else {
      sum += 4 * D;
    }
  }
  hmsa_integrator_destroy(&it);
  CLOSE(bal, 0, 1e-5, 0, "dirk eta_bar 1e-4: energy balance E + int D - E0");
  TEST_RETURN();
}
