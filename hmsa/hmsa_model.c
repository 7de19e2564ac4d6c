/* hmsa_model.c - right-hand side, analytic Jacobian, energies, statics and linearisation of the
 * HMSA reduced-order model, exactly as /work/shared/hmsa/MODEL.md sections 5-6. */
#include "hmsa_model.h"

#include <math.h>
#include <string.h>

#include "sa_error.h"

void hmsa_model_default(HmsaModel *m) {
  memset(m, 0, sizeof *m);
  m->model = HMSA_ZENER;
  m->c = 1.0;
  m->beta = 2.0;
  m->eta_bar = 50.0;
  m->S = 0.0;
  m->mu_c = 1.0;
  m->mu_e = 0.0;
  m->lambda_max = 2.0;
  m->loading = HMSA_LOAD_CONST;
  m->b2 = 0.16;
  m->b_a = 0.4;
  m->sgn = 1.0;
  m->omega = 2.13;
  m->b2_dc = 0.0;
  m->b2_ac = 0.16;
}

int hmsa_model_neq(const HmsaModel *m) { return m->model == HMSA_ZENER ? 3 : 2; }

double hmsa_model_b2(const HmsaModel *m, double tau) {
  switch (m->loading) {
  case HMSA_LOAD_SQ: {
    double s = sin(m->omega * tau);
    return m->sgn * m->b_a * m->b_a * s * s;
  }
  case HMSA_LOAD_LIN:
    return m->b2_dc + m->b2_ac * sin(m->omega * tau);
  default:
    return m->b2;
  }
}

double hmsa_model_b2_mean(const HmsaModel *m) {
  switch (m->loading) {
  case HMSA_LOAD_SQ:
    return 0.5 * m->sgn * m->b_a * m->b_a;
  case HMSA_LOAD_LIN:
    return m->b2_dc;
  default:
    return m->b2;
  }
}

double hmsa_model_period(const HmsaModel *m) {
  if (m->loading == HMSA_LOAD_CONST || m->omega <= 0) return 0.0;
  return 2.0 * HMSA_PI / m->omega;
}

void hmsa_model_rest(const HmsaModel *m, double *y) {
  y[0] = 1.0;
  y[1] = 0.0;
  if (m->model == HMSA_ZENER) y[2] = 1.0;
}

double hmsa_lambda3(const double *y) { return 1.0 / (y[0] * y[0]); }
double hmsa_dlambda3(const double *y) { return -2.0 * y[1] / (y[0] * y[0] * y[0]); }

int hmsa_model_pc_domain(const HmsaModel *m, double *lo, double *hi) {
  /* I1(l) = 2 l^2 + l^-4 is decreasing on (0,1), increasing on (1,inf), I1(1) = 3. */
  double lim = 3.0 * m->lambda_max * m->lambda_max;
  if (!(m->lambda_max > 1.0)) return SA_ERROR(SA_ERR_INPUT, "lambda_max = %g must exceed 1", m->lambda_max);
  double a = 1e-6, b = 1.0;
  for (int i = 0; i < 200; i++) { /* lower end on (0,1) */
    double x = 0.5 * (a + b);
    double x2 = x * x;
    if (2 * x2 + 1.0 / (x2 * x2) >= lim) a = x; else b = x;
  }
  *lo = b; /* inside */
  a = 1.0;
  b = m->lambda_max * 2.0;
  for (int i = 0; i < 200; i++) {
    double x = 0.5 * (a + b);
    double x2 = x * x;
    if (2 * x2 + 1.0 / (x2 * x2) >= lim) b = x; else a = x;
  }
  *hi = a;
  return 0;
}

int hmsa_model_force(const HmsaModel *m, double l, double xi, double b2, double *F, double *dF_dl,
                     double *dF_dxi) {
  if (!(l > 0) || !isfinite(l)) return SA_ERR_DOMAIN;
  double l2 = l * l, l3 = l2 * l, l4 = l2 * l2, l5 = l4 * l, l6 = l3 * l3;
  if (m->model == HMSA_ZENER) {
    if (!(xi > 0) || !isfinite(xi)) return SA_ERR_DOMAIN;
    double x2 = xi * xi, x3 = x2 * xi, x4 = x2 * x2;
    if (F) *F = (l - 1.0 / l5) + m->beta * (l / x2 - x4 / l5) - m->S + b2 / l3;
    if (dF_dl) *dF_dl = 1.0 + 5.0 / l6 + m->beta * (1.0 / x2 + 5.0 * x4 / l6) - 3.0 * b2 / l4;
    if (dF_dxi) *dF_dxi = m->beta * (-2.0 * l / x3 - 4.0 * x3 / l5);
    return 0;
  }
  double lm2 = m->lambda_max * m->lambda_max;
  double I1 = 2.0 * l2 + 1.0 / l4;
  double gap = 3.0 * lm2 - I1;
  if (!(gap > 0)) return SA_ERR_DOMAIN;
  double g = l - 1.0 / l5, gp = 1.0 + 5.0 / l6;
  double h = 1.0 / 3.0 + 2.0 * lm2 / gap;
  /* dh/dl = 2 lm^2 I1'/gap^2, I1' = 4 g */
  double hp = 2.0 * lm2 * 4.0 * g / (gap * gap);
  if (F) *F = m->mu_c * g * h + m->mu_e * (1.0 + l - 1.0 / l2 - 1.0 / l3) - m->S + b2 / l3;
  if (dF_dl)
    *dF_dl = m->mu_c * (gp * h + g * hp) + m->mu_e * (1.0 + 2.0 / l3 + 3.0 / l4) - 3.0 * b2 / l4;
  if (dF_dxi) *dF_dxi = 0.0;
  return 0;
}

int hmsa_model_rhs(const HmsaModel *m, double tau, const double *y, double *ydot) {
  double l = y[0], v = y[1];
  double xi = m->model == HMSA_ZENER ? y[2] : 1.0;
  double F;
  double b2 = hmsa_model_b2(m, tau);
  int rc = hmsa_model_force(m, l, xi, b2, &F, NULL, NULL);
  if (rc) return rc;
  double l2 = l * l, l3 = l2 * l, l6 = l3 * l3, l7 = l6 * l;
  double M = 1.0 + 2.0 * m->c / l6;
  ydot[0] = v;
  ydot[1] = (6.0 * m->c * v * v / l7 - 3.0 * F) / M;
  if (m->model == HMSA_ZENER) {
    double k = 2.0 * m->beta / m->eta_bar;
    double x3 = xi * xi * xi;
    ydot[2] = k * (l2 / x3 - x3 / (l2 * l2));
  }
  return 0;
}

int hmsa_model_jacobian(const HmsaModel *m, double tau, const double *y, double *J) {
  int n = hmsa_model_neq(m);
  double l = y[0], v = y[1];
  double xi = m->model == HMSA_ZENER ? y[2] : 1.0;
  double F, Fl, Fx;
  double b2 = hmsa_model_b2(m, tau);
  int rc = hmsa_model_force(m, l, xi, b2, &F, &Fl, &Fx);
  if (rc) return rc;
  double l2 = l * l, l3 = l2 * l, l6 = l3 * l3, l7 = l6 * l, l8 = l7 * l;
  double M = 1.0 + 2.0 * m->c / l6;
  double Ml = -12.0 * m->c / l7;
  double num = 6.0 * m->c * v * v / l7 - 3.0 * F;
  memset(J, 0, sizeof(double) * (size_t)(n * n));
  J[0 * n + 1] = 1.0;
  J[1 * n + 0] = (-42.0 * m->c * v * v / l8 - 3.0 * Fl) / M - num * Ml / (M * M);
  J[1 * n + 1] = 12.0 * m->c * v / l7 / M;
  if (m->model == HMSA_ZENER) {
    double k = 2.0 * m->beta / m->eta_bar;
    double x2 = xi * xi, x3 = x2 * xi, x4 = x2 * x2;
    double l4 = l2 * l2, l5 = l4 * l;
    J[1 * n + 2] = -3.0 * Fx / M;
    J[2 * n + 0] = k * (2.0 * l / x3 + 4.0 * x3 / l5);
    J[2 * n + 2] = k * (-3.0 * l2 / x4 - 3.0 * x2 / l4);
  }
  return 0;
}

int hmsa_model_energy(const HmsaModel *m, const double *y, double b2, double *T, double *U) {
  double l = y[0], v = y[1];
  if (!(l > 0)) return SA_ERR_DOMAIN;
  double l2 = l * l, l4 = l2 * l2, l6 = l4 * l2;
  *T = (1.0 / 3.0) * (1.0 + 2.0 * m->c / l6) * v * v;
  double load = -2.0 * m->S * (l - 1.0) - b2 / l2;
  if (m->model == HMSA_ZENER) {
    double xi = y[2];
    if (!(xi > 0)) return SA_ERR_DOMAIN;
    double x2 = xi * xi, x4 = x2 * x2;
    *U = 0.5 * (2.0 * l2 + 1.0 / l4 - 3.0) + 0.5 * m->beta * (2.0 * l2 / x2 + x4 / l4 - 3.0) + load;
    return 0;
  }
  double lm2 = m->lambda_max * m->lambda_max;
  double I1 = 2.0 * l2 + 1.0 / l4;
  if (!(3.0 * lm2 - I1 > 0)) return SA_ERR_DOMAIN;
  double W0 = m->mu_c * (0.5 - lm2 * log(3.0 * lm2 - 3.0)) + 6.0 * m->mu_e;
  *U = m->mu_c * (I1 / 6.0 - lm2 * log(3.0 * lm2 - I1)) +
       m->mu_e * (2.0 * l + 2.0 / l + l2 + 1.0 / l2) + load - W0;
  return 0;
}

double hmsa_model_dissipation(const HmsaModel *m, const double *y, double b2) {
  (void)b2;
  if (m->model != HMSA_ZENER) return 0.0;
  double l = y[0], xi = y[2];
  double k = 2.0 * m->beta / m->eta_bar;
  double x3 = xi * xi * xi;
  double xid = k * (l * l / x3 - x3 / (l * l * l * l));
  return m->eta_bar * xid * xid;
}

/* ---------------------------------------------------------------- statics */

int hmsa_static_force(const HmsaModel *m, double l, double b2, double *F, double *K) {
  if (m->model == HMSA_ZENER) {
    if (!(l > 0)) return SA_ERR_DOMAIN;
    double l2 = l * l, l3 = l2 * l, l4 = l2 * l2, l5 = l4 * l, l6 = l3 * l3;
    if (F) *F = l - 1.0 / l5 - m->S + b2 / l3;
    if (K) *K = 1.0 + 5.0 / l6 - 3.0 * b2 / l4;
    return 0;
  }
  return hmsa_model_force(m, l, 1.0, b2, F, K, NULL);
}

/* Search interval and a scaled function whose sign equals F_r's (Zener: l^5 F_r, the
 * polynomial l^6 - S l^5 + b2 l^2 - 1 of section 6, which is better behaved than F_r). */
static int static_interval(const HmsaModel *m, double *lo, double *hi) {
  if (m->model == HMSA_ZENER) {
    *lo = 1e-3;
    *hi = 1e3;
    return 0;
  }
  SA_CHECK(hmsa_model_pc_domain(m, lo, hi));
  /* stay strictly inside the pole: the force is +-inf there */
  double w = *hi - *lo;
  *lo += 1e-12 * w;
  *hi -= 1e-12 * w;
  return 0;
}

typedef int (*ScalarFn)(const HmsaModel *m, double l, double b2, double *val);

/* f = l^5 F_r for Zener (the polynomial l^6 - S l^5 + b2 l^2 - 1), F_r for PC. */
static int fn_force(const HmsaModel *m, double l, double b2, double *val) {
  if (m->model == HMSA_ZENER) {
    if (!(l > 0)) return SA_ERR_DOMAIN;
    double l2 = l * l, l5 = l2 * l2 * l;
    *val = (l - m->S) * l5 + b2 * l2 - 1.0;
    return 0;
  }
  return hmsa_static_force(m, l, b2, val, NULL);
}

/* df/dl of fn_force: Zener 6 l^5 - 5 S l^4 + 2 b2 l, PC K_r. */
static int fn_dforce(const HmsaModel *m, double l, double b2, double *val) {
  if (m->model == HMSA_ZENER) {
    if (!(l > 0)) return SA_ERR_DOMAIN;
    double l2 = l * l, l4 = l2 * l2;
    *val = (6.0 * l - 5.0 * m->S) * l4 + 2.0 * b2 * l;
    return 0;
  }
  return hmsa_static_force(m, l, b2, NULL, val);
}

/* Bound on the rounding error of fn_force at l: a few ulps of the sum of its terms' moduli. */
static double force_rounding(const HmsaModel *m, double l, double b2) {
  double mag;
  if (m->model == HMSA_ZENER) {
    double l2 = l * l, l5 = l2 * l2 * l;
    mag = l5 * l + fabs(m->S) * l5 + fabs(b2) * l2 + 1.0;
  } else {
    double F;
    if (hmsa_static_force(m, l, 0.0, &F, NULL)) return 0.0;
    F += m->S; /* the elastic part alone */
    mag = fabs(F) + fabs(m->S) + fabs(b2) / (l * l * l);
  }
  return 64.0 * 2.220446049250313e-16 * mag;
}

static int fn_stiff(const HmsaModel *m, double l, double b2, double *val) {
  double K;
  int rc = hmsa_static_force(m, l, b2, NULL, &K);
  if (rc) return rc;
  double l2 = l * l;
  *val = m->model == HMSA_ZENER ? K * (l2 * l2 * l2) : K;
  return 0;
}

/* Root of fn in [a, b] (fa = fn(a) and fn(b) of opposite signs) by bisection to machine
 * precision. */
static double bisect(const HmsaModel *m, double b2, ScalarFn fn, double a, double b, double fa) {
  for (int it = 0; it < 200 && b - a > 4e-16 * b; it++) {
    double c = 0.5 * (a + b), fc;
    if (fn(m, c, b2, &fc)) break;
    if (fc == 0.0) return c;
    if ((fc < 0) == (fa < 0)) { a = c; fa = fc; } else b = c;
  }
  return 0.5 * (a + b);
}

/* All sign changes of fn on a fine grid over (lo, hi), refined by bisection to machine precision.
 * Grid: logarithmic for Zener (roots span decades), uniform in a tanh-like stretch for PC so
 * points cluster at the poles. A root where fn touches zero without changing sign, or two roots
 * inside one grid cell, are not seen here: hmsa_static_solve therefore brackets F_r between the
 * zeros of its derivative, where it is monotone. */
static int bracket_roots(const HmsaModel *m, double b2, ScalarFn fn, double *roots, int *n) {
  double lo, hi;
  SA_CHECK(static_interval(m, &lo, &hi));
  const int N = 20000;
  int nr = 0;
  double xp = 0, fp = 0;
  int have = 0;
  for (int i = 0; i <= N; i++) {
    double s = (double)i / N, x;
    if (m->model == HMSA_ZENER) {
      x = lo * pow(hi / lo, s);
    } else {
      double u = 0.5 * (1.0 - cos(HMSA_PI * s)); /* clusters at both ends */
      x = lo + (hi - lo) * u;
    }
    double f;
    if (fn(m, x, b2, &f)) continue;
    if (have && f == 0.0) {
      if (nr < HMSA_MAX_ROOTS) roots[nr++] = x;
    } else if (have && (fp < 0) != (f < 0) && fp != 0.0) {
      if (nr < HMSA_MAX_ROOTS) roots[nr++] = bisect(m, b2, fn, xp, x, fp);
    }
    xp = x;
    fp = f;
    have = 1;
  }
  *n = nr;
  return 0;
}

/* Every root of the equilibrium function f (fn_force). f is monotone between consecutive zeros
 * of f' (found by bracket_roots on fn_dforce), so each such piece holds at most one simple root,
 * found by bisection when f changes sign over it, however close it lies to its neighbours. At
 * a zero c of f' with |f(c)| within f's rounding error, f touches zero: a double root (a limit
 * point of the prestress path), returned once with *dbl set; the pieces next to it then count
 * f(c) as 0 so that no copy of it is bracketed. roots sorted ascending. */
static int equilibrium_roots(const HmsaModel *m, double b2, double *roots, int *dbl, int *n) {
  double lo, hi, crit[HMSA_MAX_ROOTS];
  int nc, nr = 0;
  SA_CHECK(static_interval(m, &lo, &hi));
  SA_CHECK(bracket_roots(m, b2, fn_dforce, crit, &nc));
  double x[HMSA_MAX_ROOTS + 2], f[HMSA_MAX_ROOTS + 2];
  int ok[HMSA_MAX_ROOTS + 2], np = 0;
  x[np++] = lo;
  for (int i = 0; i < nc; i++) x[np++] = crit[i];
  x[np++] = hi;
  for (int i = 0; i < np; i++) ok[i] = fn_force(m, x[i], b2, &f[i]) == 0;
  for (int i = 0; i < np; i++) {
    if (i > 0 && ok[i - 1] && ok[i] && ((f[i - 1] < 0 && f[i] > 0) || (f[i - 1] > 0 && f[i] < 0)))
      if (nr < HMSA_MAX_ROOTS) {
        roots[nr] = bisect(m, b2, fn_force, x[i - 1], x[i], f[i - 1]);
        dbl[nr++] = 0;
      }
    if (i > 0 && i < np - 1 && ok[i] && fabs(f[i]) <= force_rounding(m, x[i], b2)) {
      if (nr < HMSA_MAX_ROOTS) {
        roots[nr] = x[i];
        dbl[nr++] = 1;
      }
      f[i] = 0.0;
    }
  }
  *n = nr;
  return 0;
}

/* Real root of s^3 + r s^2 + wu2 s + r wr2 on (-r, 0) and the remaining quadratic. */
static void zener_cubic(double r, double wr2, double wu2, HmsaEquilibrium *eq) {
  double a = -r, b = 0.0;
  for (int i = 0; i < 300 && b - a > 1e-16 * (1 + fabs(a)); i++) {
    double s = 0.5 * (a + b);
    double p = ((s + r) * s + wu2) * s + r * wr2;
    if (p < 0) a = s; else b = s;
  }
  double s1 = 0.5 * (a + b);
  double p = r + s1, q = wu2 + s1 * p;
  eq->creep = -s1;
  double disc = p * p - 4.0 * q;
  if (disc < 0) {
    eq->omega_d = sqrt(-disc) / 2.0;
    eq->decay = p / 2.0;
    eq->zeta = q > 0 ? (p / 2.0) / sqrt(q) : 0.0;
  } else {
    eq->omega_d = 0.0;
    eq->decay = (p - sqrt(disc)) / 2.0; /* slowest of the two real modes */
    eq->zeta = q > 0 ? (p / 2.0) / sqrt(q) : 1.0;
  }
}

int hmsa_linearise(const HmsaModel *m, double l0, double b2, HmsaEquilibrium *eq) {
  memset(eq, 0, sizeof *eq);
  double K;
  int rc = hmsa_static_force(m, l0, b2, NULL, &K);
  if (rc) return SA_ERROR(rc, "equilibrium lambda = %g outside the model's domain", l0);
  double l02 = l0 * l0, M0 = 1.0 + 2.0 * m->c / (l02 * l02 * l02);
  eq->lambda = l0;
  eq->lambda3 = 1.0 / (l0 * l0);
  eq->K_r = K;
  eq->K_u = m->model == HMSA_ZENER ? K + 6.0 * m->beta / (l0 * l0) : K;
  eq->stable = K > 0;
  eq->omega_r = K > 0 ? sqrt(3.0 * K / M0) : 0.0;
  eq->omega_u = eq->K_u > 0 ? sqrt(3.0 * eq->K_u / M0) : 0.0;
  if (m->model == HMSA_ZENER && K > 0) {
    double r = 12.0 * m->beta / (m->eta_bar * l0 * l0);
    zener_cubic(r, 3.0 * K / M0, 3.0 * eq->K_u / M0, eq);
  } else {
    eq->omega_d = eq->omega_r;
    eq->zeta = 0.0;
  }
  return 0;
}

int hmsa_static_solve(const HmsaModel *m, double b2, HmsaEquilibrium *eq, int *nroots) {
  double roots[HMSA_MAX_ROOTS];
  int n, dbl[HMSA_MAX_ROOTS];
  SA_CHECK(equilibrium_roots(m, b2, roots, dbl, &n));
  for (int i = 0; i < n; i++) {
    SA_CHECK(hmsa_linearise(m, roots[i], b2, &eq[i]));
    if (dbl[i]) { /* K_r = 0 up to rounding: marginal, not stable */
      eq[i].limit_point = 1;
      eq[i].stable = 0;
    }
  }
  *nroots = n;
  return 0;
}

int hmsa_static_limit_points(const HmsaModel *m, double b2, double *lambda_lp, double *S_lp,
                             int *n) {
  SA_CHECK(bracket_roots(m, b2, fn_stiff, lambda_lp, n));
  for (int i = 0; i < *n; i++) {
    double F;
    SA_CHECK(hmsa_static_force(m, lambda_lp[i], b2, &F, NULL));
    S_lp[i] = F + m->S;
  }
  return 0;
}
