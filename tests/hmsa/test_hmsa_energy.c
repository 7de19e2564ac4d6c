/* test_hmsa_energy - conservation and dissipation identities of MODEL.md section 5.
 *
 * (a) No dissipation under a constant load: E = T + U is a first integral of (E1). Checked over
 *     10^4 periods of the linearised frequency for the polymer-chain model, and over 2000
 *     periods for a chain near its limit and for the Zener model with beta = 0
 *     (Dormand-Prince, rtol 1e-10: the drift grows linearly with rtol and with the number of
 *     periods; measured 6.6e-8 over 1e4 periods, 1e-7 .. 4e-7 for 1e4 periods of the others).
 * (b) Zener: dE/dtau = -(2 beta/k)(xi')^2 = -eta_bar (xi')^2, checked pointwise (gradient of E
 *     by finite differences dotted with the implemented rhs) and integrated along a trajectory:
 *     E(tau) + int_0^tau eta_bar xi'^2 = E(0) (composite Simpson on the dense output). */
#include <stdlib.h>

#include "hmsa_integrate.h"
#include "hmsa_test.h"

/* Max |E(tau_k) - E(0)| at the ends of n_periods periods of the linearised frequency. */
static int conserved(const HmsaModel *m, int n_periods, double *drift, double *E0out, long *steps) {
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.method = HMSA_METHOD_ERK;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  HmsaEquilibrium eq[HMSA_MAX_ROOTS];
  int n;
  SA_CHECK(hmsa_static_solve(m, m->b2, eq, &n));
  SA_REQUIRE(n >= 1, SA_ERR_INTERNAL, "no equilibrium");
  double T = 2 * HMSA_PI / eq[0].omega_r;
  HmsaIntegrator *it;
  SA_CHECK(hmsa_integrator_create(m, &o, &it));
  double y[3];
  hmsa_model_rest(m, y);
  SA_CHECK(hmsa_integrator_reset(it, 0, y));
  double Tk, U, E0;
  SA_CHECK(hmsa_model_energy(m, y, m->b2, &Tk, &U));
  E0 = Tk + U;
  *drift = 0;
  for (int k = 1; k <= n_periods; k++) {
    SA_CHECK(hmsa_integrator_advance(it, k * T, y));
    SA_CHECK(hmsa_model_energy(m, y, m->b2, &Tk, &U));
    *drift = fmax(*drift, fabs(Tk + U - E0));
  }
  HmsaIntegratorStats st;
  hmsa_integrator_get_stats(it, &st);
  *steps = st.steps;
  *E0out = E0;
  hmsa_integrator_destroy(&it);
  return 0;
}

static double energy(const HmsaModel *m, const double *y) {
  double T, U;
  hmsa_model_energy(m, y, m->b2, &T, &U);
  return T + U;
}

int main(void) {
  double drift, E0;
  long steps;
  HmsaModel m;
  /* (a) polymer chain: m_c = 1, m_e = 0.5, lambda_max = 2, S = 0.5, b2 = 0.16 */
  hmsa_model_default(&m);
  m.model = HMSA_PC;
  m.mu_c = 1, m.mu_e = 0.5, m.lambda_max = 2, m.S = 0.5, m.b2 = 0.16;
  OK(conserved(&m, 10000, &drift, &E0, &steps));
  /* |E0| = 0.16; 1e-6 absolute (6e-6 relative) leaves a factor 15 over the measured drift and
   * is far below what a wrong energy term gives (1e-3 and more) */
  CLOSE(drift, 0.0, 1e-6, 0, "PC energy drift over 1e4 periods");
  /* a stiff chain close to its limit */
  m.lambda_max = 1.2, m.mu_e = 0, m.S = 0, m.b2 = 2.0;
  OK(conserved(&m, 2000, &drift, &E0, &steps));
  CLOSE(drift, 0.0, 1e-6, 0, "PC (lambda_max 1.2, b2 2) energy drift over 2000 periods");
  /* (a) Zener with beta = 0: xi decouples and the equilibrium spring alone is conservative */
  hmsa_model_default(&m);
  m.beta = 0, m.S = 1, m.b2 = -0.16;
  OK(conserved(&m, 2000, &drift, &E0, &steps));
  CLOSE(drift, 0.0, 1e-6, 0, "Zener beta = 0 energy drift over 2000 periods");

  /* (b) pointwise identity dE/dtau = -eta_bar xi'^2 at random states (fourth-order central
   * differences of E, h = 2e-4: truncation h^4 |E^(5)|/30 <~ 1e-10 for the l^-4 xi^4 terms at
   * l = 0.6, rounding ~ eps |E|/h ~ 1e-11) */
  unsigned long long seed = 12345;
  for (int t = 0; t < 200; t++) {
    hmsa_model_default(&m);
    m.beta = hmsa_test_uniform(&seed, 0.1, 3), m.eta_bar = hmsa_test_uniform(&seed, 1, 60);
    m.c = hmsa_test_uniform(&seed, 0.2, 2), m.S = hmsa_test_uniform(&seed, -1, 1);
    m.b2 = hmsa_test_uniform(&seed, -1, 1);
    double y[3] = {hmsa_test_uniform(&seed, 0.6, 1.5), hmsa_test_uniform(&seed, -1, 1),
                   hmsa_test_uniform(&seed, 0.6, 1.5)};
    double f[3], dE = 0, h = 2e-4;
    OK(hmsa_model_rhs(&m, 0, y, f));
    for (int j = 0; j < 3; j++) {
      double y1[3] = {y[0], y[1], y[2]}, y2[3] = {y[0], y[1], y[2]};
      double y3[3] = {y[0], y[1], y[2]}, y4[3] = {y[0], y[1], y[2]};
      y1[j] += 2 * h, y2[j] += h, y3[j] -= h, y4[j] -= 2 * h;
      dE += (-energy(&m, y1) + 8 * energy(&m, y2) - 8 * energy(&m, y3) + energy(&m, y4)) /
            (12 * h) * f[j];
    }
    double D = hmsa_model_dissipation(&m, y, m.b2);
    CLOSE(dE, -D, 1e-8 * (1 + fabs(D)), 1e-7, "dE/dtau = -eta_bar xi'^2");
    CLOSE(D, (2 * m.beta / (2 * m.beta / m.eta_bar)) * f[2] * f[2], 0, 1e-12, "(2 beta/k) xi'^2");
  }
  /* (b) integrated balance along a trajectory, eta_bar = 5 (strong dissipation) */
  hmsa_model_default(&m);
  m.eta_bar = 5, m.S = 1, m.b2 = 0.16;
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.rtol = 1e-11, o.atol = 1e-13;
  HmsaIntegrator *it;
  OK(hmsa_integrator_create(&m, &o, &it));
  double y[3];
  hmsa_model_rest(&m, y);
  OK(hmsa_integrator_reset(it, 0, y));
  E0 = energy(&m, y);
  const double dt = 0.005; /* Simpson error ~ dt^4 max|D''''| tau / 180 ~ 1e-11 */
  const int N = 10000;     /* tau = 50 */
  double sum = hmsa_model_dissipation(&m, y, m.b2), maxerr = 0;
  for (int k = 1; k <= N; k++) {
    OK(hmsa_integrator_advance(it, k * dt, y));
    double D = hmsa_model_dissipation(&m, y, m.b2);
    if (k % 2 == 0) {
      double integral = (sum + D) * dt / 3; /* Simpson up to tau = k dt */
      maxerr = fmax(maxerr, fabs(energy(&m, y) + integral - E0));
      sum += 2 * D;
    } else {
      sum += 4 * D;
    }
  }
  hmsa_integrator_destroy(&it);
  /* the dissipated energy is ~0.1; integrator (rtol 1e-11) and Simpson errors ~1e-10 */
  CLOSE(maxerr, 0.0, 1e-8, 0, "Zener energy balance E + int D = E0");
  TEST_RETURN();
}
