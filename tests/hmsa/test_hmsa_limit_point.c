/* test_hmsa_limit_point - static equilibria exactly at and next to a limit point (issue 15,
 * item 3): every root, including the double root, is found, and the double root is reported
 * as a limit point.
 *
 * Independent reference (analytic, not from the code under test): on the relaxed Zener path
 * S(l) = l - l^-5 + b2 l^-3 (MODEL.md section 6), dS/dl = 1 + 5 l^-6 - 3 b2 l^-4 = 0 is, with
 * u = l^2, the depressed cubic u^3 - 3 b2 u + 5 = 0. For b2 = 3 (u^3 - 9 u + 5 = 0, three real
 * roots) the trigonometric solution u_k = 2 sqrt(b2) cos(phi/3 - 2 pi k/3),
 * cos(phi) = -5 / (2 b2^1.5), gives two positive roots: the limit points l = sqrt(u), at
 * prestress S_lp = S(l) (2.236 and 3.650, cases/hmsa_statics.ini). With S = S_lp the relaxed
 * polynomial l^6 - S l^5 + b2 l^2 - 1 has a double root at l_lp and one simple root elsewhere.
 * S_lp is rounded to a double, so the exact double root splits into two roots ~sqrt(eps) ~ 1e-8
 * apart or into none: the solver must return it (once) within 1e-6 in lambda. The simple root
 * is checked by its residual. Next to the limit point (S_lp -+ 1e-9 toward the three-root side)
 * the two roots are ~3e-5 apart, closer than the root-finder's grid: all three must be found;
 * on the other side one root only. */
#include "hmsa_model.h"

#include "hmsa_test.h"

static double poly(double l, double S, double b2) {
  return pow(l, 6) - S * pow(l, 5) + b2 * l * l - 1;
}
static double poly_scale(double l, double S, double b2) {
  return pow(l, 6) + fabs(S) * pow(l, 5) + fabs(b2) * l * l + 1;
}

int main(void) {
  const double b2 = 3.0;
  double phi = acos(-5.0 / (2.0 * pow(b2, 1.5))), llp[2];
  int nlp = 0;
  for (int k = 0; k < 3; k++) {
    double u = 2.0 * sqrt(b2) * cos(phi / 3.0 - 2.0 * HMSA_PI * k / 3.0);
    CLOSE(u * u * u - 3 * b2 * u + 5, 0, 1e-12, 0, "cubic root (reference)");
    if (u > 0 && nlp < 2) llp[nlp++] = sqrt(u);
  }
  EXPECT(nlp == 2, "two positive limit points expected from the cubic, got %d", nlp);
  HmsaModel m;
  hmsa_model_default(&m);
  for (int i = 0; i < nlp; i++) {
    double l = llp[i], Slp = l - pow(l, -5) + b2 * pow(l, -3);
    CLOSE(1 + 5 * pow(l, -6) - 3 * b2 * pow(l, -4), 0, 1e-12, 0, "dS/dlambda at the reference");
    /* the code's limit points agree with the reference */
    double lp[HMSA_MAX_ROOTS], sp[HMSA_MAX_ROOTS];
    int n;
    m.S = Slp;
    OK(hmsa_static_limit_points(&m, b2, lp, sp, &n));
    int hit = 0;
    for (int k = 0; k < n; k++)
      if (fabs(lp[k] - l) < 1e-12 * l && fabs(sp[k] - Slp) < 1e-12 * Slp) hit = 1;
    EXPECT(hit, "limit point lambda %.15g, S %.15g not among the %d reported", l, Slp, n);

    /* exactly at the limit point: the double root and the simple root */
    HmsaEquilibrium eq[HMSA_MAX_ROOTS];
    OK(hmsa_static_solve(&m, b2, eq, &n));
    EXPECT(n == 2, "S = S_lp = %.15g (lambda_lp %.15g): 2 equilibria expected (double + simple), "
           "found %d", Slp, l, n);
    int dbl = -1;
    for (int k = 0; k < n; k++) {
      double r = poly(eq[k].lambda, Slp, b2) / poly_scale(eq[k].lambda, Slp, b2);
      CLOSE(r, 0, 1e-14, 0, "relative residual of a reported root");
      if (fabs(eq[k].lambda - l) < 1e-6 * l) dbl = k;
    }
    EXPECT(dbl >= 0, "double root lambda = %.15g at S = S_lp not found", l);
    if (dbl >= 0) {
      EXPECT(eq[dbl].limit_point, "the double root is not reported as a limit point");
      EXPECT(!eq[dbl].stable, "the limit point is reported as stable");
      CLOSE(eq[dbl].K_r, 0, 1e-6, 0, "K_r at the double root");
    }
    for (int k = 0; k < n; k++)
      if (k != dbl) EXPECT(!eq[k].limit_point, "simple root %g reported as a limit point", eq[k].lambda);

    /* next to it: S on each side; the three-root side is the one toward the other limit load */
    double other = i == 0 ? llp[1] : llp[0];
    double Sother = other - pow(other, -5) + b2 * pow(other, -3);
    double side = Sother > Slp ? 1.0 : -1.0;
    for (int s = -1; s <= 1; s += 2) {
      m.S = Slp + s * side * 1e-9;
      OK(hmsa_static_solve(&m, b2, eq, &n));
      int expect = s > 0 ? 3 : 1;
      EXPECT(n == expect, "S = S_lp %+g: %d equilibria expected, found %d", s * side * 1e-9,
             expect, n);
      for (int k = 0; k < n; k++) {
        double r = poly(eq[k].lambda, m.S, b2) / poly_scale(eq[k].lambda, m.S, b2);
        CLOSE(r, 0, 1e-14, 0, "relative residual next to the limit point");
        EXPECT(!eq[k].limit_point, "root %g next to (not at) the limit point flagged", eq[k].lambda);
      }
      if (n == 3)
        EXPECT(eq[0].stable + eq[1].stable + eq[2].stable == 2 && !eq[1].stable,
               "stability pattern %d %d %d", eq[0].stable, eq[1].stable, eq[2].stable);
    }
  }
  TEST_RETURN();
}
