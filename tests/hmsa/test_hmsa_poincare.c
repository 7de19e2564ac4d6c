/* test_hmsa_poincare - Poincare sampling at tau = n 2 pi/Omega (dense output), steady-state
 * classification and the largest Lyapunov exponent (Benettin, two trajectories renormalised
 * every period).
 *
 * References:
 *  - Zener, sq loading far below resonance (Omega = 1, a3 small): the steady orbit is period-1
 *    and its largest Floquet exponent is that of the linearised equilibrium at the mean load,
 *    -min(decay, creep) from the cubic of section 6 (independent of the integration). The
 *    response amplitude ~1e-2 shifts it by O(a^2): 2 %.
 *  - Zener at the primary resonance (Omega = 2.13): period-1, exponent < 0.
 *  - Polymer chain (no dissipation) under the sq load: the free oscillation never decays and
 *    its frequency is incommensurate with the forcing: quasi-periodic, exponent ~ 0 (|.| < 0.01
 *    per period; measured 5e-4). */
#include <stdlib.h>
#include <string.h>

#include "hmsa_analysis.h"
#include "hmsa_classify.h"
#include "hmsa_test.h"

static int section(HmsaModel *m, int np, HmsaClassifyResult *cr, double *lyap) {
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.rtol = 1e-10, o.atol = 1e-12;
  double *x = calloc((size_t)np * 3, sizeof *x), y0[3];
  if (!x) return SA_ERROR(SA_ERR_MEMORY, "samples");
  hmsa_model_rest(m, y0);
  int rc = hmsa_poincare(m, &o, y0, 300, np, 1e-7, x, lyap, NULL);
  if (!rc) rc = hmsa_poincare_classify(np, hmsa_model_neq(m), x, *lyap, NULL, cr);
  /* the samples are the states at the period ends: check one against a direct integration */
  if (!rc) {
    HmsaIntegrator *it;
    double y[3];
    rc = hmsa_integrator_create(m, &o, &it);
    if (!rc) rc = hmsa_integrator_reset(it, 0, y0);
    if (!rc) rc = hmsa_integrator_advance(it, 301 * hmsa_model_period(m), y);
    hmsa_integrator_destroy(&it);
    if (!rc) CLOSE(x[0], y[0], 1e-8, 0, "first Poincare sample = state at tau = 301 T");
  }
  free(x);
  return rc;
}

int main(void) {
  HmsaModel m;
  HmsaClassifyResult cr;
  double lyap;
  hmsa_model_default(&m);
  m.loading = HMSA_LOAD_SQ, m.sgn = -1, m.omega = 1.0;
  OK(section(&m, 100, &cr, &lyap));
  EXPECT(cr.kind == HMSA_ORBIT_PERIODIC && cr.period == 1, "Omega 1: %s period %d",
         hmsa_orbit_kind_name(cr.kind), cr.period);
  HmsaEquilibrium eq[HMSA_MAX_ROOTS];
  int n;
  OK(hmsa_static_solve(&m, hmsa_model_b2_mean(&m), eq, &n));
  CLOSE(lyap / hmsa_model_period(&m), -fmin(eq[0].decay, eq[0].creep), 0, 0.02,
        "Lyapunov exponent off resonance against the linearised decay rate");
  m.omega = 2.13;
  OK(section(&m, 100, &cr, &lyap));
  EXPECT(cr.kind == HMSA_ORBIT_PERIODIC && cr.period == 1, "Omega 2.13: %s period %d",
         hmsa_orbit_kind_name(cr.kind), cr.period);
  EXPECT(lyap < 0, "Omega 2.13: exponent %g should be negative", lyap);
  hmsa_model_default(&m);
  m.model = HMSA_PC, m.mu_c = 1, m.mu_e = 0.5, m.lambda_max = 2;
  m.loading = HMSA_LOAD_SQ, m.sgn = -1, m.omega = 1.3;
  OK(section(&m, 300, &cr, &lyap));
  EXPECT(cr.kind == HMSA_ORBIT_QUASIPERIODIC, "PC: %s (period %d, mismatch %g)",
         hmsa_orbit_kind_name(cr.kind), cr.period, cr.mismatch);
  CLOSE(lyap, 0, 0.01, 0, "PC Lyapunov exponent per period ~ 0");
  TEST_RETURN();
}
