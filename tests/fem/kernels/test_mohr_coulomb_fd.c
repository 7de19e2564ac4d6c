/* test_mohr_coulomb_fd.c - finite-strain Mohr-Coulomb law (fem_mc_eval):
 *  - states built to land in each region: trial principal log strains from a stress on the
 *    plane, an edge or the apex plus D times flow vectors (as in test_mohr_coulomb_return), in a
 *    random frame, behind a random plastic history C_p^-1 = Fp^-1 Fp^-T (F = Ve R Fp); also
 *    exactly repeated trial eigenvalues (edge pairs, hydrostatic apex, elastic pairs);
 *  - A = dP/dF against central differences of P with step h = 1e-6 on F (truncation ~h^2,
 *    round-off ~1e-16 |P| / h, both < 1e-9 of max |A| here); tol 1e-6 of max |A|;
 *  - major symmetry A_iJkL = A_kLiJ for psi = phi (1e-8), asymmetry for psi < phi;
 *  - region, plastic volume change ln det Fp_new - ln det Fp_n = 2 sin(psi) (dg_a + dg_b);
 *  - P F^T = tau symmetric; re-evaluating with the new history at the same F gives the same P
 *    and no further plastic strain (consistent history, new state on the surface);
 *  - objectivity: P(QF) = Q P(F), A(QF)_iJkL = Q_im Q_kn A(F)_mJnL, same new history;
 *  - F = I, virgin: A = lambda d_iJ d_kL + G (d_ik d_JL + d_iL d_Jk) (Hooke);
 *  - initialisation hook: K0 and a rotated general state give back tau0 at F = I; an
 *    inadmissible tau0 is SA_ERR_INPUT;
 *  - apex_stiffness: at the apex the same P and history, and the tangent of the point kept
 *    elastic with the apex's geometric term at apex_stiffness = 1, linear in between;
 *  - codes: det F <= 0 is SA_ERR_INVERTED, a NaN is SA_ERR_DOMAIN (both recoverable, > 0).
 * Pass -v to print the largest errors (reported in docs/mohr_coulomb.md). */
#include <stdio.h>
#include <string.h>

#include "fem_mohr_coulomb.h"
#include "kt_util.h"
#include "sa_error.h"

static double err_fd[5], err_obj, err_sym, err_idem, err_init;
static int ncase[5];

static void mm(const double A[9], const double B[9], double C[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

static void transpose(const double A[9], double T[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * j + i] = A[3 * i + j];
}

static void inv3(const double A[9], double B[9])
{
  double d = kt_det3(A);
  B[0] = (A[4] * A[8] - A[5] * A[7]) / d, B[1] = (A[2] * A[7] - A[1] * A[8]) / d;
  B[2] = (A[1] * A[5] - A[2] * A[4]) / d, B[3] = (A[5] * A[6] - A[3] * A[8]) / d;
  B[4] = (A[0] * A[8] - A[2] * A[6]) / d, B[5] = (A[2] * A[3] - A[0] * A[5]) / d;
  B[6] = (A[3] * A[7] - A[4] * A[6]) / d, B[7] = (A[1] * A[6] - A[0] * A[7]) / d;
  B[8] = (A[0] * A[4] - A[1] * A[3]) / d;
}

static void random_rotation(double R[9])
{
  double w[3] = {kt_rand(-2, 2), kt_rand(-2, 2), kt_rand(-2, 2)};
  kt_rotation(w, R);
}

typedef struct {
  double G, K, lam, sf, cf, sp;
} Consts;

static Consts consts(const FemMohrCoulomb *p)
{
  Consts k;
  k.G = p->young / (2 * (1 + p->poisson));
  k.K = p->young / (3 * (1 - 2 * p->poisson));
  k.lam = k.K - 2 * k.G / 3;
  k.sf = sin(p->phi), k.cf = cos(p->phi), k.sp = sin(p->psi);
  return k;
}

static void Dv(const Consts *k, const double v[3], double o[3])
{
  double tr = v[0] + v[1] + v[2];
  for (int i = 0; i < 3; i++) o[i] = k->lam * tr + 2 * k->G * v[i];
}

static void n_ij(double sn, int i, int j, double n[3])
{
  n[0] = n[1] = n[2] = 0;
  n[i] = 1 + sn, n[j] = -(1 - sn);
}

/* F and history whose trial principal Kirchhoff stresses are sT (random frame, random Fp). */
static void build_state(const FemMohrCoulomb *p, const double sT[3], double F[9], double hist[8])
{
  double tr = sT[0] + sT[1] + sT[2], nu = p->poisson, R0[9], R0t[9], V[9] = {0}, T1[9], Ve[9];
  for (int a = 0; a < 3; a++) V[4 * a] = exp(((1 + nu) * sT[a] - nu * tr) / p->young);
  random_rotation(R0);
  transpose(R0, R0t);
  mm(R0, V, T1);
  mm(T1, R0t, Ve);
  double Fp[9], Fpi[9], Fpit[9], Cpi[9], R1[9];
  kt_random_F(0.2, kt_rand(0.9, 1.1), Fp);
  inv3(Fp, Fpi);
  transpose(Fpi, Fpit);
  mm(Fpi, Fpit, Cpi);
  random_rotation(R1);
  mm(Ve, R1, T1);
  mm(T1, Fp, F);
  hist[0] = Cpi[0], hist[1] = Cpi[4], hist[2] = Cpi[8];
  hist[3] = Cpi[5], hist[4] = Cpi[2], hist[5] = Cpi[1];
  hist[6] = kt_rand(0, 0.1), hist[7] = 0;
}

static double det_voigt(const double h[6])
{
  double M[9] = {h[0], h[5], h[4], h[5], h[1], h[3], h[4], h[3], h[2]};
  return kt_det3(M);
}

/* apex_stiffness a at an apex state (F, hist; P0, A0, hn0 its results with a = 0): P and the
 * new history do not depend on a; the tangent is linear in a (A(1/2) = (A(0) + A(1)) / 2); and
 * A(1) is the tangent of the same point kept elastic (cohesion 1e6 E, A_el) with the geometric
 * term -P_iL F^-1_Jk of the apex's P instead of the elastic point's:
 * A(1) = A_el - (P - P_el)_iL F^-1_Jk (the material part is then the elastic one). */
static double err_apex;
static void check_apex_stiffness(const char *name, const FemMohrCoulomb *p, const double F[9],
                                 const double hist[8], const double hn0[8], const double P0[9],
                                 const double A0[81])
{
  char what[200];
  FemMohrCoulomb p1 = *p, ph = *p, pe = *p;
  p1.apex_stiffness = 1, ph.apex_stiffness = 0.5, pe.c = 1e6 * p->young;
  double h1[8], he[8], P1[9], A1[81], Ph[9], Ah[81], Pe[9], Ae[81], Fi[9];
  if (fem_mc_eval(&p1, F, hist, h1, P1, A1, NULL) || fem_mc_eval(&ph, F, hist, NULL, Ph, Ah, NULL) ||
      fem_mc_eval(&pe, F, hist, he, Pe, Ae, NULL)) {
    fprintf(stderr, "%s: eval with apex_stiffness failed: %s\n", name, sa_error_message());
    sa_error_clear();
    kt_fail++;
    return;
  }
  if ((int)he[7] != FEM_MC_ELASTIC || (int)h1[7] != FEM_MC_APEX) {
    fprintf(stderr, "%s: regions %d (cohesion 1e6 E) and %d (apex_stiffness 1)\n", name,
            (int)he[7], (int)h1[7]);
    kt_fail++;
  }
  for (int r = 0; r < 9; r++) {
    snprintf(what, sizeof what, "%s: P with apex_stiffness [%d]", name, r);
    kt_close(what, P1[r], P0[r], 0, 0);
  }
  for (int r = 0; r < 8; r++) {
    snprintf(what, sizeof what, "%s: history with apex_stiffness [%d]", name, r);
    kt_close(what, h1[r], hn0[r], 0, 0);
  }
  inv3(F, Fi);
  double Amax = kt_maxabs(Ae, 81);
  for (int i = 0; i < 3; i++)
    for (int J = 0; J < 3; J++)
      for (int k = 0; k < 3; k++)
        for (int L = 0; L < 3; L++) {
          int ix = 9 * (3 * i + J) + 3 * k + L;
          double ref = Ae[ix] - (P1[3 * i + L] - Pe[3 * i + L]) * Fi[3 * J + k];
          snprintf(what, sizeof what, "%s: A(apex_stiffness 1)[%d%d%d%d] = elastic", name, i, J,
                   k, L);
          kt_close(what, A1[ix], ref, 1e-10 * Amax, 0);
          err_apex = fmax(err_apex, fabs(A1[ix] - ref) / Amax);
          snprintf(what, sizeof what, "%s: A linear in apex_stiffness [%d]", name, ix);
          kt_close(what, Ah[ix], 0.5 * (A0[ix] + A1[ix]), 1e-12 * Amax, 0);
        }
}

static void check_state(const char *name, const FemMohrCoulomb *p, const double sT[3],
                        FemMcRegion region, double dg_sum)
{
  char what[200];
  double F[9], hist[8], hn[8], P[9], A[81], tau[9];
  build_state(p, sT, F, hist);
  int rc = fem_mc_eval(p, F, hist, hn, P, A, tau);
  if (rc) {
    fprintf(stderr, "%s: eval failed (%d): %s\n", name, rc, sa_error_message());
    sa_error_clear();
    kt_fail++;
    return;
  }
  if ((int)hn[7] != (int)region) {
    fprintf(stderr, "%s: region %d, expected %d\n", name, (int)hn[7], (int)region);
    kt_fail++;
  }
  ncase[region]++;
  double Pmax = kt_maxabs(P, 9), Amax = kt_maxabs(A, 81), h = 1e-6, e = 0;
  /* P F^T = tau, symmetric */
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double t = 0;
      for (int L = 0; L < 3; L++) t += P[3 * i + L] * F[3 * j + L];
      snprintf(what, sizeof what, "%s: (P F^T)[%d%d] = tau", name, i, j);
      kt_close(what, t, tau[3 * i + j], 1e-12 * kt_maxabs(tau, 9), 0);
      snprintf(what, sizeof what, "%s: tau symmetric", name);
      kt_close(what, tau[3 * i + j], tau[3 * j + i], 1e-13 * kt_maxabs(tau, 9), 0);
    }
  /* FD of P */
  for (int c = 0; c < 9; c++) {
    double Fp[9], Fm[9], Pp[9], Pm[9];
    memcpy(Fp, F, sizeof Fp), memcpy(Fm, F, sizeof Fm);
    Fp[c] += h, Fm[c] -= h;
    int r1 = fem_mc_eval(p, Fp, hist, NULL, Pp, NULL, NULL);
    int r2 = fem_mc_eval(p, Fm, hist, NULL, Pm, NULL, NULL);
    if (r1 || r2) {
      fprintf(stderr, "%s: perturbed eval failed\n", name);
      kt_fail++;
      return;
    }
    for (int r = 0; r < 9; r++) {
      double fd = (Pp[r] - Pm[r]) / (2 * h);
      snprintf(what, sizeof what, "%s: A[%d][%d] vs FD of P", name, r, c);
      kt_close(what, A[9 * r + c], fd, 1e-6 * Amax, 0);
      e = fmax(e, fabs(A[9 * r + c] - fd) / Amax);
    }
  }
  if (e > err_fd[region]) err_fd[region] = e;
  /* symmetry */
  double asym = 0;
  for (int r = 0; r < 9; r++)
    for (int c = 0; c < 9; c++) asym = fmax(asym, fabs(A[9 * r + c] - A[9 * c + r]) / Amax);
  if (fem_mc_symmetric(p)) {
    snprintf(what, sizeof what, "%s: major symmetry (associated)", name);
    kt_close(what, asym, 0, 1e-8, 0);
    err_sym = fmax(err_sym, asym);
  } else if (region == FEM_MC_PLANE && asym < 1e-4) {
    fprintf(stderr, "%s: non-associated but symmetric tangent (%g)\n", name, asym);
    kt_fail++;
  }
  if (region == FEM_MC_APEX) check_apex_stiffness(name, p, F, hist, hn, P, A);
  /* plastic volume change */
  if (region == FEM_MC_PLANE || region == FEM_MC_EDGE_LEFT || region == FEM_MC_EDGE_RIGHT) {
    double dv = -0.5 * log(det_voigt(hn) / det_voigt(hist));
    snprintf(what, sizeof what, "%s: plastic volume change 2 sin(psi) dgamma", name);
    kt_close(what, dv, 2 * sin(p->psi) * dg_sum, 1e-10 * dg_sum, 1e-9);
  }
  if (region != FEM_MC_ELASTIC && !(hn[6] > hist[6])) {
    fprintf(stderr, "%s: equivalent plastic strain did not grow\n", name);
    kt_fail++;
  }
  /* the new history is consistent: the same F gives the same P with no further plastic flow
     (the state is on the surface up to round-off, so a region other than elastic is allowed) */
  double h2[8], P2[9], Pscale = Pmax + 1e-3 * p->young;
  fem_mc_eval(p, F, hn, h2, P2, NULL, NULL);
  snprintf(what, sizeof what, "%s: no plastic flow when re-evaluated with the new history", name);
  kt_close(what, h2[6] - hn[6], 0, 1e-12, 0);
  for (int r = 0; r < 9; r++) {
    snprintf(what, sizeof what, "%s: P with new history [%d]", name, r);
    kt_close(what, P2[r], P[r], 1e-10 * Pscale, 0);
    err_idem = fmax(err_idem, fabs(P2[r] - P[r]) / Pscale);
  }
  /* objectivity */
  double Q[9], QF[9], PQ[9], AQ[81], hq[8], QP[9];
  random_rotation(Q);
  mm(Q, F, QF);
  fem_mc_eval(p, QF, hist, hq, PQ, AQ, NULL);
  mm(Q, P, QP);
  for (int r = 0; r < 9; r++) {
    snprintf(what, sizeof what, "%s: P(QF) = Q P(F) [%d]", name, r);
    kt_close(what, PQ[r], QP[r], 1e-11 * Pmax, 0);
    err_obj = fmax(err_obj, fabs(PQ[r] - QP[r]) / Pmax);
  }
  for (int r = 0; r < 7; r++) {
    snprintf(what, sizeof what, "%s: history(QF) = history(F) [%d]", name, r);
    kt_close(what, hq[r], hn[r], 1e-11 * (1 + fabs(hn[r])), 0);
  }
  for (int i = 0; i < 3; i++)
    for (int J = 0; J < 3; J++)
      for (int k = 0; k < 3; k++)
        for (int L = 0; L < 3; L++) {
          double ref = 0;
          for (int m = 0; m < 3; m++)
            for (int n = 0; n < 3; n++)
              ref += Q[3 * i + m] * Q[3 * k + n] * A[9 * (3 * m + J) + 3 * n + L];
          snprintf(what, sizeof what, "%s: A(QF)[%d%d%d%d] = Q Q A(F)", name, i, J, k, L);
          kt_close(what, AQ[9 * (3 * i + J) + 3 * k + L], ref, 1e-10 * Amax, 0);
          err_obj = fmax(err_obj, fabs(AQ[9 * (3 * i + J) + 3 * k + L] - ref) / Amax);
        }
}

static double plane_x(const FemMohrCoulomb *p, double y)
{
  return (2 * p->c * cos(p->phi) + y * (1 - sin(p->phi))) / (1 + sin(p->phi));
}

static void check_material(const char *name, const FemMohrCoulomb *p)
{
  char what[160];
  Consts k = consts(p);
  for (int trial = 0; trial < 6; trial++) {
    double y = -kt_rand(20e3, 200e3), x = plane_x(p, y), sT[3], d1[3], d2[3], n1[3], n2[3];
    double ta = kt_rand(1e-3, 5e-3), tb = ta * kt_rand(0.1, 0.9);
    int rep = trial % 2; /* odd trials: exactly repeated trial eigenvalues */
    if (rep) tb = ta;
    double s_in[3] = {0.7 * x + 0.3 * y, rep ? 0.7 * x + 0.3 * y : 0.5 * (x + y), y};
    snprintf(what, sizeof what, "%s elastic%s %d", name, rep ? " (repeated)" : "", trial);
    check_state(what, p, s_in, FEM_MC_ELASTIC, 0);
    n_ij(k.sp, 0, 2, n1), Dv(&k, n1, d1);
    double w = kt_rand(0.2, 0.8);
    for (int a = 0; a < 3; a++) sT[a] = (double[3]){x, y + w * (x - y), y}[a] + ta * d1[a];
    snprintf(what, sizeof what, "%s plane %d", name, trial);
    check_state(what, p, sT, FEM_MC_PLANE, ta);
    n_ij(k.sp, 1, 2, n2), Dv(&k, n2, d2);
    for (int a = 0; a < 3; a++) sT[a] = (double[3]){x, x, y}[a] + ta * d1[a] + tb * d2[a];
    snprintf(what, sizeof what, "%s left edge%s %d", name, rep ? " (repeated)" : "", trial);
    check_state(what, p, sT, FEM_MC_EDGE_LEFT, ta + tb);
    n_ij(k.sp, 0, 1, n2), Dv(&k, n2, d2);
    for (int a = 0; a < 3; a++) sT[a] = (double[3]){x, y, y}[a] + ta * d1[a] + tb * d2[a];
    snprintf(what, sizeof what, "%s right edge%s %d", name, rep ? " (repeated)" : "", trial);
    check_state(what, p, sT, FEM_MC_EDGE_RIGHT, ta + tb);
    if (p->phi > 0) {
      double pa = p->c * k.cf / k.sf, ph = pa + kt_rand(5e3, 5e4);
      double sh[3] = {ph, ph, ph};
      if (!rep) sh[0] += 2e3, sh[2] -= 1e3;
      snprintf(what, sizeof what, "%s apex%s %d", name, rep ? " (hydrostatic)" : "", trial);
      check_state(what, p, sh, FEM_MC_APEX, 0);
    }
  }
}

int main(int argc, char **argv)
{
  int verbose = argc > 1 && !strcmp(argv[1], "-v");
  const double deg = M_PI / 180;
  FemMohrCoulomb mats[] = {{20e6, 0.3, 30 * deg, 10e3, 30 * deg, 0, 0},
                           {20e6, 0.3, 30 * deg, 10e3, 10 * deg, 0, 0},
                           {5e6, 0.2, 35 * deg, 0, 5 * deg, 0, 0},
                           {5e6, 0.2, 40 * deg, 0, 40 * deg, 0, 0},
                           {20e6, 0.45, 0, 10e3, 0, 0, 0}};
  const char *names[] = {"associated", "non-associated", "c = 0 non-associated", "c = 0 associated",
                         "Tresca"};
  for (int i = 0; i < 5; i++) check_material(names[i], &mats[i]);

  /* F = I, virgin: Hooke */
  char what[160];
  FemMohrCoulomb p = mats[1];
  Consts k = consts(&p);
  double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, P[9], A[81], hist[8], tau[9];
  fem_mc_eval(&p, I, NULL, NULL, P, A, NULL);
  for (int i = 0; i < 3; i++)
    for (int J = 0; J < 3; J++)
      for (int kk = 0; kk < 3; kk++)
        for (int L = 0; L < 3; L++) {
          double ref = k.lam * (i == J) * (kk == L) + k.G * ((i == kk) * (J == L) + (i == L) * (J == kk));
          snprintf(what, sizeof what, "A(I)[%d%d%d%d] vs Hooke", i, J, kk, L);
          kt_close(what, A[9 * (3 * i + J) + 3 * kk + L], ref, 1e-12 * p.young, 0);
        }
  /* initialisation hook: K0 state and a rotated general admissible state */
  double sv = -50e3, K0 = 1 - sin(p.phi), tau0[6] = {K0 * sv, K0 * sv, sv, 0, 0, 0};
  for (int rot = 0; rot < 2; rot++) {
    if (rot) {
      double R[9], Rt[9], S[9] = {-30e3, 0, 0, 0, -45e3, 0, 0, 0, -60e3}, T1[9], T[9];
      random_rotation(R), transpose(R, Rt), mm(R, S, T1), mm(T1, Rt, T);
      tau0[0] = T[0], tau0[1] = T[4], tau0[2] = T[8], tau0[3] = T[5], tau0[4] = T[2], tau0[5] = T[1];
    }
    if (fem_mc_hist_init(&p, tau0, hist)) {
      fprintf(stderr, "hist_init rejected an admissible stress: %s\n", sa_error_message());
      sa_error_clear();
      kt_fail++;
      continue;
    }
    double hn[8];
    fem_mc_eval(&p, I, hist, hn, P, NULL, tau);
    double ref[9] = {tau0[0], tau0[5], tau0[4], tau0[5], tau0[1], tau0[3], tau0[4], tau0[3], tau0[2]};
    for (int r = 0; r < 9; r++) {
      snprintf(what, sizeof what, "hist_init %d: tau(F = I) = tau0 [%d]", rot, r);
      kt_close(what, tau[r], ref[r], 1e-12 * fabs(sv), 0);
      err_init = fmax(err_init, fabs(tau[r] - ref[r]) / fabs(sv));
    }
    if ((int)hn[7] != FEM_MC_ELASTIC) {
      fprintf(stderr, "hist_init %d: initial state not elastic\n", rot);
      kt_fail++;
    }
  }
  double bad0[6] = {0, 0, -100e3, 0, 0, 0}; /* uniaxial 100 kPa > strength */
  if (fem_mc_hist_init(&p, bad0, hist) != SA_ERR_INPUT) {
    fprintf(stderr, "hist_init accepted an inadmissible stress\n");
    kt_fail++;
  }
  sa_error_clear();
  /* recoverable codes */
  double Finv[9] = {1, 0, 0, 0, -1, 0, 0, 0, 1}, Fnan[9] = {1, 0, 0, 0, NAN, 0, 0, 0, 1};
  int rc = fem_mc_eval(&p, Finv, NULL, NULL, P, A, NULL);
  if (rc != SA_ERR_INVERTED || rc <= 0) {
    fprintf(stderr, "det F < 0: code %d, expected SA_ERR_INVERTED\n", rc);
    kt_fail++;
  }
  rc = fem_mc_eval(&p, Fnan, NULL, NULL, P, A, NULL);
  if (rc != SA_ERR_DOMAIN || rc <= 0) {
    fprintf(stderr, "NaN in F: code %d, expected SA_ERR_DOMAIN\n", rc);
    kt_fail++;
  }
  sa_error_clear();
  if (verbose) {
    const char *rn[5] = {"elastic", "plane", "right edge", "left edge", "apex"};
    for (int r = 0; r < 5; r++) printf("%-10s  %3d states  A vs FD %.2e\n", rn[r], ncase[r], err_fd[r]);
    printf("associated major symmetry %.2e, objectivity %.2e, new-history re-evaluation %.2e, "
           "hist_init %.2e, apex_stiffness 1 against the elastic tangent %.2e\n", err_sym,
           err_obj, err_idem, err_init, err_apex);
  }
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
