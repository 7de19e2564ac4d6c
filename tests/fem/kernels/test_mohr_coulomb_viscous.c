/* test_mohr_coulomb_viscous.c - Duvaut-Lions viscoplasticity of the Mohr-Coulomb law
 * (FemMohrCoulomb.tau_over_dt = w, the law's relaxation_time over FemLawCtx.dt).
 * References independent of the kernel's viscous path:
 *  - the definition (Simo and Hughes 1998, section 2.7, backward Euler): at any state the
 *    viscous P is (P_inviscid + w P_elastic) / (1 + w), with P_inviscid the same kernel at
 *    w = 0 and P_elastic the same material made unable to yield (cohesion 1e6 E), and the
 *    equivalent plastic strain grows by the inviscid increment / (1 + w);
 *  - the consistent tangent against central differences of P (h = 1e-6 on F; tol 1e-6 of
 *    max |A|), in every region the random states reach;
 *  - relaxation at a held F: the overstress |tau_n - tau_inviscid| decays by w / (1 + w) per
 *    step (the exact backward-Euler solution of d(tau)/dt = -(tau - tau_inviscid) / tau_r)
 *    and, with n steps over t = tau_r, approaches exp(-1) as n grows (to 1/(2n));
 *  - the law object (fem_law_mohr_coulomb): relaxation_time with ctx->dt > 0 is w = tau_r / dt,
 *    with dt = 0 rate-independent; a negative relaxation_time is SA_ERR_INPUT.
 * Pass -v to print the largest errors. */
#include <stdio.h>
#include <string.h>

#include "fem_law.h"
#include "fem_mohr_coulomb.h"
#include "kt_util.h"
#include "sa_error.h"

static double err_def, err_fd, err_relax, err_exp;
static int nregion[5];

static int eval(const FemMohrCoulomb *p, double w, const double F[9], const double *h,
                double *hn, double P[9], double A[81], double tau[9])
{
  FemMohrCoulomb q = *p;
  q.tau_over_dt = w;
  int rc = fem_mc_eval(&q, F, h, hn, P, A, tau);
  if (rc) {
    fprintf(stderr, "eval failed (%d): %s\n", rc, sa_error_message());
    sa_error_clear();
    kt_fail++;
  }
  return rc;
}

/* One state (F, history h) at viscosity w: definition, history and tangent. */
static void check_state(const char *name, const FemMohrCoulomb *p, double w, const double F[9],
                        const double h[FEM_MC_NHIST])
{
  char what[200];
  FemMohrCoulomb el = *p;
  el.c = 1e6 * p->young;
  double P[9], A[81], hn[8], P0[9], A0[81], h0[8], Pe[9], Ae[81];
  if (eval(p, w, F, h, hn, P, A, NULL) || eval(p, 0, F, h, h0, P0, A0, NULL) ||
      eval(&el, 0, F, h, NULL, Pe, Ae, NULL))
    return;
  nregion[(int)h0[7]]++;
  double Pmax = kt_maxabs(P0, 9) + kt_maxabs(Pe, 9), Amax = kt_maxabs(A, 81);
  for (int r = 0; r < 9; r++) {
    double ref = (P0[r] + w * Pe[r]) / (1 + w);
    snprintf(what, sizeof what, "%s, w %g: P[%d] = (P_inviscid + w P_elastic) / (1 + w)", name, w, r);
    kt_close(what, P[r], ref, 1e-12 * Pmax, 0);
    err_def = fmax(err_def, fabs(P[r] - ref) / Pmax);
  }
  snprintf(what, sizeof what, "%s, w %g: plastic strain increment / (1 + w)", name, w);
  kt_close(what, hn[6] - h[6], (h0[6] - h[6]) / (1 + w), 1e-13, 1e-10);
  for (int c = 0; c < 9; c++) {
    double Fp[9], Fm[9], Pp[9], Pm[9];
    memcpy(Fp, F, sizeof Fp), memcpy(Fm, F, sizeof Fm);
    Fp[c] += 1e-6, Fm[c] -= 1e-6;
    if (eval(p, w, Fp, h, NULL, Pp, NULL, NULL) || eval(p, w, Fm, h, NULL, Pm, NULL, NULL)) return;
    for (int r = 0; r < 9; r++) {
      double fd = (Pp[r] - Pm[r]) / 2e-6;
      snprintf(what, sizeof what, "%s, w %g, region %d: A[%d][%d] vs FD of P", name, w,
               (int)h0[7], r, c);
      kt_close(what, A[9 * r + c], fd, 1e-6 * Amax, 0);
      err_fd = fmax(err_fd, fabs(A[9 * r + c] - fd) / Amax);
    }
  }
}

static double dist(const double a[9], const double b[9])
{
  double s = 0;
  for (int i = 0; i < 9; i++) s += (a[i] - b[i]) * (a[i] - b[i]);
  return sqrt(s);
}

/* Relaxation at a held F from a virgin point: n steps over the time t_r (w = n). */
static double relax(const FemMohrCoulomb *p, const double F[9], int n, int check_steps)
{
  char what[160];
  double h[8], hn[8], P[9], tau[9], tau_inv[9], tau_tr[9];
  FemMohrCoulomb el = *p;
  el.c = 1e6 * p->young;
  if (eval(p, 0, F, NULL, NULL, P, NULL, tau_inv) || eval(&el, 0, F, NULL, NULL, P, NULL, tau_tr))
    return NAN;
  double d0 = dist(tau_tr, tau_inv), w = n, d = d0;
  fem_mc_hist_init(p, NULL, h);
  for (int k = 1; k <= n; k++) {
    if (eval(p, w, F, h, hn, P, NULL, tau)) return NAN;
    memcpy(h, hn, sizeof h);
    double dk = dist(tau, tau_inv);
    if (check_steps) {
      snprintf(what, sizeof what, "relaxation step %d: overstress ratio w / (1 + w)", k);
      kt_close(what, dk / d, w / (1 + w), 1e-9, 0);
      err_relax = fmax(err_relax, fabs(dk / d - w / (1 + w)));
    }
    d = dk;
  }
  return d / d0;
}

int main(int argc, char **argv)
{
  int verbose = argc > 1 && !strcmp(argv[1], "-v");
  const double deg = M_PI / 180;
  FemMohrCoulomb mats[] = {{20e6, 0.3, 30 * deg, 10e3, 30 * deg, 0, 0},
                           {20e6, 0.3, 28 * deg, 100, 3 * deg, 0, 0},
                           {5e6, 0.2, 35 * deg, 0, 5 * deg, 0, 0}};
  const char *names[] = {"associated", "fill (non-associated, c 100 Pa)",
                         "c = 0 (apex: the consistent zero blended)"};
  const double ws[] = {0.3, 4};
  for (int m = 0; m < 3; m++)
    for (int k = 0; k < 40; k++) {
      /* a plastic history (one inviscid step from a random F), then a random F from it */
      double F1[9], F[9], h1[8], P1[9];
      kt_random_F(0.02, kt_rand(0.97, 1.03), F1);
      if (eval(&mats[m], 0, F1, NULL, h1, P1, NULL, NULL)) continue;
      kt_random_F(0.03, kt_rand(0.96, 1.04), F);
      for (int i = 0; i < 2; i++) check_state(names[m], &mats[m], ws[i], F, h1);
    }
  for (int r = 1; r < 5; r++)
    if (!nregion[r]) fprintf(stderr, "note: no random state in region %d\n", r);
  if (!nregion[1] || !(nregion[2] + nregion[3])) {
    fprintf(stderr, "the random states reached neither a plane nor an edge\n");
    kt_fail++;
  }

  /* relaxation at a held F (a compressive shear well beyond yield) */
  double F[9] = {1.01, 0.004, 0, 0.002, 0.985, 0.003, 0, 0.001, 0.99};
  relax(&mats[1], F, 5, 1);
  relax(&mats[0], F, 5, 1);
  double prev = INFINITY;
  for (int n = 10; n <= 1000; n *= 10) {
    double ratio = relax(&mats[1], F, n, 0), e = fabs(ratio / exp(-1.0) - 1);
    char what[120];
    snprintf(what, sizeof what, "relaxation over t_r in %d steps: exp(-1) to 1/(2n)", n);
    kt_close(what, e, 0, 1.0 / (2 * n), 0);
    if (!(e < prev)) {
      fprintf(stderr, "relaxation error does not fall with n (%g at n = %d)\n", e, n);
      kt_fail++;
    }
    prev = e, err_exp = e;
  }

  /* the law object: relaxation_time over ctx->dt */
  const FemLaw *law = fem_law_find("mohr_coulomb");
  double par[7] = {20e6, 0.3, 28, 100, 3, 0, 0.5}, hist[8], P[9], Pw[9], W;
  law->init_hist(par, hist);
  FemLawCtx ctx = {0, 0.2, -1, -1, NULL};
  law->eval(par, &ctx, F, hist, NULL, &W, P, NULL);
  eval(&mats[1], 2.5, F, NULL, NULL, Pw, NULL, NULL);
  for (int r = 0; r < 9; r++) kt_close("law: relaxation_time 0.5 s, dt 0.2 s is w = 2.5", P[r], Pw[r], 1e-9, 0);
  ctx.dt = 0;
  law->eval(par, &ctx, F, hist, NULL, &W, P, NULL);
  eval(&mats[1], 0, F, NULL, NULL, Pw, NULL, NULL);
  for (int r = 0; r < 9; r++) kt_close("law: dt = 0 is rate-independent", P[r], Pw[r], 1e-9, 0);
  par[6] = -1;
  if (law->check(par) != SA_ERR_INPUT) {
    fprintf(stderr, "a negative relaxation_time was accepted\n");
    kt_fail++;
  }
  sa_error_clear();
  if (verbose)
    printf("states per region (elastic, plane, right, left, apex) %d %d %d %d %d; definition "
           "%.2e, A vs FD %.2e, per-step relaxation %.2e, exp(-1) at n = 1000 %.2e\n",
           nregion[0], nregion[1], nregion[2], nregion[3], nregion[4], err_def, err_fd,
           err_relax, err_exp);
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
