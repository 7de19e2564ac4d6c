/* test_hmsa_linear - small free vibrations oscillate at the linearised frequency (section 6).
 *
 * The state starts at the relaxed equilibrium plus a small multiple (1e-4) of the oscillatory
 * eigenvector of the analytic Jacobian there (Zener: the complex pair, so the creep mode is not
 * excited; PC: the undamped pair). In the linear regime lambda - lambda0 is then
 * A exp(-decay tau) cos(omega_d tau + phi), whose zeros are exactly pi/omega_d apart. The zeros
 * are located on the dense output (bisection) over up to 20 half-periods (fewer when damping
 * brings the amplitude 1e-4 down to 1e-10) and the mean spacing gives
 * the measured frequency, to be within 0.1 % of omega_d (issue requirement; amplitude effects
 * are O(1e-12) here, so the measured agreement is ~1e-6, limited by rtol). */
#include <complex.h>

#include "hmsa_integrate.h"
#include "hmsa_test.h"

static int measure(const HmsaModel *m, double *omega_meas, double *omega_lin) {
  HmsaEquilibrium eq[HMSA_MAX_ROOTS];
  int n;
  SA_CHECK(hmsa_static_solve(m, m->b2, eq, &n));
  const HmsaEquilibrium *e = &eq[0];
  double l0 = e->lambda, y0[3] = {l0, 0, l0}, J[9];
  SA_CHECK(hmsa_model_jacobian(m, 0, y0, J));
  double complex s = -e->decay + I * e->omega_d;
  int N = hmsa_model_neq(m);
  /* eigenvector (1, s, v2): row 3 of (J - s) v = 0 gives v2 = J20 / (s - J22) */
  double complex v2 = N == 3 ? J[6] / (s - J[8]) : 0;
  const double amp = 1e-4; /* frequency shift O(amp^2) = 1e-8 */
  double y[3] = {l0 + amp, amp * creal(s), l0 + amp * creal(v2)};
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.rtol = 1e-12, o.atol = 1e-18; /* the deviation is 1e-6: atol well below it */
  HmsaIntegrator *it;
  SA_CHECK(hmsa_integrator_create(m, &o, &it));
  SA_CHECK(hmsa_integrator_reset(it, 0, y));
  double T = 2 * HMSA_PI / e->omega_d, dt = T / 64, t = 0, gprev = amp;
  double zeros[32];
  int nz = 0, nzmax = 21;
  /* only zeros while the envelope stays well above the integration error (1e-10) */
  if (e->decay > 0) {
    int k = (int)(log(amp / 1e-10) / (e->decay * T / 2));
    if (k + 1 < nzmax) nzmax = k + 1;
  }
  double ya[3] = {y[0], y[1], y[2]};
  while (nz < nzmax) {
    double yb[3];
    SA_CHECK(hmsa_integrator_advance(it, t + dt, yb));
    double g = yb[0] - l0;
    if ((g < 0) != (gprev < 0)) {
      /* bisection on the dense output: re-integrate from the grid point */
      HmsaIntegrator *it2;
      SA_CHECK(hmsa_integrator_create(m, &o, &it2));
      double a = t, b = t + dt;
      for (int k = 0; k < 50; k++) {
        double c = 0.5 * (a + b), yc[3];
        SA_CHECK(hmsa_integrator_reset(it2, t, ya));
        SA_CHECK(hmsa_integrator_advance(it2, c, yc));
        if (((yc[0] - l0) < 0) == (gprev < 0)) a = c; else b = c;
      }
      hmsa_integrator_destroy(&it2);
      zeros[nz++] = 0.5 * (a + b);
    }
    for (int i = 0; i < 3; i++) ya[i] = yb[i];
    gprev = g;
    t += dt;
  }
  hmsa_integrator_destroy(&it);
  *omega_meas = HMSA_PI * (nz - 1) / (zeros[nz - 1] - zeros[0]);
  *omega_lin = e->omega_d;
  return 0;
}

int main(void) {
  HmsaModel m;
  double w, wl;
  const double etas[] = {5, 50}, Ss[] = {0, 1}, b2s[] = {0.16, -0.16};
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) {
      hmsa_model_default(&m);
      m.eta_bar = etas[i], m.S = Ss[j], m.b2 = b2s[(i + j) % 2];
      OK(measure(&m, &w, &wl));
      CLOSE(w, wl, 0, 1e-3, "Zener small-amplitude frequency against omega_d");
    }
  hmsa_model_default(&m);
  m.model = HMSA_PC, m.mu_c = 1, m.mu_e = 0.5, m.lambda_max = 1.5, m.S = 0.5, m.b2 = 0.16;
  OK(measure(&m, &w, &wl));
  CLOSE(w, wl, 0, 1e-3, "PC small-amplitude frequency against omega_r");
  TEST_RETURN();
}
