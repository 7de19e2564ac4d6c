/* test_fem_material_fd.c - material laws against independent references:
 *  - P = dW/dF and A = dP/dF by central finite differences at random F (det F in 0.8..1.3);
 *    central differences with h = 1e-5 have truncation error ~h^2 |W'''| ~ 1e-10 and round-off
 *    ~eps |W| / h ~ 1e-11 relative, so rtol 1e-7 of the largest entry is a safe bound;
 *  - isochoric invariance W(aF) = W(F) and tr(P F^T) = 0 (no volumetric stress in W_iso);
 *  - symmetry A_iJkL = A_kLiJ (hyperelastic);
 *  - small-strain limit at F = I: A = mu0 (d_ik d_JL + d_iL d_Jk) - (2/3) mu0 d_iJ d_kL with
 *    mu0 = 2 (C10 + C01), the linearised deviatoric Hooke law;
 *  - U' and U'' by finite differences; stiff law from E, nu: mu = E/(2(1+nu)), K = E/(3(1-2nu)). */
#include <stdio.h>
#include <string.h>

#include "fem_material.h"
#include "sa_error.h"
#include "kt_util.h"

static void check_law(const char *name, const FemMaterial *m)
{
  char what[160];
  for (int trial = 0; trial < 20; trial++) {
    double F[9], W, P[9], A[81];
    kt_random_F(0.3, kt_rand(0.8, 1.3), F);
    if (fem_material_eval_iso(m, F, NULL, NULL, &W, P, A)) {
      fprintf(stderr, "%s: eval failed\n", name);
      kt_fail++;
      return;
    }
    double Pmax = kt_maxabs(P, 9), Amax = kt_maxabs(A, 81), h = 1e-5;
    for (int c = 0; c < 9; c++) {
      double Fp[9], Fm[9], Wp, Wm, Pp[9], Pm[9];
      memcpy(Fp, F, sizeof Fp);
      memcpy(Fm, F, sizeof Fm);
      Fp[c] += h, Fm[c] -= h;
      fem_material_eval_iso(m, Fp, NULL, NULL, &Wp, Pp, NULL);
      fem_material_eval_iso(m, Fm, NULL, NULL, &Wm, Pm, NULL);
      snprintf(what, sizeof what, "%s trial %d: P[%d] vs FD of W", name, trial, c);
      kt_close(what, P[c], (Wp - Wm) / (2 * h), 1e-7 * Pmax, 0);
      for (int r = 0; r < 9; r++) {
        snprintf(what, sizeof what, "%s trial %d: A[%d][%d] vs FD of P", name, trial, r, c);
        kt_close(what, A[9 * r + c], (Pp[r] - Pm[r]) / (2 * h), 1e-7 * Amax, 0);
        snprintf(what, sizeof what, "%s trial %d: A symmetry [%d][%d]", name, trial, r, c);
        kt_close(what, A[9 * r + c], A[9 * c + r], 1e-12 * Amax, 0);
      }
    }
    double aF[9], Wa, Pa[9], tr = 0;
    for (int i = 0; i < 9; i++) aF[i] = 1.37 * F[i];
    fem_material_eval_iso(m, aF, NULL, NULL, &Wa, Pa, NULL);
    snprintf(what, sizeof what, "%s: W(1.37 F) = W(F)", name);
    kt_close(what, Wa, W, 1e-13 * fabs(W) + 1e-300, 1e-12);
    for (int i = 0; i < 9; i++) tr += P[i] * F[i];
    snprintf(what, sizeof what, "%s: tr(P F^T)", name);
    kt_close(what, tr, 0, 1e-12 * Pmax, 0);
  }
  /* Small-strain limit. */
  double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, W, P[9], A[81], mu = fem_material_mu0(m);
  fem_material_eval_iso(m, I, NULL, NULL, &W, P, A);
  snprintf(what, sizeof what, "%s: W(I)", name);
  kt_close(what, W, 0, 1e-14 * mu, 0);
  for (int i = 0; i < 3; i++)
    for (int J = 0; J < 3; J++) {
      snprintf(what, sizeof what, "%s: P(I)[%d%d]", name, i, J);
      kt_close(what, P[3 * i + J], 0, 1e-14 * mu, 0);
      for (int k = 0; k < 3; k++)
        for (int L = 0; L < 3; L++) {
          double ref = mu * ((i == k) * (J == L) + (i == L) * (J == k)) -
                       2.0 / 3.0 * mu * (i == J) * (k == L);
          snprintf(what, sizeof what, "%s: A(I)[%d%d%d%d] vs linear elasticity", name, i, J, k, L);
          kt_close(what, A[9 * (3 * i + J) + 3 * k + L], ref, 1e-13 * mu, 0);
        }
    }
  /* Volumetric part. */
  double J = kt_rand(0.8, 1.3), U, dU, d2U, Up, Um, dUp, dUm, h = 1e-6;
  fem_material_eval_vol(m, J, &U, &dU, &d2U);
  fem_material_eval_vol(m, J + h, &Up, &dUp, NULL);
  fem_material_eval_vol(m, J - h, &Um, &dUm, NULL);
  snprintf(what, sizeof what, "%s: U' vs FD", name);
  kt_close(what, dU, (Up - Um) / (2 * h), 1e-7 * m->kappa, 0);
  snprintf(what, sizeof what, "%s: U'' vs FD", name);
  kt_close(what, d2U, (dUp - dUm) / (2 * h), 1e-7 * m->kappa, 0);
  fem_material_eval_vol(m, 1, &U, &dU, &d2U);
  snprintf(what, sizeof what, "%s: U(1), U'(1), U''(1) = 0, 0, kappa", name);
  kt_close(what, U, 0, 0, 0);
  kt_close(what, dU, 0, 0, 0);
  kt_close(what, d2U, m->kappa, 0, 1e-15);
  if (fem_material_check(m)) {
    fprintf(stderr, "%s: fem_material_check rejected valid parameters\n", name);
    kt_fail++;
  }
}

int main(void)
{
  FemMaterial nh = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 1000};
  FemMaterial mr = {.kind = FEM_MAT_MOONEY_RIVLIN, .c10 = 0.3, .c01 = 0.2, .kappa = 500};
  FemMaterial ye = {.kind = FEM_MAT_YEOH, .c10 = 0.11, .c20 = 0.02, .c30 = -0.003, .kappa = 100};
  check_law("neo-Hooke", &nh);
  check_law("Mooney-Rivlin", &mr);
  check_law("Yeoh", &ye);
  double E = 1000, nu = 0.3;
  FemMaterial st = fem_material_from_e_nu(E, nu, 1000);
  check_law("stiff", &st);
  kt_close("stiff mu0", fem_material_mu0(&st), E / (2 * (1 + nu)), 0, 1e-15);
  kt_close("stiff kappa", st.kappa, E / (3 * (1 - 2 * nu)), 0, 1e-15);
  FemMaterial bad = nh;
  bad.kappa = -1;
  if (fem_material_check(&bad) != SA_ERR_INPUT) {
    fprintf(stderr, "fem_material_check accepted kappa < 0\n");
    kt_fail++;
  }
  double Fi[9] = {1, 0, 0, 0, -1, 0, 0, 0, 1}, W, P[9];
  if (fem_material_eval_iso(&nh, Fi, NULL, NULL, &W, P, NULL) != SA_ERR_INVERTED) {
    fprintf(stderr, "det F < 0 not reported as SA_ERR_INVERTED\n");
    kt_fail++;
  }
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
