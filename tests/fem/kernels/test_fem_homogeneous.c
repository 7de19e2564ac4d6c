/* test_fem_homogeneous.c - homogeneous uniaxial and equibiaxial stretch through the element
 * (one distorted straight-sided tet10 and one curved tet10, rotated frame x = R diag(lam) X;
 * an isoparametric element reproduces x = F X exactly, so the element's Cauchy stress must be
 * the analytic one to round-off).
 *
 * 1. Incompressible limit, derived by hand from W(I1, I2). With J = 1 and a pressure p,
 *      sigma = -p I + 2 W1 b - 2 W2 b^-1,
 *    so sigma_11 - sigma_33 = 2 W1 (l1^2 - l3^2) - 2 W2 (l1^-2 - l3^-2) (p cancels).
 *    Uniaxial, l1 = l, l2 = l3 = l^-1/2 (I1 = l^2 + 2/l, I2 = 2l + 1/l^2):
 *      sigma_11 - sigma_33 = 2 (l^2 - 1/l) (W1 + W2 / l).
 *    Equibiaxial, l1 = l2 = l, l3 = l^-2 (I1 = 2 l^2 + l^-4, I2 = l^4 + 2 l^-2):
 *      sigma_11 - sigma_33 = 2 (l^2 - l^-4) (W1 + l^2 W2).
 *    W1 = C10 + 2 C20 (I1 - 3) + 3 C30 (I1 - 3)^2, W2 = C01. The element is given exactly this
 *    isochoric deformation (J = 1, so U'(1) = 0 and the split law reduces to the above).
 * 2. Finite kappa (K/mu = 10 and 1000): with the split W_iso(I1b, I2b) + (K/2)(J - 1)^2 in
 *    principal form (Holzapfel, Nonlinear Solid Mechanics, 6.5):
 *      bb_i = J^-2/3 l_i^2, s_i = (W1 + I1b W2) bb_i - W2 bb_i^2,
 *      sigma_i = (2/J) (s_i - (s_1 + s_2 + s_3)/3) + K (J - 1),
 *    the lateral stretch is solved by bisection for zero lateral stress, and the element must give
 *    sigma_11 from the formula and zero lateral stress. Tolerances: the element evaluates the
 *    same quantities through P = dW/dF and averaging, so agreement is to round-off; rtol 1e-10 of
 *    the largest stress (K (J - 1) terms cancel to 1e-16 K).
 * Principal stretches must be (l1, l2, l3) sorted descending. */
#include <stdio.h>
#include <string.h>

#include "fem_element.h"
#include "kt_util.h"

typedef struct {
  double c10, c01, c20, c30;
} Coef;

static void derivs(const Coef *c, double I1, double *W1, double *W2)
{
  double e = I1 - 3;
  *W1 = c->c10 + 2 * c->c20 * e + 3 * c->c30 * e * e;
  *W2 = c->c01;
}

/* Principal Cauchy stresses of the split law. */
static void split_stress(const Coef *c, double K, const double l[3], double sig[3])
{
  double J = l[0] * l[1] * l[2], bb[3], s[3], I1b = 0, W1, W2;
  for (int i = 0; i < 3; i++) bb[i] = pow(J, -2.0 / 3.0) * l[i] * l[i], I1b += bb[i];
  derivs(c, I1b, &W1, &W2);
  for (int i = 0; i < 3; i++) s[i] = (W1 + I1b * W2) * bb[i] - W2 * bb[i] * bb[i];
  double m = (s[0] + s[1] + s[2]) / 3;
  for (int i = 0; i < 3; i++) sig[i] = 2 / J * (s[i] - m) + K * (J - 1);
}

/* Element Cauchy stress for x = R diag(l) X, rotated back to the principal frame. */
static void element_stress(const FemMaterial *m, const double *X, const double R[9],
                           const double l[3], double sig[9], double lam[3])
{
  double x[30], F[9], s[9];
  for (int i = 0; i < 3; i++)
    for (int J = 0; J < 3; J++) F[3 * i + J] = R[3 * i + J] * l[J];
  for (int a = 0; a < 10; a++)
    for (int i = 0; i < 3; i++)
      x[3 * a + i] = F[3 * i] * X[3 * a] + F[3 * i + 1] * X[3 * a + 1] + F[3 * i + 2] * X[3 * a + 2];
  if (fem_element_stress(FEM_TET10, X, x, m, NULL, s, lam)) {
    fprintf(stderr, "fem_element_stress failed\n");
    kt_fail++;
  }
  for (int i = 0; i < 3; i++) /* sig = R^T s R */
    for (int j = 0; j < 3; j++) {
      double v = 0;
      for (int k = 0; k < 3; k++)
        for (int n = 0; n < 3; n++) v += R[3 * k + i] * s[3 * k + n] * R[3 * n + j];
      sig[3 * i + j] = v;
    }
}

static void check_stretches(const char *what, const double lam[3], const double l[3])
{
  double s[3] = {l[0], l[1], l[2]};
  for (int i = 0; i < 2; i++)
    for (int j = i + 1; j < 3; j++)
      if (s[j] > s[i]) {
        double t = s[i];
        s[i] = s[j], s[j] = t;
      }
  for (int i = 0; i < 3; i++) kt_close(what, lam[i], s[i], 0, 1e-12);
}

static void run_law(const char *name, FemMaterial m, const Coef *c, const double *X, const double R[9])
{
  char what[200];
  double lams[] = {0.7, 1.3, 2.0};
  for (int mode = 0; mode < 2; mode++) /* 0 uniaxial, 1 equibiaxial */
    for (int il = 0; il < 3; il++) {
      double l = lams[il], W1, W2, sig[9], lam[3], ref, st[3];
      /* 1. incompressible */
      double lu[3] = {l, 1 / sqrt(l), 1 / sqrt(l)}, le[3] = {l, l, 1 / (l * l)};
      const double *ls = mode ? le : lu;
      double I1 = ls[0] * ls[0] + ls[1] * ls[1] + ls[2] * ls[2];
      derivs(c, I1, &W1, &W2);
      ref = mode ? 2 * (l * l - pow(l, -4)) * (W1 + l * l * W2) : 2 * (l * l - 1 / l) * (W1 + W2 / l);
      element_stress(&m, X, R, ls, sig, lam);
      snprintf(what, sizeof what, "%s %s l=%g incompressible: sigma11 - sigma33", name,
               mode ? "equibiaxial" : "uniaxial", l);
      kt_close(what, sig[0] - sig[8], ref, 1e-12 * fabs(ref), 1e-10);
      snprintf(what, sizeof what, "%s %s l=%g: principal stretches", name,
               mode ? "equibiaxial" : "uniaxial", l);
      check_stretches(what, lam, ls);
      /* 2. finite kappa: bisection on the free lateral stretch */
      for (int kk = 0; kk < 2; kk++) {
        double K = (kk ? 1000 : 10) * 2 * (c->c10 + c->c01);
        FemMaterial mk = m;
        mk.kappa = K;
        double lo = 0.1, hi = 5.0, lt = 1; /* lateral stretch lies in (0.1, 5) for l in 0.7..2 */
        for (int it = 0; it < 200; it++) {
          lt = 0.5 * (lo + hi);
          double lv[3] = {l, mode ? l : lt, lt};
          split_stress(c, K, lv, st);
          if (st[2] > 0) hi = lt; else lo = lt; /* lateral stress grows with lt */
        }
        double lv[3] = {l, mode ? l : lt, lt};
        split_stress(c, K, lv, st);
        element_stress(&mk, X, R, lv, sig, lam);
        double smax = fabs(st[0]) + 1e-300;
        snprintf(what, sizeof what, "%s %s l=%g K/mu=%s: sigma11", name,
                 mode ? "equibiaxial" : "uniaxial", l, kk ? "1000" : "10");
        kt_close(what, sig[0], st[0], 1e-10 * smax, 1e-10);
        snprintf(what, sizeof what, "%s %s l=%g K/mu=%s: lateral stress sigma33 = 0", name,
                 mode ? "equibiaxial" : "uniaxial", l, kk ? "1000" : "10");
        kt_close(what, sig[8], 0, 1e-9 * smax, 0);
        if (!mode) kt_close(what, sig[4], 0, 1e-9 * smax, 0);
        snprintf(what, sizeof what, "%s %s l=%g K/mu=%s: shear stresses", name,
                 mode ? "equibiaxial" : "uniaxial", l, kk ? "1000" : "10");
        kt_close(what, sig[1], 0, 1e-10 * smax, 0);
        kt_close(what, sig[2], 0, 1e-10 * smax, 0);
        kt_close(what, sig[5], 0, 1e-10 * smax, 0);
        check_stretches(what, lam, lv);
      }
    }
}

int main(void)
{
  double Xs[30], Xc[30], R[9], I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w[3] = {0.3, -0.5, 0.8};
  kt_random_tet(10, 0.2, 0, Xs);
  kt_random_tet(10, 0.2, 0.06, Xc);
  kt_rotation(w, R);
  Coef cn = {0.5, 0, 0, 0}, cm = {0.3, 0.2, 0, 0}, cy = {0.11, 0, 0.02, 0.001};
  FemMaterial nh = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 1};
  FemMaterial mr = {.kind = FEM_MAT_MOONEY_RIVLIN, .c10 = 0.3, .c01 = 0.2, .kappa = 1};
  FemMaterial ye = {.kind = FEM_MAT_YEOH, .c10 = 0.11, .c20 = 0.02, .c30 = 0.001, .kappa = 1};
  FemMaterial st = fem_material_from_e_nu(2.6, 0.3, 1); /* mu = 1 */
  Coef cs = {st.c10, 0, 0, 0};
  run_law("neo-Hooke straight", nh, &cn, Xs, I);
  run_law("neo-Hooke curved rotated", nh, &cn, Xc, R);
  run_law("Mooney-Rivlin straight rotated", mr, &cm, Xs, R);
  run_law("Mooney-Rivlin curved", mr, &cm, Xc, I);
  run_law("Yeoh straight rotated", ye, &cy, Xs, R);
  run_law("Yeoh curved rotated", ye, &cy, Xc, R);
  run_law("stiff straight", st, &cs, Xs, R);
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
