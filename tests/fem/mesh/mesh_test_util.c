/* mesh_test_util.c - see mesh_test_util.h. The tri6 rule is the 6-point degree-4 rule of
 * Dunavant (1985) on the reference triangle of area 1/2: x.(x_r x x_s) is degree 4 on a tri6, so
 * the flux is integrated exactly. */
#include "mesh_test_util.h"

#include <math.h>
#include <stdio.h>

int mt_close(const char *label, double a, double b, double atol, double rtol)
{
  if (fabs(a - b) <= atol + rtol * fabs(b)) return 1;
  fprintf(stderr, "%s: got %.12g, expected %.12g (diff %.3g, atol %.3g, rtol %.3g)\n", label, a, b,
          a - b, atol, rtol);
  return 0;
}

const char *mt_geo(const char *name, char *buf, int n)
{
  snprintf(buf, (size_t)n, "%s/%s", SOFTACT_MESH_DIR, name);
  return buf;
}

static const double d4_a[2] = {0.445948490915965, 0.091576213509771};
static const double d4_w[2] = {0.223381589678011, 0.109951743655322};

/* Points (L0, L1, L2) and weights (sum 1/2). */
static int tri_rule(int nfn, double L[6][3], double w[6])
{
  if (nfn == 3) {
    L[0][0] = L[0][1] = L[0][2] = 1.0 / 3.0;
    w[0] = 0.5;
    return 1;
  }
  int n = 0;
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 3; ++i, ++n) {
      for (int j = 0; j < 3; ++j) L[n][j] = (i == j) ? 1.0 - 2.0 * d4_a[k] : d4_a[k];
      w[n] = 0.5 * d4_w[k];
    }
  return n;
}

/* x, x_r, x_s of face f at L (r = L1, s = L2). */
static void tri_eval(int nfn, const double *X, const double L[3], double x[3], double xr[3],
                     double xs[3])
{
  double N[6], Nr[6], Ns[6];
  if (nfn == 3) {
    N[0] = L[0], N[1] = L[1], N[2] = L[2];
    Nr[0] = -1, Nr[1] = 1, Nr[2] = 0;
    Ns[0] = -1, Ns[1] = 0, Ns[2] = 1;
  } else {
    const double dL[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
    for (int a = 0; a < 3; ++a) {
      N[a] = L[a] * (2 * L[a] - 1);
      Nr[a] = (4 * L[a] - 1) * dL[a][0];
      Ns[a] = (4 * L[a] - 1) * dL[a][1];
    }
    for (int a = 0; a < 3; ++a) {
      int b = (a + 1) % 3;
      N[3 + a] = 4 * L[a] * L[b];
      Nr[3 + a] = 4 * (L[a] * dL[b][0] + L[b] * dL[a][0]);
      Ns[3 + a] = 4 * (L[a] * dL[b][1] + L[b] * dL[a][1]);
    }
  }
  for (int i = 0; i < 3; ++i) {
    x[i] = xr[i] = xs[i] = 0;
    for (int a = 0; a < nfn; ++a) {
      x[i] += N[a] * X[3 * a + i];
      xr[i] += Nr[a] * X[3 * a + i];
      xs[i] += Ns[a] * X[3 * a + i];
    }
  }
}

static void integrate(const FemMesh *m, const FemSurface *s, double a[3], double *vol,
                      double *area)
{
  double L[6][3], w[6];
  int nq = tri_rule(s->nfn, L, w);
  a[0] = a[1] = a[2] = 0;
  *vol = *area = 0;
  for (int f = 0; f < s->nfaces; ++f) {
    double X[18];
    for (int k = 0; k < s->nfn; ++k)
      for (int i = 0; i < 3; ++i) X[3 * k + i] = m->xyz[3 * s->faces[s->nfn * f + k] + i];
    for (int q = 0; q < nq; ++q) {
      double x[3], xr[3], xs[3];
      tri_eval(s->nfn, X, L[q], x, xr, xs);
      double n[3] = {xr[1] * xs[2] - xr[2] * xs[1], xr[2] * xs[0] - xr[0] * xs[2],
                     xr[0] * xs[1] - xr[1] * xs[0]};
      for (int i = 0; i < 3; ++i) a[i] += w[q] * n[i];
      *vol -= w[q] * (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) / 3.0;
      *area += w[q] * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
  }
}

void mt_surface_integrals(const FemMesh *m, const FemSurface *s, double a[3], double *vol)
{
  double area;
  integrate(m, s, a, vol, &area);
}

double mt_surface_area(const FemMesh *m, const FemSurface *s)
{
  double a[3], vol, area;
  integrate(m, s, a, &vol, &area);
  return area;
}
