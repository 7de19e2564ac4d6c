/* test_fem_quadrature.c - the private quadrature rules and shape functions of the kernels.
 * Rules against the exact monomial integrals over the reference simplex,
 *   tet:      int L0^a L1^b L2^c L3^d dV = a! b! c! d! / (a+b+c+d+3)!    (3! V, V = 1/6)
 *   triangle: int L0^a L1^b L2^c dA      = a! b! c! / (a+b+c+2)!         (2! A, A = 1/2),
 * up to each rule's stated degree (round-off tolerance 1e-15), and failing one degree higher
 * (so the stated degree is the true one). Shape functions: partition of unity, N_a(node b) =
 * delta_ab, derivatives vs central FD (h = 1e-6, quadratic N: error ~1e-10). */
#include <stdio.h>

#include "fem_kernel_quad.h"
#include "kt_util.h"

static double fact(int n) { return n <= 1 ? 1 : n * fact(n - 1); }

/* Largest error over all monomials of total degree `deg` exactly. */
static double rule_error(const FemKqRule *R, int nbary, int deg)
{
  double err = 0;
  int e[4] = {0, 0, 0, 0};
  for (e[0] = 0; e[0] <= deg; e[0]++)
    for (e[1] = 0; e[1] <= deg - e[0]; e[1]++)
      for (e[2] = 0; e[2] <= deg - e[0] - e[1]; e[2]++) {
        int rest = deg - e[0] - e[1] - e[2];
        if (nbary == 3) {
          if (rest != 0) continue; /* triangle: e[2] takes the remainder */
          e[3] = 0;
        } else {
          e[3] = rest;
        }
        double q = 0, ex = 1;
        for (int p = 0; p < R->n; p++) {
          double v = R->w[p];
          for (int i = 0; i < nbary; i++) v *= pow(R->L[p][i], e[i]);
          q += v;
        }
        for (int i = 0; i < nbary; i++) ex *= fact(e[i]);
        ex /= fact(deg + nbary - 1);
        if (fabs(q - ex) > err) err = fabs(q - ex);
      }
  return err;
}

static void check_rule(const char *name, const FemKqRule *R, int nbary, int degree)
{
  char what[120];
  for (int d = 0; d <= degree; d++) {
    snprintf(what, sizeof what, "%s: monomials of degree %d", name, d);
    kt_close(what, rule_error(R, nbary, d), 0, 1e-15, 0);
  }
  if (rule_error(R, nbary, degree + 1) < 1e-12) {
    fprintf(stderr, "%s: exact for degree %d too (stated %d)\n", name, degree + 1, degree);
    kt_fail++;
  }
  for (int p = 0; p < R->n; p++) {
    double s = 0;
    for (int i = 0; i < nbary; i++) s += R->L[p][i];
    snprintf(what, sizeof what, "%s: barycentric sum of point %d", name, p);
    kt_close(what, s, 1, 1e-15, 0);
    if (R->w[p] <= 0) {
      fprintf(stderr, "%s: weight %d not positive\n", name, p);
      kt_fail++;
    }
  }
}

static void check_tet_shape(int nen)
{
  static const double node[10][4] = {{1, 0, 0, 0},       {0, 1, 0, 0},    {0, 0, 1, 0},
                                     {0, 0, 0, 1},       {.5, .5, 0, 0},  {0, .5, .5, 0},
                                     {.5, 0, .5, 0},     {.5, 0, 0, .5},  {0, .5, 0, .5},
                                     {0, 0, .5, .5}};
  char what[120];
  double N[10], dN[10][3];
  for (int b = 0; b < nen; b++) {
    fem_kq_tet_shape(nen, node[b], N, NULL);
    for (int a = 0; a < nen; a++) {
      snprintf(what, sizeof what, "tet%d: N_%d at node %d", nen, a, b);
      kt_close(what, N[a], a == b, 1e-15, 0);
    }
  }
  for (int t = 0; t < 5; t++) {
    double r = kt_rand(0, .4), s = kt_rand(0, .3), u = kt_rand(0, .3), h = 1e-6, sum = 0;
    double L[4] = {1 - r - s - u, r, s, u};
    fem_kq_tet_shape(nen, L, N, dN);
    for (int a = 0; a < nen; a++) sum += N[a];
    snprintf(what, sizeof what, "tet%d: partition of unity", nen);
    kt_close(what, sum, 1, 1e-14, 0);
    for (int k = 0; k < 3; k++) {
      double Lp[4] = {L[0] - h, L[1], L[2], L[3]}, Lm[4] = {L[0] + h, L[1], L[2], L[3]};
      Lp[k + 1] += h, Lm[k + 1] -= h;
      double Np[10], Nm[10];
      fem_kq_tet_shape(nen, Lp, Np, NULL);
      fem_kq_tet_shape(nen, Lm, Nm, NULL);
      for (int a = 0; a < nen; a++) {
        snprintf(what, sizeof what, "tet%d: dN_%d/dxi_%d vs FD", nen, a, k);
        kt_close(what, dN[a][k], (Np[a] - Nm[a]) / (2 * h), 1e-8, 0);
      }
    }
  }
}

static void check_tri_shape(int nfn)
{
  static const double node[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {.5, .5, 0}, {0, .5, .5}, {.5, 0, .5}};
  char what[120];
  double N[6], dN[6][2];
  for (int b = 0; b < nfn; b++) {
    fem_kq_tri_shape(nfn, node[b], N, NULL);
    for (int a = 0; a < nfn; a++) {
      snprintf(what, sizeof what, "tri%d: N_%d at node %d", nfn, a, b);
      kt_close(what, N[a], a == b, 1e-15, 0);
    }
  }
  double r = 0.23, s = 0.41, h = 1e-6, L[3] = {1 - r - s, r, s};
  fem_kq_tri_shape(nfn, L, N, dN);
  for (int k = 0; k < 2; k++) {
    double Lp[3] = {L[0] - h, L[1], L[2]}, Lm[3] = {L[0] + h, L[1], L[2]}, Np[6], Nm[6];
    Lp[k + 1] += h, Lm[k + 1] -= h;
    fem_kq_tri_shape(nfn, Lp, Np, NULL);
    fem_kq_tri_shape(nfn, Lm, Nm, NULL);
    for (int a = 0; a < nfn; a++) {
      snprintf(what, sizeof what, "tri%d: dN_%d/dxi_%d vs FD", nfn, a, k);
      kt_close(what, dN[a][k], (Np[a] - Nm[a]) / (2 * h), 1e-8, 0);
    }
  }
}

int main(void)
{
  check_rule("tet 1-point", &fem_kq_tet1, 4, 1);
  check_rule("tet 4-point", &fem_kq_tet4, 4, 2);
  check_rule("tet 8-point", &fem_kq_tet8, 4, 3);
  check_rule("tet 14-point", &fem_kq_tet14, 4, 5);
  check_rule("tri 3-point", &fem_kq_tri3, 3, 2);
  check_rule("tri 6-point", &fem_kq_tri6, 3, 4);
  check_tet_shape(4);
  check_tet_shape(10);
  check_tri_shape(3);
  check_tri_shape(6);
  double X[30];
  kt_random_tet(10, 0.2, 0, X);
  if (fem_kq_tet10_curved(X)) {
    fprintf(stderr, "straight tet10 classified as curved\n");
    kt_fail++;
  }
  X[3 * 7 + 1] += 1e-3;
  if (!fem_kq_tet10_curved(X)) {
    fprintf(stderr, "curved tet10 classified as straight\n");
    kt_fail++;
  }
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
