/* test_fem_patch.c - patch test: a homogeneous deformation x = F X + c of a small distorted tet10
 * mesh gives zero internal force at every interior node. The mesh: the 8 corners of a perturbed
 * cube and one interior centre node, 12 tets (centre + each of the 12 triangles of the cube's
 * surface); interior nodes are the centre and the 8 mid-nodes of the spokes. Both with straight
 * edges (4-point rule) and with curved spokes and faces (mid-nodes displaced, 8-point rule).
 * F constant means constant P and theta = J in every element, so f_a = P int grad N_a dV, whose
 * sum over the patch vanishes for interior a when the rule integrates grad N det J0 exactly
 * (degree 1 for straight, 3 for curved tet10). Tolerance: 1e-11 of the largest nodal force
 * (round-off of sums of O(10) terms). Also: the net force on the patch is zero.
 * Composite tet10 (FemMaterial.tet10_composite): the patch is then a conforming mesh of 96
 * linear sub-tets (a face's 4 sub-triangles do not depend on the octahedron's diagonal), so
 * interior forces vanish for straight and curved patches alike, and every element's stress
 * (fem_element_stress) equals the law's Cauchy stress at F, computed directly from the law
 * (independent reference: built-in laws sigma = P_iso F^T / J + U'(J) I, law objects P F^T / J),
 * to 1e-12 of its largest component; also with the Mohr-Coulomb law (FEM_LAW_FULL) from a
 * virgin history in a yielding state (F with 30 % random part: every point yields). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fem_element.h"
#include "fem_law.h"
#include "fem_mohr_coulomb.h"
#include "sa_error.h"
#include "kt_util.h"

#define MAXN 64

static int nnode;
static double Xn[3 * MAXN];
static int edges[MAXN][3]; /* a, b, mid node */
static int nedge;

static int mid_node(int a, int b, double curve)
{
  for (int e = 0; e < nedge; e++)
    if ((edges[e][0] == a && edges[e][1] == b) || (edges[e][0] == b && edges[e][1] == a))
      return edges[e][2];
  int m = nnode++;
  for (int k = 0; k < 3; k++) Xn[3 * m + k] = 0.5 * (Xn[3 * a + k] + Xn[3 * b + k]) + kt_rand(-curve, curve);
  edges[nedge][0] = a, edges[nedge][1] = b, edges[nedge][2] = m;
  nedge++;
  return m;
}

/* The law's Cauchy stress sigma [out] at F [in] (history from hist [in] or none). */
static void law_sigma(const FemMaterial *mat, const double F[9], const double *hist, double sg[9])
{
  double W, P[9], hn[FEM_MAT_MAX_HIST], J = kt_det3(F), dU = 0;
  if (mat->law) {
    FemLawCtx lc = {0.0, 0.0, -1, 0, NULL};
    mat->law->eval(mat->par, &lc, F, hist, mat->nhist ? hn : NULL, &W, P, NULL);
  } else {
    fem_material_eval_iso(mat, F, NULL, NULL, &W, P, NULL);
    fem_material_eval_vol(mat, J, NULL, &dU, NULL);
  }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double v = 0;
      for (int K = 0; K < 3; K++) v += P[3 * i + K] * F[3 * j + K];
      sg[3 * i + j] = v / J + (i == j ? dU : 0);
    }
}

static void patch(const FemMaterial *mat, double curve)
{
  int conn[12][10], ne = 0;
  nnode = 9, nedge = 0;
  for (int k = 0; k < 2; k++)
    for (int j = 0; j < 2; j++)
      for (int i = 0; i < 2; i++) {
        double *X = Xn + 3 * (i + 2 * j + 4 * k);
        X[0] = i + kt_rand(-0.15, 0.15), X[1] = j + kt_rand(-0.15, 0.15), X[2] = k + kt_rand(-0.15, 0.15);
      }
  const int c = 8;
  Xn[24] = 0.5 + kt_rand(-0.1, 0.1), Xn[25] = 0.5 + kt_rand(-0.1, 0.1), Xn[26] = 0.5 + kt_rand(-0.1, 0.1);
  for (int d = 0; d < 3; d++)
    for (int s = 0; s < 2; s++) {
      int u = (d + 1) % 3, v = (d + 2) % 3, g[2][2];
      for (int p = 0; p < 2; p++)
        for (int q = 0; q < 2; q++) {
          int ijk[3];
          ijk[d] = s, ijk[u] = p, ijk[v] = q;
          g[p][q] = ijk[0] + 2 * ijk[1] + 4 * ijk[2];
        }
      int tri[2][3] = {{g[0][0], g[1][0], g[1][1]}, {g[0][0], g[1][1], g[0][1]}};
      for (int t = 0; t < 2; t++) {
        int n[4] = {tri[t][0], tri[t][1], tri[t][2], c};
        double A[9];
        for (int r = 0; r < 3; r++)
          for (int k = 0; k < 3; k++) A[3 * r + k] = Xn[3 * n[r + 1] + k] - Xn[3 * n[0] + k];
        if (kt_det3(A) < 0) {
          int tmp = n[1];
          n[1] = n[2], n[2] = tmp;
        }
        for (int a = 0; a < 4; a++) conn[ne][a] = n[a];
        for (int e = 0; e < 6; e++) conn[ne][4 + e] = mid_node(n[kt_tet_edge[e][0]], n[kt_tet_edge[e][1]], curve);
        ne++;
      }
    }
  int interior[MAXN] = {0};
  interior[c] = 1;
  for (int e = 0; e < nedge; e++)
    if (edges[e][0] == c || edges[e][1] == c) interior[edges[e][2]] = 1;

  double F[9], off[3] = {0.3, -0.2, 0.7}, xn[3 * MAXN], f[3 * MAXN] = {0};
  kt_random_F(0.3, kt_rand(0.8, 1.3), F);
  for (int a = 0; a < nnode; a++)
    for (int i = 0; i < 3; i++)
      xn[3 * a + i] = F[3 * i] * Xn[3 * a] + F[3 * i + 1] * Xn[3 * a + 1] + F[3 * i + 2] * Xn[3 * a + 2] + off[i];
  static FemElemOut out;
  char what[160];
  const int comp = mat->tet10_composite, nh = mat->nhist;
  double hold[8 * FEM_MAT_MAX_HIST], hnew[8 * FEM_MAT_MAX_HIST], sref[9];
  if (nh) { /* the Mohr-Coulomb law: virgin points */
    const double d = M_PI / 180;
    FemMohrCoulomb p = {mat->par[0], mat->par[1], mat->par[2] * d, mat->par[3], mat->par[4] * d,
                        mat->par[5], 0};
    for (int q = 0; q < 8; q++) fem_mc_hist_init(&p, NULL, hold + q * nh);
  }
  law_sigma(mat, F, nh ? hold : NULL, sref);
  for (int e = 0; e < ne; e++) {
    double X[30], x[30];
    for (int a = 0; a < 10; a++)
      for (int k = 0; k < 3; k++) X[3 * a + k] = Xn[3 * conn[e][a] + k], x[3 * a + k] = xn[3 * conn[e][a] + k];
    if (fem_element_tl(FEM_TET10, X, x, mat, nh ? hold : NULL, nh ? hnew : NULL, 0, &out)) {
      fprintf(stderr, "patch (curve %g): element %d failed: %s\n", curve, e, sa_error_message());
      kt_fail++;
      return;
    }
    for (int a = 0; a < 10; a++)
      for (int k = 0; k < 3; k++) f[3 * conn[e][a] + k] += out.fe[3 * a + k];
    if (!comp) continue;
    double sg[9], lam[3], smax = kt_maxabs(sref, 9);
    if (fem_element_stress(FEM_TET10, X, x, mat, nh ? hold : NULL, sg, lam)) {
      fprintf(stderr, "patch (composite, curve %g): stress of element %d failed: %s\n", curve, e,
              sa_error_message());
      kt_fail++;
      return;
    }
    for (int i = 0; i < 9; i++) {
      snprintf(what, sizeof what, "patch (composite, curve %g): element %d sigma[%d]", curve, e, i);
      kt_close(what, sg[i], sref[i], 1e-12 * smax, 0);
    }
    for (int q = 0; nh && q < 8; q++)
      if (hnew[q * nh + 7] == FEM_MC_ELASTIC) {
        fprintf(stderr, "patch (composite MC, curve %g): element %d point %d did not yield\n",
                curve, e, q);
        kt_fail++;
      }
  }
  double fmax = kt_maxabs(f, 3 * nnode), sum[3] = {0, 0, 0};
  if (fmax < 1e-3) {
    fprintf(stderr, "patch: no boundary forces (deformation too small to test)\n");
    kt_fail++;
  }
  int ninterior = 0;
  for (int a = 0; a < nnode; a++) {
    for (int k = 0; k < 3; k++) sum[k] += f[3 * a + k];
    if (!interior[a]) continue;
    ninterior++;
    for (int k = 0; k < 3; k++) {
      snprintf(what, sizeof what, "patch (%scurve %g): interior node %d force %d", comp ? "composite, " : "", curve, a, k);
      kt_close(what, f[3 * a + k], 0, 1e-11 * fmax, 0);
    }
  }
  if (ninterior != 9) {
    fprintf(stderr, "patch: %d interior nodes, expected 9\n", ninterior);
    kt_fail++;
  }
  for (int k = 0; k < 3; k++) {
    snprintf(what, sizeof what, "patch (%scurve %g): net force %d", comp ? "composite, " : "", curve, k);
    kt_close(what, sum[k], 0, 1e-11 * fmax, 0);
  }
}

int main(void)
{
  FemMaterial ye = {.kind = FEM_MAT_YEOH, .c10 = 0.11, .c20 = 0.02, .c30 = 0.001, .kappa = 110};
  FemMaterial mr = {.kind = FEM_MAT_MOONEY_RIVLIN, .c10 = 0.3, .c01 = 0.2, .kappa = 1000};
  for (int rep = 0; rep < 3; rep++) {
    patch(&ye, 0);
    patch(&mr, 0);
    patch(&ye, 0.04);
    patch(&mr, 0.04);
  }
  FemMaterial mc;
  const char *nm[] = {"young", "poisson", "friction_angle", "cohesion", "dilation_angle"};
  double v[] = {100.0, 0.3, 30, 0.1, 10};
  if (fem_material_from_law("mohr_coulomb", 5, nm, v, 1, &mc)) {
    fprintf(stderr, "mohr_coulomb material: %s\n", sa_error_message());
    return 1;
  }
  ye.tet10_composite = mr.tet10_composite = mc.tet10_composite = 1;
  for (int rep = 0; rep < 3; rep++)
    for (int cv = 0; cv < 2; cv++) {
      patch(&ye, 0.04 * cv);
      patch(&mr, 0.04 * cv);
      patch(&mc, 0.04 * cv);
    }
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
