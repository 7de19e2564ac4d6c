/* test_mohr_coulomb_triaxial.c - drained triaxial compression at one material point
 * (fem_mc_eval), mixed control: F = diag(lx, lx, lz), the axial log strain -ln(lz) raised in
 * 120 steps to three times the strain at failure, the lateral stretch lx found by Newton (with the
 * kernel's consistent tangent) so that the lateral stress stays at the confining pressure sc; the
 * point starts from the isotropic state -sc (fem_mc_hist_init).
 * Compression positive in this comment: closed form at failure (Mohr-Coulomb, perfect plasticity)
 *   s1 = s3 N + 2 c sqrt(N),  N = (1 + sin phi) / (1 - sin phi),  q = s1 - s3 = s3 (N - 1) + 2 c sqrt(N).
 * The yield surface is on Kirchhoff stress, so with the lateral Kirchhoff stress held at sc the
 * peak Kirchhoff q must match to 1e-6 relative (the return lands exactly on the edge; what is
 * left is the lateral Newton tolerance, 1e-12 + round-off). With the lateral Cauchy stress held instead, the
 * closed form holds with c / J in place of c: checked to 1 % (issue 13) and the error reported.
 * Dilatancy on the compression edge: d eps_v^p / d eps_axial^p = -2 sin(psi) / (1 - sin(psi))
 * (tension positive; i.e. -d eps_v / d eps_1 = 2 sin psi / (1 - sin psi) with compression
 * positive), from the plastic log strains -ln(C_p^-1)_ii / 2 over the last 20 steps; tol 1e-9.
 * Cases: phi = 0 (Tresca, c > 0), 10, 28, 40 deg; c = 0, 100 Pa, 10 kPa; sc = 1, 10, 100 kPa;
 * psi = phi, phi/2, 0. Pass -v to print the largest errors. */
#include <stdio.h>
#include <string.h>

#include "fem_mohr_coulomb.h"
#include "kt_util.h"
#include "sa_error.h"

static double err_q, err_qc, err_dil, jmin = 1, jmax = 1;
static long newton_its, newton_solves;

/* Runs one test; cauchy = 1 holds the lateral Cauchy stress, else the Kirchhoff one. */
static void triaxial(const FemMohrCoulomb *p, double sc, int cauchy)
{
  char what[200];
  double sf = sin(p->phi), N = (1 + sf) / (1 - sf);
  double q_cf = sc * (N - 1) + 2 * p->c * sqrt(N);
  double hist[8], hn[8], P[9], A[81], tau[9], tau0[6] = {-sc, -sc, -sc, 0, 0, 0};
  snprintf(what, sizeof what, "phi %.0f deg, psi %.1f deg, c %g Pa, sc %g Pa, %s control",
           p->phi * 180 / M_PI, p->psi * 180 / M_PI, p->c, sc, cauchy ? "Cauchy" : "Kirchhoff");
  if (fem_mc_hist_init(p, tau0, hist)) {
    fprintf(stderr, "%s: hist_init failed: %s\n", what, sa_error_message());
    sa_error_clear();
    kt_fail++;
    return;
  }
  double ea_max = 3 * q_cf / p->young + 1e-3, lx = 1, q_peak = -INFINITY, ep_hist[121][3];
  int nstep = 120, region = 0;
  for (int step = 1; step <= nstep; step++) {
    double lz = exp(-ea_max * step / nstep), g = 0, J = 0;
    int it, ok = 0;
    for (it = 0; it < 30; it++) {
      double F[9] = {lx, 0, 0, 0, lx, 0, 0, 0, lz};
      if (fem_mc_eval(p, F, hist, hn, P, A, tau)) {
        fprintf(stderr, "%s: eval failed at step %d: %s\n", what, step, sa_error_message());
        sa_error_clear();
        kt_fail++;
        return;
      }
      J = lx * lx * lz;
      double dtau = lx * (A[0] + A[4]) + P[0]; /* d tau_xx / d lx, tau_xx = P_xx lx */
      double dg = cauchy ? dtau / J - 2 * tau[0] / (lx * J) : dtau;
      g = (cauchy ? tau[0] / J : tau[0]) + sc;
      if (fabs(g) <= 1e-12 * (sc + q_cf) + 1e-14 * p->young) { /* round-off of tau ~1e-16 E */
        ok = 1;
        break;
      }
      lx -= g / dg;
    }
    newton_its += it, newton_solves++;
    if (!ok) {
      fprintf(stderr, "%s: lateral Newton did not converge at step %d (g = %g)\n", what, step, g);
      kt_fail++;
      return;
    }
    memcpy(hist, hn, sizeof hist);
    region = (int)hn[7];
    double q = (tau[0] - tau[8]) / (cauchy ? J : 1);
    if (q > q_peak) q_peak = q;
    for (int a = 0; a < 3; a++) ep_hist[step][a] = -0.5 * log(hist[a]);
    jmin = fmin(jmin, J), jmax = fmax(jmax, J);
  }
  if (region != FEM_MC_EDGE_LEFT) {
    fprintf(stderr, "%s: final region %d, expected the compression edge\n", what, region);
    kt_fail++;
  }
  double e = fabs(q_peak - q_cf) / q_cf;
  if (!cauchy) {
    snprintf(what + strlen(what), sizeof what - strlen(what), ": peak q");
    kt_close(what, q_peak, q_cf, 0, 1e-6);
    err_q = fmax(err_q, e);
    double dv = 0, dz = ep_hist[nstep][2] - ep_hist[nstep - 20][2], sp = sin(p->psi);
    for (int a = 0; a < 3; a++) dv += ep_hist[nstep][a] - ep_hist[nstep - 20][a];
    char w2[240];
    snprintf(w2, sizeof w2, "%s: dilatancy d eps_v^p / d eps_z^p", what);
    kt_close(w2, dv / dz, -2 * sp / (1 - sp), 1e-9, 0);
    err_dil = fmax(err_dil, fabs(dv / dz + 2 * sp / (1 - sp)));
  } else {
    snprintf(what + strlen(what), sizeof what - strlen(what), ": peak Cauchy q (1 %%)");
    kt_close(what, q_peak, q_cf, 0, 1e-2);
    err_qc = fmax(err_qc, e);
  }
}

int main(int argc, char **argv)
{
  int verbose = argc > 1 && !strcmp(argv[1], "-v");
  const double deg = M_PI / 180;
  double phis[] = {0, 10, 28, 40}, cs[] = {0, 100, 10e3}, scs[] = {1e3, 10e3, 100e3};
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 3; j++)
      for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++) {
          FemMohrCoulomb p = {50e6, 0.3, phis[i] * deg, cs[j], phis[i] * deg * (2 - l) / 2,
                              0, 0};
          if (phis[i] == 0 && (cs[j] == 0 || l > 0)) continue;
          if (fem_mc_check(&p)) {
            fprintf(stderr, "rejected valid parameters: %s\n", sa_error_message());
            sa_error_clear();
            kt_fail++;
            continue;
          }
          triaxial(&p, scs[k], 0);
          triaxial(&p, scs[k], 1);
        }
  if (verbose)
    printf("peak q (Kirchhoff) max rel err %.2e; dilatancy ratio max abs err %.2e; peak q (Cauchy)"
           " max rel err %.2e with J in [%.4f, %.4f]; lateral Newton %.2f iterations/step\n",
           err_q, err_dil, err_qc, jmin, jmax, (double)newton_its / newton_solves);
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
