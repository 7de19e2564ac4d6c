/* test_hmsa_statics - static equilibria, stability, limit points and linearisation
 * (MODEL.md section 6), and relaxation of the dynamics onto the relaxed equilibrium.
 *
 * References:
 *  - S = 0: u = lambda^2 solves u^3 + b2 u - 1 = 0, solved here by Cardano's formula (one
 *    positive root by Descartes' rule) - independent of the bracketing solver.
 *  - S > 0: the relaxed polynomial l^6 - S l^5 + b2 l^2 - 1 has at most 3 positive roots
 *    (Descartes); where the solver finds 3, they are complete. Each root is checked for a
 *    residual, the stability pattern (stable, unstable, stable) and the limit points for K = 0.
 *  - Table of section 6 (spec author's values, 6 digits): lambda3 = 0.642053 (S 1, b2 0.16),
 *    0.574293 (S 1, b2 -0.16).
 *  - The damped frequency and decay rate from the cubic are checked as eigenvalues of the
 *    analytic 3x3 Jacobian at the equilibrium: det(J - s I) = 0 for s = -decay +- i omega_d
 *    and s = -creep.
 *  - Dynamics from rest under a constant load settle on the relaxed equilibrium (xi = lambda). */
#include <complex.h>

#include "hmsa_integrate.h"
#include "hmsa_test.h"

static double cardano_lambda3(double b2) {
  double p = b2, q = -1.0;
  double D = q * q / 4 + p * p * p / 27;
  double u;
  if (D >= 0) {
    u = cbrt(-q / 2 + sqrt(D)) + cbrt(-q / 2 - sqrt(D));
  } else { /* three real roots: the largest is the positive one */
    u = 2 * sqrt(-p / 3) * cos(acos(3 * q / (2 * p) * sqrt(-3 / p)) / 3);
  }
  return 1.0 / u;
}

static double complex det3(const double *J, double complex s) {
  double complex a[9];
  for (int i = 0; i < 9; i++) a[i] = J[i];
  for (int i = 0; i < 3; i++) a[i * 3 + i] -= s;
  return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
         a[2] * (a[3] * a[7] - a[4] * a[6]);
}

int main(void) {
  HmsaModel m;
  hmsa_model_default(&m);
  HmsaEquilibrium eq[HMSA_MAX_ROOTS];
  int n;
  /* Cardano, S = 0 */
  const double b2s[] = {0, 0.16, -0.16, 1, -1, 5, -5, 2.5, -2.5};
  for (int i = 0; i < 9; i++) {
    m.S = 0;
    OK(hmsa_static_solve(&m, b2s[i], eq, &n));
    EXPECT(n == 1, "S = 0, b2 = %g: one equilibrium expected, found %d", b2s[i], n);
    if (n >= 1) {
      CLOSE(eq[0].lambda3, cardano_lambda3(b2s[i]), 0, 1e-12, "lambda3 against Cardano");
      EXPECT(eq[0].stable, "S = 0 equilibria are stable (K_r = 4 + 2 l^-6)");
      double l = eq[0].lambda;
      CLOSE(eq[0].K_r, 4 + 2 * pow(l, -6), 0, 1e-10, "K_r at S = 0 equilibrium");
    }
  }
  /* section 6 table (S = 1): author's values to 6 digits, and the frequencies */
  m.S = 1;
  OK(hmsa_static_solve(&m, 0.16, eq, &n));
  EXPECT(n == 1, "S = 1, b2 = 0.16: %d roots", n);
  CLOSE(eq[0].lambda3, 0.642053, 1e-6, 0, "lambda3 (S 1, b2 0.16) against the table");
  CLOSE(eq[0].omega_r, 2.0419, 1e-4, 0, "omega_r (S 1, b2 0.16)");
  CLOSE(eq[0].omega_u, 4.3912, 1e-4, 0, "omega_u (S 1, b2 0.16)");
  OK(hmsa_static_solve(&m, -0.16, eq, &n));
  CLOSE(eq[0].lambda3, 0.574293, 1e-6, 0, "lambda3 (S 1, b2 -0.16) against the table");
  /* damped frequencies of the table (3 decimals) */
  const double Ss[] = {0, 0, 0, 1, 1}, bb[] = {0, 0.16, -0.16, 0.16, -0.16};
  const double wd[5][3] = {{3.278, 4.010, 4.234}, {3.037, 3.856, 4.114}, {3.500, 4.147, 4.342},
                           {4.023, 4.303, 4.388}, {4.133, 4.354, 4.422}};
  const double zt[5][3] = {{0.350, 0.188, 0.038}, {0.362, 0.204, 0.041}, {0.332, 0.174, 0.035},
                           {0.280, 0.138, 0.028}, {0.242, 0.120, 0.024}};
  const double etas[] = {5, 10, 50};
  for (int r = 0; r < 5; r++)
    for (int e = 0; e < 3; e++) {
      m.S = Ss[r], m.eta_bar = etas[e];
      OK(hmsa_static_solve(&m, bb[r], eq, &n));
      CLOSE(eq[0].omega_d, wd[r][e], 6e-4, 0, "omega_d against the table (3 decimals)");
      CLOSE(eq[0].zeta, zt[r][e], 6e-4, 0, "zeta against the table (3 decimals)");
      /* eigenvalues of the analytic Jacobian at the equilibrium */
      double y[3] = {eq[0].lambda, 0, eq[0].lambda}, J[9];
      m.b2 = bb[r];
      OK(hmsa_model_jacobian(&m, 0, y, J));
      double sc = eq[0].omega_u * eq[0].omega_u * (eq[0].omega_u + eq[0].creep);
      CLOSE(cabs(det3(J, -eq[0].decay + I * eq[0].omega_d)) / sc, 0, 1e-12, 0, "complex pair is an eigenvalue of J");
      CLOSE(cabs(det3(J, -eq[0].creep)) / sc, 0, 1e-12, 0, "creep rate is an eigenvalue of J");
    }
  m.eta_bar = 50;
  /* several equilibria: S = 3, b2 = 3 lies between the two limit points */
  m.S = 3.0;
  OK(hmsa_static_solve(&m, 3.0, eq, &n));
  EXPECT(n == 3, "S = 3, b2 = 3: three equilibria expected, found %d", n);
  if (n == 3) {
    for (int i = 0; i < 3; i++) {
      double l = eq[i].lambda;
      double P = pow(l, 6) - 3 * pow(l, 5) + 3 * l * l - 1;
      CLOSE(P / (pow(l, 6) + 3 * pow(l, 5) + 3 * l * l + 1), 0, 1e-14, 0, "root residual");
    }
    EXPECT(eq[0].stable && !eq[1].stable && eq[2].stable, "stability pattern %d %d %d",
           eq[0].stable, eq[1].stable, eq[2].stable);
  }
  double llp[HMSA_MAX_ROOTS], slp[HMSA_MAX_ROOTS];
  OK(hmsa_static_limit_points(&m, 3.0, llp, slp, &n));
  EXPECT(n == 2, "two limit points expected, found %d", n);
  for (int i = 0; i < n; i++) {
    double K;
    OK(hmsa_static_force(&m, llp[i], 3.0, NULL, &K));
    CLOSE(K, 0, 1e-10, 0, "K_r = 0 at the limit point");
    /* S_lp is the prestress on the relaxed path: S(l) = l - l^-5 + b2 l^-3 */
    CLOSE(slp[i], llp[i] - pow(llp[i], -5) + 3 * pow(llp[i], -3), 1e-12, 0, "limit-point prestress");
  }
  if (n == 2) EXPECT(fmin(slp[0], slp[1]) < 3 && 3 < fmax(slp[0], slp[1]), "S = 3 between the limit loads");
  /* polymer chain: roots inside the domain, F = 0, frequency from the FD stiffness */
  m.model = HMSA_PC, m.mu_c = 1, m.mu_e = 0.3, m.lambda_max = 1.2, m.S = 0;
  OK(hmsa_static_solve(&m, 2.0, eq, &n));
  EXPECT(n == 1, "PC: one equilibrium, found %d", n);
  if (n >= 1) {
    double lo, hi, F, Fp, Fm, l = eq[0].lambda;
    OK(hmsa_model_pc_domain(&m, &lo, &hi));
    EXPECT(lo < l && l < hi, "root %g inside (%g, %g)", l, lo, hi);
    OK(hmsa_static_force(&m, l, 2.0, &F, NULL));
    CLOSE(F, 0, 1e-12, 0, "PC F at root");
    OK(hmsa_static_force(&m, l + 1e-6, 2.0, &Fp, NULL));
    OK(hmsa_static_force(&m, l - 1e-6, 2.0, &Fm, NULL));
    double w = sqrt(3 * (Fp - Fm) / 2e-6 / (1 + 2 * m.c * pow(l, -6)));
    CLOSE(eq[0].omega_r, w, 0, 1e-7, "PC linear frequency");
  }
  /* relaxation: from rest, step load, long time -> relaxed equilibrium with xi = lambda */
  hmsa_model_default(&m);
  HmsaIntegratorOptions o;
  hmsa_integrator_options_default(&o);
  o.rtol = 1e-10, o.atol = 1e-12;
  const double relax_S[] = {0, 1, 0, 1}, relax_b2[] = {0.16, 0.16, -0.16, -0.16};
  for (int c = 0; c < 4; c++) {
    m.S = relax_S[c], m.b2 = relax_b2[c], m.eta_bar = 5;
    HmsaIntegrator *it;
    OK(hmsa_integrator_create(&m, &o, &it));
    double y[3];
    hmsa_model_rest(&m, y);
    OK(hmsa_integrator_reset(it, 0, y));
    /* slowest mode decays like exp(-0.35 tau) or slower (creep ~ 2.7, decay ~1.1 at eta 5):
     * tau = 120 leaves < 1e-12 */
    OK(hmsa_integrator_advance(it, 120, y));
    hmsa_integrator_destroy(&it);
    OK(hmsa_static_solve(&m, m.b2, eq, &n));
    double ref = m.S == 0 ? cardano_lambda3(m.b2) : eq[0].lambda3;
    CLOSE(hmsa_lambda3(y), ref, 1e-9, 0, "relaxed lambda3 after a long time");
    CLOSE(y[2], y[0], 1e-9, 0, "Maxwell branch relaxed: xi = lambda");
    CLOSE(y[1], 0, 1e-9, 0, "at rest");
  }
  TEST_RETURN();
}
