/* fem_material.c - isochoric/volumetric hyperelastic laws (see fem_material.h).
 *
 * Isochoric invariants of F (J = det F, H = F^-T, C = F^T F, b = F F^T):
 *   I1b = J^-2/3 I1,  I1 = F:F,                     dI1/dF = 2F
 *   I2b = J^-4/3 I2,  I2 = (I1^2 - C:C)/2,          dI2/dF = 2 (I1 F - F C)
 * With dJ/dF = J H and dH_iJ/dF_kL = -H_iL H_kJ, for g = J^-a f:
 *   dg/dF        = J^-a (df - a f H)
 *   d2g/dF dF    = J^-a [d2f - a (df (x) H + H (x) df) + a^2 f H (x) H + a f H (.) H]
 * where (H (.) H)_iJkL = H_iL H_kJ, and
 *   d2I1_iJkL = 2 d_ik d_JL
 *   d2I2_iJkL = 2 [2 F_iJ F_kL + I1 d_ik d_JL - d_ik C_JL - F_iL F_kJ - b_ik d_JL].
 * P = W1 D1 + W2 D2 (Dn = dInb/dF), A = sum Wmn Dm (x) Dn + W1 d2I1b + W2 d2I2b.
 * The element adds U(J) through the mean dilatation; U(J) = (kappa/2)(J - 1)^2. */
#include "fem_material.h"

#include <math.h>
#include <stddef.h>

#include "fem_kernel_tensor.h"
#include "fem_law.h"
#include "sa_error.h"

double fem_material_mu0(const FemMaterial *m)
{
  if (m->law) return m->law->mu0 ? m->law->mu0(m->par) : 0.0;
  return 2 * (m->c10 + (m->kind == FEM_MAT_MOONEY_RIVLIN ? m->c01 : 0));
}

double fem_material_kappa_fluct(const FemMaterial *m)
{
  if (m->law && m->law->kind == FEM_LAW_FULL) return 0.0; /* displacement formulation */
  double a = m->mix_alpha == 0 ? FEM_MAT_MIX_ALPHA_DEFAULT : m->mix_alpha;
  if (a < 0) return 0;
  double k = a * fem_material_mu0(m);
  return k < m->kappa ? k : m->kappa;
}

FemMaterial fem_material_from_e_nu(double E, double nu, double rho)
{
  FemMaterial m = {0};
  m.kind = FEM_MAT_STIFF_NEOHOOKE;
  m.c10 = E / (4 * (1 + nu)); /* mu / 2 */
  m.kappa = E / (3 * (1 - 2 * nu));
  m.rho = rho;
  return m;
}

static int check_law(const FemMaterial *m)
{
  const FemLaw *L = m->law;
  SA_REQUIRE(m->nhist == L->nhist, SA_ERR_INPUT, "material of law '%s': nhist %d, the law has %d",
             L->name, m->nhist, L->nhist);
  SA_REQUIRE(m->rho >= 0, SA_ERR_INPUT, "material: rho = %g must be >= 0", m->rho);
  if (L->kind == FEM_LAW_ISOCHORIC) {
    SA_REQUIRE(m->kappa > 0, SA_ERR_INPUT, "law '%s': kappa = %g must be > 0", L->name, m->kappa);
    SA_REQUIRE(fem_material_mu0(m) > 0, SA_ERR_INPUT, "law '%s': initial shear modulus %g must "
               "be > 0", L->name, fem_material_mu0(m));
  }
  if (L->check) SA_CHECK(L->check(m->par));
  return 0;
}

int fem_material_check(const FemMaterial *m)
{
  if (m->law) return check_law(m);
  SA_REQUIRE(m->kind >= FEM_MAT_NEOHOOKE && m->kind <= FEM_MAT_STIFF_NEOHOOKE, SA_ERR_INPUT,
             "unknown material kind %d", (int)m->kind);
  SA_REQUIRE(m->c10 > 0, SA_ERR_INPUT, "material: c10 = %g must be > 0", m->c10);
  if (m->kind == FEM_MAT_MOONEY_RIVLIN)
    SA_REQUIRE(m->c01 >= 0, SA_ERR_INPUT, "material: c01 = %g must be >= 0", m->c01);
  SA_REQUIRE(m->kappa > 0, SA_ERR_INPUT, "material: kappa = %g must be > 0", m->kappa);
  SA_REQUIRE(m->rho >= 0, SA_ERR_INPUT, "material: rho = %g must be >= 0", m->rho);
  SA_REQUIRE(m->nhist >= 0 && m->nhist <= FEM_MAT_MAX_HIST, SA_ERR_INPUT,
             "material: nhist = %d outside 0..%d", m->nhist, FEM_MAT_MAX_HIST);
  return 0;
}

int fem_material_symmetric(const FemMaterial *m)
{
  if (!m->law) return 1; /* every built-in law is hyperelastic */
  return m->law->symmetric_par ? m->law->symmetric_par(m->par) : m->law->symmetric;
}

void fem_material_eval_vol(const FemMaterial *m, double J, double *U, double *dU, double *d2U)
{
  /* a full-stress law carries its own pressure */
  double k = (m->law && m->law->kind == FEM_LAW_FULL) ? 0.0 : m->kappa;
  if (U) *U = 0.5 * k * (J - 1) * (J - 1);
  if (dU) *dU = k * (J - 1);
  if (d2U) *d2U = k;
}

int fem_material_eval_iso(const FemMaterial *m, const double F[9], const double *hist_old,
                          double *hist_new, double *W, double P[9], double A[81])
{
  (void)hist_old;
  (void)hist_new;
  double Hc[9];
  double J = fem_kt_cof(F, Hc); /* cof F = J F^-T */
  if (!(J > 0)) return SA_ERROR(SA_ERR_INVERTED, "det F = %g <= 0", J);
  double H[9], iJ = 1 / J;
  for (int i = 0; i < 9; i++) H[i] = Hc[i] * iJ;
  double I1 = 0;
  for (int i = 0; i < 9; i++) I1 += F[i] * F[i];
  double Jm13 = 1 / cbrt(J), Jm23 = Jm13 * Jm13;
  double I1b = Jm23 * I1, e1 = I1b - 3;

  /* W(I1b, I2b) and its derivatives. */
  double c10 = m->c10, c01 = 0, c20 = 0, c30 = 0;
  if (m->kind == FEM_MAT_MOONEY_RIVLIN) c01 = m->c01;
  if (m->kind == FEM_MAT_YEOH) c20 = m->c20, c30 = m->c30;
  double W1 = c10 + e1 * (2 * c20 + 3 * c30 * e1), W11 = 2 * c20 + 6 * c30 * e1;
  double Wv = e1 * (c10 + e1 * (c20 + c30 * e1));

  double D1[9];
  for (int i = 0; i < 9; i++) D1[i] = Jm23 * (2 * F[i] - (2.0 / 3.0) * I1 * H[i]);

  if (c01 == 0) { /* I1-only laws: neo-Hookean, Yeoh, stiff */
    *W = Wv;
    for (int i = 0; i < 9; i++) P[i] = W1 * D1[i];
    if (!A) return 0;
    /* A = W11 D1 D1 + W1 Jm23 [2 I - 4/3 (F H + H F) + 4/9 I1 H H + 2/3 I1 H(.)H] */
    double s = W1 * Jm23, f1 = -4.0 / 3.0 * s, f2 = 4.0 / 9.0 * I1 * s, f3 = 2.0 / 3.0 * I1 * s;
    for (int i = 0; i < 3; i++)
      for (int Jj = 0; Jj < 3; Jj++) {
        int r = 3 * i + Jj;
        double d1r = W11 * D1[r], Fr = f1 * F[r], Hr = H[r], Hr2 = f2 * H[r];
        double *Ar = A + 9 * r;
        for (int k = 0; k < 3; k++)
          for (int L = 0; L < 3; L++) {
            int c = 3 * k + L;
            Ar[c] = d1r * D1[c] + Fr * H[c] + f1 * Hr * F[c] + Hr2 * H[c] +
                    f3 * H[3 * i + L] * H[3 * k + Jj];
          }
        Ar[r] += 2 * s;
      }
    return 0;
  }

  /* Mooney-Rivlin: add the I2 part (W2 = c01, W22 = W12 = 0). */
  double C[9], b[9], FC[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double sc = 0, sb = 0;
      for (int k = 0; k < 3; k++) {
        sc += F[3 * k + i] * F[3 * k + j];
        sb += F[3 * i + k] * F[3 * j + k];
      }
      C[3 * i + j] = sc, b[3 * i + j] = sb;
    }
  double CC = 0;
  for (int i = 0; i < 9; i++) CC += C[i] * C[i];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0;
      for (int k = 0; k < 3; k++) s += F[3 * i + k] * C[3 * k + j];
      FC[3 * i + j] = s;
    }
  double I2 = 0.5 * (I1 * I1 - CC), Jm43 = Jm23 * Jm23, I2b = Jm43 * I2;
  double W2 = c01;
  double dI2[9], D2[9];
  for (int i = 0; i < 9; i++) {
    dI2[i] = 2 * (I1 * F[i] - FC[i]);
    D2[i] = Jm43 * (dI2[i] - (4.0 / 3.0) * I2 * H[i]);
  }
  *W = Wv + c01 * (I2b - 3);
  for (int i = 0; i < 9; i++) P[i] = W1 * D1[i] + W2 * D2[i];
  if (!A) return 0;
  double s1 = W1 * Jm23, s2 = W2 * Jm43;
  for (int i = 0; i < 3; i++)
    for (int Jj = 0; Jj < 3; Jj++) {
      int r = 3 * i + Jj;
      double *Ar = A + 9 * r;
      for (int k = 0; k < 3; k++)
        for (int L = 0; L < 3; L++) {
          int c = 3 * k + L;
          double HH = H[r] * H[c], HdH = H[3 * i + L] * H[3 * k + Jj];
          double d2i1 = (i == k && Jj == L) ? 2 : 0;
          double a1 = d2i1 - (4.0 / 3.0) * (F[r] * H[c] + H[r] * F[c]) + (4.0 / 9.0) * I1 * HH +
                      (2.0 / 3.0) * I1 * HdH;
          double d2i2 = 4 * F[r] * F[c] - 2 * F[3 * i + L] * F[3 * k + Jj];
          if (i == k) d2i2 -= 2 * C[3 * Jj + L];
          if (Jj == L) d2i2 += 2 * (-b[3 * i + k] + (i == k ? I1 : 0));
          double a2 = d2i2 - (4.0 / 3.0) * (dI2[r] * H[c] + H[r] * dI2[c]) +
                      (16.0 / 9.0) * I2 * HH + (4.0 / 3.0) * I2 * HdH;
          Ar[c] = W11 * D1[r] * D1[c] + s1 * a1 + s2 * a2;
        }
    }
  return 0;
}
