/* fem_kernel_quad.c - quadrature rules and tet/triangle shape functions (see fem_kernel_quad.h).
 * Rule values verified by tests/fem/kernels/test_fem_quadrature.c against the exact monomial
 * integrals int L^a dV = a! b! c! d! 3! V / (a+b+c+d+3)!. */
#include "fem_kernel_quad.h"

#include <math.h>

#define TET_S31(a, w)                                                                         \
  {a, a, a, 1 - 3 * (a)}, {a, a, 1 - 3 * (a), a}, {a, 1 - 3 * (a), a, a}, {1 - 3 * (a), a, a, a}
#define TET_S22(a, b)                                                                         \
  {a, a, b, b}, {a, b, a, b}, {a, b, b, a}, {b, a, a, b}, {b, a, b, a}, {b, b, a, a}

const FemKqRule fem_kq_tet1 = {1, {{0.25, 0.25, 0.25, 0.25}}, {1.0 / 6.0}};

#define T4A 0.1381966011250105151795 /* (5 - sqrt 5) / 20 */
const FemKqRule fem_kq_tet4 = {4, {TET_S31(T4A, 0)}, {1.0 / 24, 1.0 / 24, 1.0 / 24, 1.0 / 24}};

/* Degree 3, 8 points, positive weights: two S31 orbits (a, a, a, 1 - 3a). Fully symmetric
 * rules need exactness only on the symmetric polynomials 1, sum L_i^2, sum L_i^3, which gives a
 * one-parameter family; this member has a = 1/10 (b and the weights solved to 25 digits). */
#define T8A 0.1
#define T8B 0.3276485088606362762869967
#define T8WA (0.09821539928159403844322218 / 6)
#define T8WB (0.1517846007184059615567778 / 6)
const FemKqRule fem_kq_tet8 = {8,
                               {TET_S31(T8A, 0), TET_S31(T8B, 0)},
                               {T8WA, T8WA, T8WA, T8WA, T8WB, T8WB, T8WB, T8WB}};

/* Walkington, "Quadrature on simplices of arbitrary dimension" (2014), 14 points, degree 5. */
#define T14A 0.0927352503108912
#define T14B 0.3108859192633006
#define T14C 0.0455037041256496
#define T14WA (0.07349304311636196 / 6)
#define T14WB (0.1126879257180159 / 6)
#define T14WC (0.04254602077708147 / 6)
const FemKqRule fem_kq_tet14 = {
    14,
    {TET_S31(T14A, 0), TET_S31(T14B, 0), TET_S22(T14C, 0.5 - T14C)},
    {T14WA, T14WA, T14WA, T14WA, T14WB, T14WB, T14WB, T14WB, T14WC, T14WC, T14WC, T14WC, T14WC,
     T14WC}};

const FemKqRule fem_kq_tri3 = {
    3, {{2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}},
    {1.0 / 6, 1.0 / 6, 1.0 / 6}};

#define TRA 0.445948490915964886
#define TRB 0.091576213509770743
#define TRWA (0.223381589678011466 / 2)
#define TRWB (0.109951743655321868 / 2)
const FemKqRule fem_kq_tri6 = {6,
                               {{1 - 2 * TRA, TRA, TRA},
                                {TRA, 1 - 2 * TRA, TRA},
                                {TRA, TRA, 1 - 2 * TRA},
                                {1 - 2 * TRB, TRB, TRB},
                                {TRB, 1 - 2 * TRB, TRB},
                                {TRB, TRB, 1 - 2 * TRB}},
                               {TRWA, TRWA, TRWA, TRWB, TRWB, TRWB}};

/* dL_i/d(r,s,t): L0 = 1 - r - s - t, L1 = r, L2 = s, L3 = t. */
static const double dLtet[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
static const int tet_edge[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};

void fem_kq_tet_shape(int nen, const double L[4], double *N, double (*dN)[3])
{
  if (nen == 4) {
    for (int a = 0; a < 4; a++) {
      if (N) N[a] = L[a];
      if (dN)
        for (int k = 0; k < 3; k++) dN[a][k] = dLtet[a][k];
    }
    return;
  }
  for (int a = 0; a < 4; a++) {
    if (N) N[a] = L[a] * (2 * L[a] - 1);
    if (dN)
      for (int k = 0; k < 3; k++) dN[a][k] = (4 * L[a] - 1) * dLtet[a][k];
  }
  for (int e = 0; e < 6; e++) {
    int i = tet_edge[e][0], j = tet_edge[e][1];
    if (N) N[4 + e] = 4 * L[i] * L[j];
    if (dN)
      for (int k = 0; k < 3; k++) dN[4 + e][k] = 4 * (dLtet[i][k] * L[j] + L[i] * dLtet[j][k]);
  }
}

static const double dLtri[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
static const int tri_edge[3][2] = {{0, 1}, {1, 2}, {2, 0}};

void fem_kq_tri_shape(int nfn, const double L[3], double *N, double (*dN)[2])
{
  if (nfn == 3) {
    for (int a = 0; a < 3; a++) {
      if (N) N[a] = L[a];
      if (dN) dN[a][0] = dLtri[a][0], dN[a][1] = dLtri[a][1];
    }
    return;
  }
  for (int a = 0; a < 3; a++) {
    if (N) N[a] = L[a] * (2 * L[a] - 1);
    if (dN)
      for (int k = 0; k < 2; k++) dN[a][k] = (4 * L[a] - 1) * dLtri[a][k];
  }
  for (int e = 0; e < 3; e++) {
    int i = tri_edge[e][0], j = tri_edge[e][1];
    if (N) N[3 + e] = 4 * L[i] * L[j];
    if (dN)
      for (int k = 0; k < 2; k++) dN[3 + e][k] = 4 * (dLtri[i][k] * L[j] + L[i] * dLtri[j][k]);
  }
}

int fem_kq_tet10_curved(const double *X)
{
  for (int e = 0; e < 6; e++) {
    const double *xi = X + 3 * tet_edge[e][0], *xj = X + 3 * tet_edge[e][1], *xm = X + 3 * (4 + e);
    double len2 = 0, dev2 = 0;
    for (int k = 0; k < 3; k++) {
      double d = xj[k] - xi[k], m = xm[k] - 0.5 * (xi[k] + xj[k]);
      len2 += d * d;
      dev2 += m * m;
    }
    if (dev2 > 1e-20 * len2) return 1;
  }
  return 0;
}
