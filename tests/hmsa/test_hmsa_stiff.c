/* test_hmsa_stiff - the stiff and extreme regimes of MODEL.md section 9.
 *
 * Each row runs from rest with method auto (the default) and must finish without NaN with its
 * check holding, or stop with the documented diagnosis:
 *   Zener eta_bar 1e-3 and 1e-5  auto must switch to BDF; energy balance E + int D = E0
 *   PC lambda_max 1.2, b2 = +2     energy conserved (no dissipation)
 *   PC lambda_max 1.05, b2 = +50   frequency ~77; energy conserved; at rtol 1e-4 (erk) stages land
 *                                  beyond the pole and must be rejected (counted), never NaN
 *   PC lambda_max 1.01, b2 = -500  the turning point lies ~1e-28 from the pole (energy barrier
 *                                  -lm^2 ln(gap) must absorb ~65): not representable, so the run
 *                                  must stop with SA_ERR_DOMAIN naming the PC pole
 *   Zener |b2| = 5, S = 0 and 1   energy balance
 *   Zener S = 2.5, b2 = 3          three equilibria; dynamics from rest settle on a stable one
 * The energy balance uses composite Simpson on the dense output (dtau = 0.005) for int D.
 * With --report every row is also run with erk, dirk and bdf (explicit capped at 3e6 steps)
 * and a markdown table of steps, rejected steps, RHS/Jacobian evaluations, time and outcome is
 * printed (docs/hmsa.md). */
#include <stdlib.h>
#include <string.h>

#include "hmsa_integrate.h"
#include "hmsa_test.h"
#include "sa_log.h"

typedef struct {
  const char *name;
  HmsaModel m;
  double t_end;
  int expect_domain; /* 1: must stop with SA_ERR_DOMAIN */
  int expect_switch; /* 1: auto must switch to bdf */
} Row;

typedef struct {
  int rc;
  double balance; /* max |E + int D - E0| */
  double y[3];
  int finite;
  HmsaIntegratorStats st;
  double seconds;
  char msg[256];
} Outcome;

static double energy(const HmsaModel *m, const double *y) {
  double T, U;
  if (hmsa_model_energy(m, y, m->b2, &T, &U)) return NAN;
  return T + U;
}

static int run_row(const Row *r, HmsaMethod method, double rtol, long cap, Outcome *out) {
  memset(out, 0, sizeof *out);
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.method = method, o.rtol = rtol, o.atol = rtol * 1e-2;
  if (cap > 0) o.max_steps = cap;
  HmsaIntegrator *it;
  SA_CHECK(hmsa_integrator_create(&r->m, &o, &it));
  double y[3];
  hmsa_model_rest(&r->m, y);
  SA_CHECK(hmsa_integrator_reset(it, 0, y));
  double E0 = energy(&r->m, y), dt = 0.005, sum = hmsa_model_dissipation(&r->m, y, r->m.b2);
  long N = (long)lround(r->t_end / dt);
  double t0 = sa_time_now();
  out->finite = 1;
  for (long k = 1; k <= N; k++) {
    int rc = hmsa_integrator_advance(it, k * dt, y);
    if (rc) {
      out->rc = rc;
      snprintf(out->msg, sizeof out->msg, "%s", sa_error_message());
      sa_error_clear();
      break;
    }
    for (int i = 0; i < hmsa_model_neq(&r->m); i++) out->finite &= isfinite(y[i]);
    double D = hmsa_model_dissipation(&r->m, y, r->m.b2);
    if (k % 2 == 0) {
      double bal = fabs(energy(&r->m, y) + (sum + D) * dt / 3 - E0);
      out->balance = fmax(out->balance, bal);
      sum += 2 * D;
    } else {
      sum += 4 * D;
    }
  }
  out->seconds = sa_time_now() - t0;
  for (int i = 0; i < 3; i++) out->y[i] = y[i];
  hmsa_integrator_get_stats(it, &out->st);
  hmsa_integrator_destroy(&it);
  return 0;
}

int main(int argc, char **argv) {
  int report = argc > 1 && !strcmp(argv[1], "--report");
  Row rows[9];
  int nr = 0;
#define ZENER(nm, eta, S_, b2_, tend, sw)                                                   \
  do {                                                                                    \
    Row *r = &rows[nr++];                                                                 \
    hmsa_model_default(&r->m);                                                            \
    r->name = nm, r->m.eta_bar = eta, r->m.S = S_, r->m.b2 = b2_, r->t_end = tend;          \
    r->expect_domain = 0, r->expect_switch = sw;                                          \
  } while (0)
#define PC(nm, lm, b2_, tend, dom)                                                          \
  do {                                                                                    \
    Row *r = &rows[nr++];                                                                 \
    hmsa_model_default(&r->m);                                                            \
    r->name = nm, r->m.model = HMSA_PC, r->m.mu_c = 1, r->m.mu_e = 0, r->m.lambda_max = lm; \
    r->m.b2 = b2_, r->m.S = 0, r->t_end = tend, r->expect_domain = dom, r->expect_switch = 0; \
  } while (0)
  ZENER("Zener eta 1e-3 (k 4e3)", 1e-3, 0, 0.16, 20, 1);
  ZENER("Zener eta 1e-5 (k 4e5)", 1e-5, 0, 0.16, 20, 1);
  PC("PC lambda_max 1.2, b2 +2", 1.2, 2, 50, 0);
  PC("PC lambda_max 1.05, b2 +50", 1.05, 50, 20, 0);
  PC("PC lambda_max 1.01, b2 -500", 1.01, -500, 5, 1);
  ZENER("Zener b2 +5, S 0", 50, 0, 5, 50, 0);
  ZENER("Zener b2 -5, S 0", 50, 0, -5, 50, 0);
  ZENER("Zener b2 +5, S 1", 50, 1, 5, 50, 0);
  ZENER("Zener S 2.5, b2 3 (3 equilibria)", 5, 2.5, 3, 150, 0);
  const double rtol = 1e-9;
  for (int i = 0; i < nr; i++) {
    Outcome o;
    OK(run_row(&rows[i], HMSA_METHOD_AUTO, rtol, 0, &o));
    const Row *r = &rows[i];
    EXPECT(o.finite, "%s: non-finite state", r->name);
    if (r->expect_domain) {
      EXPECT(o.rc == SA_ERR_DOMAIN && strstr(o.msg, "PC pole"),
             "%s: expected SA_ERR_DOMAIN with the pole diagnosis, got %d (%s)", r->name, o.rc, o.msg);
      continue;
    }
    EXPECT(o.rc == 0, "%s: failed with %d: %s", r->name, o.rc, o.msg);
    if (r->expect_switch)
      EXPECT(o.st.switched && o.st.active == HMSA_METHOD_BDF, "%s: auto did not switch to bdf", r->name);
    else
      EXPECT(!o.st.switched, "%s: auto switched although the problem is not stiff", r->name);
    /* energy balance: |E0| <= ~10 here; integrator error (rtol 1e-9) and Simpson (dt 0.005)
     * stay below 1e-6 relative to max(1, |E0|) (measured <= 1e-7) */
    double y0[3];
    hmsa_model_rest(&r->m, y0);
    CLOSE(o.balance, 0, 1e-6 * fmax(1, fabs(energy(&r->m, y0))), 0, r->name);
    if (r->m.S == 2.5) { /* settled on a stable equilibrium, Maxwell branch relaxed */
      HmsaEquilibrium eq[HMSA_MAX_ROOTS];
      int n, hit = 0;
      OK(hmsa_static_solve(&r->m, r->m.b2, eq, &n));
      for (int k = 0; k < n; k++)
        if (eq[k].stable && fabs(o.y[0] - eq[k].lambda) < 1e-6) hit = 1;
      EXPECT(n == 3 && hit, "S 2.5, b2 3: final lambda %g is not a stable equilibrium", o.y[0]);
      CLOSE(o.y[2], o.y[0], 1e-6, 0, "xi = lambda at the end");
    }
  }
  /* loose tolerance near the pole: stages beyond it must be rejected (counted), never NaN */
  {
    Outcome o;
    OK(run_row(&rows[3], HMSA_METHOD_ERK, 1e-4, 0, &o));
    if (getenv("HMSA_TEST_VERBOSE"))
      printf("loose PC: rc %d domain rejections %ld balance %g steps %ld\n", o.rc, o.st.domain_fails,
             o.balance, o.st.steps);
    EXPECT(o.rc == 0 && o.finite, "PC near the pole at rtol 1e-4: rc %d (%s)", o.rc, o.msg);
    EXPECT(o.st.domain_fails > 0, "PC near the pole at rtol 1e-4: no stage was rejected");
    /* loose rtol: energy held to 1e-2 relative (|E0| = 50) */
    CLOSE(o.balance, 0, 0.5, 0, "PC near the pole at rtol 1e-4: energy");
  }
  if (report) {
    printf("| regime | method | steps | rejected | RHS evals | Jac evals | domain rejections | time [s] | outcome |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    const HmsaMethod ms[] = {HMSA_METHOD_ERK, HMSA_METHOD_DIRK, HMSA_METHOD_BDF, HMSA_METHOD_AUTO};
    for (int i = 0; i < nr; i++)
      for (int k = 0; k < 4; k++) {
        Outcome o;
        OK(run_row(&rows[i], ms[k], rtol, ms[k] == HMSA_METHOD_AUTO ? 0 : 3000000, &o));
        char outcome[320];
        if (o.rc == 0)
          snprintf(outcome, sizeof outcome, "ok, energy balance %.1e%s", o.balance,
                   o.st.switched ? ", switched to bdf" : "");
        else
          snprintf(outcome, sizeof outcome, "%s: %.150s", sa_error_string(o.rc), o.msg);
        printf("| %s | %s | %ld | %ld | %ld | %ld | %ld | %.3f | %s |\n", rows[i].name,
               hmsa_method_name(ms[k]), o.st.steps, o.st.attempts - o.st.steps, o.st.rhs_evals,
               o.st.jac_evals, o.st.domain_fails, o.seconds, outcome);
        fflush(stdout);
      }
  }
  TEST_RETURN();
}
