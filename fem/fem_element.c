/* fem_element.c - total-Lagrangian tet4/tet10 kernels with the mean-dilatation mixed
 * formulation, and follower-pressure / enclosed-volume face kernels (see fem_element.h).
 *
 * Solid: with reference gradients G_aJ = dN_a/dX_J, weights w_q (reference volume), F_q,
 * J_q = det F_q, H = F^-T, V = sum w_q, theta = (1/V) sum w_q J_q, ks = kappa_s:
 *   Pi   = sum_q w_q [W_iso(F_q) + (ks/2)(J_q - theta)^2] + V U(theta)
 *   f_ai = sum_q w_q Pt_iJ G_aJ,     Pt = P_iso + p_q J H,  p_q = U'(theta) + ks (J_q - theta)
 *   K    = sum_q w_q G_aJ At_iJkL G_bL + ((U''(theta) - ks)/V) b_ai b_bk,
 *          At = A_iso + p_q J (H_iJ H_kL - H_iL H_kJ) + ks J^2 H_iJ H_kL,
 *          b_ai = sum_q w_q J_q H_iJ G_aJ = V dtheta/dx_ai,
 * using sum_q w_q (J_q - theta) = 0 (which removes the dtheta terms of the ks part); the
 * pressure is eliminated (condensed) exactly at element level.
 * The B^T A B product is done per node a as T = G_a . A (3x9) then T . G_b, only for b >= a when
 * the law is symmetric.
 *
 * Quadrature: tet4 1 point; tet10 4 points (degree 2) when straight-sided, 8 points (degree 3)
 * when curved, see fem_kernel_quad.h for why. Composite tet10 (FemMaterial.tet10_composite):
 * point q is sub-tet q of composite_sub, G its tet4 gradients on its 4 nodes (zero for the
 * other 6), w_q its volume; the sums above then run over each point's 4 nodes only (ElemGeom).
 *
 * Faces: x(r, s) = sum N_a x_a, t1 = x,r, t2 = x,s, n da = t1 x t2 dr ds, and
 *   dn_i/dx_bk = e_ikm (N_b,r t2_m - N_b,s t1_m). */
#include "fem_element.h"

#include <math.h>
#include <string.h>

#include "fem_kernel_quad.h"
#include "fem_kernel_tensor.h"
#include "fem_law.h"
#include "sa_error.h"

static const FemKqRule *tet_rule(FemElemType t, const double *X)
{
  if (t == FEM_TET4) return &fem_kq_tet1;
  return fem_kq_tet10_curved(X) ? &fem_kq_tet8 : &fem_kq_tet4;
}

static inline int is_composite(FemElemType t, const FemMaterial *mat)
{
  return t == FEM_TET10 && mat && mat->tet10_composite;
}

/* The composite tet10's sub-tets (local node numbers, VTK order; positive volume in a positive
 * parent, 1/8 of the parent each when straight-sided): the 4 corner tets, then the inner
 * octahedron split along its diagonal from mid-node 02 (6) to mid-node 13 (8). */
static const int composite_sub[8][4] = {{0, 4, 6, 7}, {4, 1, 5, 8}, {6, 5, 2, 9}, {7, 8, 9, 3},
                                        {6, 8, 4, 5}, {6, 8, 5, 9}, {6, 8, 9, 7}, {6, 8, 7, 4}};
/* The same lists in ascending order (the symmetric tangent fills blocks b >= a only). */
static const int composite_sorted[8][4] = {{0, 4, 6, 7}, {1, 4, 5, 8}, {2, 5, 6, 9}, {3, 7, 8, 9},
                                           {4, 5, 6, 8}, {5, 6, 8, 9}, {6, 7, 8, 9}, {4, 6, 7, 8}};

int fem_element_nqp(FemElemType t) { return t == FEM_TET4 ? 1 : 8; }

int fem_element_nqp_used(FemElemType t, const double *X, const FemMaterial *mat)
{
  return is_composite(t, mat) ? 8 : tet_rule(t, X)->n;
}

/* Reference gradients G [out] and weight w [out] (rule weight x det dX/dxi) at point L.
 * Returns det dX/dxi; G and w are valid only when it is > 0. */
static double tet_geom(int nen, const double *X, const double L[4], double wref, double G[][3],
                       double *w)
{
  double dN[10][3], J0[9] = {0}, iJ0[9];
  fem_kq_tet_shape(nen, L, NULL, dN);
  for (int a = 0; a < nen; a++)
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++) J0[3 * i + k] += X[3 * a + i] * dN[a][k];
  double d = fem_kt_inv(J0, iJ0);
  if (!(d > 0)) return d;
  for (int a = 0; a < nen; a++)
    for (int J = 0; J < 3; J++)
      G[a][J] = dN[a][0] * iJ0[J] + dN[a][1] * iJ0[3 + J] + dN[a][2] * iJ0[6 + J];
  *w = wref * d;
  return d;
}

/* Reference geometry of one element at its quadrature points: G[q][a] the reference gradient
 * of node a's function (zero for the 6 nodes outside a composite sub-tet), w[q] the weight,
 * act[q][0..na[q]) the nodes with nonzero G (ascending). */
typedef struct {
  int nq, na[FEM_KQ_MAX_QP], act[FEM_KQ_MAX_QP][10];
  double G[FEM_KQ_MAX_QP][10][3], w[FEM_KQ_MAX_QP];
} ElemGeom;

/* Fills g [out]; returns the smallest det dX/dxi (g valid only when it is > 0). Standard: the
 * rule of tet_rule. Composite: point q is sub-tet q, whose linear functions have the constant
 * gradients of a tet4 on its 4 nodes, weight = its volume. */
static double elem_geom(FemElemType t, const double *X, const FemMaterial *mat, ElemGeom *g)
{
  const int nen = (int)t;
  double dmin = INFINITY;
  if (is_composite(t, mat)) {
    static const double Lc[4] = {0.25, 0.25, 0.25, 0.25};
    g->nq = 8;
    for (int q = 0; q < 8; q++) {
      double X4[12], G4[4][3];
      for (int k = 0; k < 4; k++)
        for (int i = 0; i < 3; i++) X4[3 * k + i] = X[3 * composite_sub[q][k] + i];
      double d = tet_geom(4, X4, Lc, 1.0 / 6.0, G4, &g->w[q]);
      if (!(d > 0)) return d;
      dmin = fmin(dmin, d);
      memset(g->G[q], 0, sizeof g->G[q]);
      for (int k = 0; k < 4; k++) memcpy(g->G[q][composite_sub[q][k]], G4[k], sizeof G4[k]);
      g->na[q] = 4;
      memcpy(g->act[q], composite_sorted[q], sizeof composite_sorted[q]);
    }
    return dmin;
  }
  const FemKqRule *R = tet_rule(t, X);
  g->nq = R->n;
  for (int q = 0; q < R->n; q++) {
    double d = tet_geom(nen, X, R->L[q], R->w[q], g->G[q], &g->w[q]);
    if (!(d > 0)) return d;
    dmin = fmin(dmin, d);
    g->na[q] = nen;
    for (int a = 0; a < nen; a++) g->act[q][a] = a;
  }
  return dmin;
}

#define ELEM_GEOM(t, X, mat, g)                                                                  \
  do {                                                                                         \
    double d_ = elem_geom(t, X, mat, g);                                                       \
    SA_REQUIRE(d_ > 0, SA_ERR_INPUT, "degenerate or inverted reference element (det J = %g)", d_); \
  } while (0)

static void def_grad(int nen, const double *x, const double G[][3], double F[9])
{
  for (int i = 0; i < 9; i++) F[i] = 0;
  for (int a = 0; a < nen; a++)
    for (int i = 0; i < 3; i++) {
      double xa = x[3 * a + i];
      F[3 * i + 0] += xa * G[a][0];
      F[3 * i + 1] += xa * G[a][1];
      F[3 * i + 2] += xa * G[a][2];
    }
}

int fem_element_tl(FemElemType t, const double *X, const double *x, const FemMaterial *mat,
                   const double *hist_old, double *hist_new, int want_K, FemElemOut *out)
{
  return fem_element_tl_ctx(t, X, x, mat, NULL, hist_old, hist_new, want_K, out);
}

/* The region's law at one quadrature point: a law object, or the built-in kinds directly. */
static inline int law_eval(const FemMaterial *mat, const FemLawCtx *lc, const double F[9],
                           const double *ho, double *hn, double *W, double P[9], double A[81])
{
  if (mat->law) return mat->law->eval(mat->par, lc, F, ho, hn, W, P, A);
  return fem_material_eval_iso(mat, F, ho, hn, W, P, A);
}

int fem_element_tl_ctx(FemElemType t, const double *X, const double *x, const FemMaterial *mat,
                       const FemLawCtx *ctx, const double *hist_old, double *hist_new,
                       int want_K, FemElemOut *out)
{
  FemLawCtx lc = ctx ? *ctx : (FemLawCtx){0.0, 0.0, -1, -1, NULL};
  const int nen = (int)t, ndof = 3 * nen, nh = mat->nhist;
  ElemGeom g;
  ELEM_GEOM(t, X, mat, &g);
  const int nq = g.nq;
  double(*G)[10][3] = g.G, *wq = g.w, Fq[FEM_KQ_MAX_QP][9], Jq[FEM_KQ_MAX_QP];
  double V = 0, v = 0, minJ = INFINITY;
  for (int q = 0; q < nq; q++) {
    def_grad(nen, x, (const double(*)[3])G[q], Fq[q]);
    Jq[q] = fem_kt_det(Fq[q]);
    if (Jq[q] < minJ) minJ = Jq[q];
    V += wq[q];
    v += wq[q] * Jq[q];
  }
  double theta = v / V;
  out->theta = theta;
  out->min_detF = minJ;
  if (!(minJ > 0) || !(theta > 0))
    return SA_ERROR(SA_ERR_INVERTED, "inverted element: min det F = %g, theta = %g", minJ, theta);

  double U, dU, d2U, ks = fem_material_kappa_fluct(mat);
  fem_material_eval_vol(mat, theta, &U, &dU, &d2U);
  double energy = V * U;
  double *fe = out->fe, *Ke = out->Ke, bv[30];
  memset(fe, 0, sizeof(double) * ndof);
  memset(bv, 0, sizeof bv);
  if (want_K) memset(Ke, 0, sizeof(double) * ndof * ndof);
  const int sym = fem_material_symmetric(mat);

  for (int q = 0; q < nq; q++) {
    const double *F = Fq[q], w = wq[q];
    const double(*Gq)[3] = (const double(*)[3])G[q];
    double W, P[9], A[81], cof[9], H[9];
    lc.qp = q;
    SA_CHECK(law_eval(mat, &lc, F, nh ? hist_old + q * nh : NULL, nh ? hist_new + q * nh : NULL,
                      &W, P, want_K ? A : NULL));
    double dJ = Jq[q] - theta, pq = dU + ks * dJ; /* quadrature-point pressure */
    energy += w * (W + 0.5 * ks * dJ * dJ);
    fem_kt_cof(F, cof); /* J H */
    double iJ = 1 / Jq[q];
    for (int i = 0; i < 9; i++) {
      H[i] = cof[i] * iJ;
      P[i] = w * (P[i] + pq * cof[i]);
    }
    const int na = g.na[q], *act = g.act[q];
    for (int ia = 0; ia < na; ia++) {
      const int a = act[ia];
      const double *Ga = Gq[a];
      for (int i = 0; i < 3; i++) {
        const double *Pi = P + 3 * i, *ci = cof + 3 * i;
        fe[3 * a + i] += Pi[0] * Ga[0] + Pi[1] * Ga[1] + Pi[2] * Ga[2];
        bv[3 * a + i] += w * (ci[0] * Ga[0] + ci[1] * Ga[1] + ci[2] * Ga[2]);
      }
    }
    if (!want_K) continue;
    /* At = w [A + p_q (cof_iJ H_kL - cof_iL H_kJ) + ks cof_iJ cof_kL] */
    for (int i = 0; i < 3; i++)
      for (int J = 0; J < 3; J++) {
        double *Ar = A + 9 * (3 * i + J), cr = pq * cof[3 * i + J], cs = ks * cof[3 * i + J];
        for (int k = 0; k < 3; k++)
          for (int L = 0; L < 3; L++)
            Ar[3 * k + L] = w * (Ar[3 * k + L] + cr * H[3 * k + L] + cs * cof[3 * k + L] -
                                 pq * cof[3 * i + L] * H[3 * k + J]);
      }
    for (int ia = 0; ia < na; ia++) {
      const int a = act[ia];
      const double *Ga = Gq[a];
      double T[3][9];
      for (int i = 0; i < 3; i++) {
        const double *A0 = A + 9 * (3 * i), *A1 = A0 + 9, *A2 = A0 + 18;
        for (int c = 0; c < 9; c++) T[i][c] = Ga[0] * A0[c] + Ga[1] * A1[c] + Ga[2] * A2[c];
      }
      for (int ib = sym ? ia : 0; ib < na; ib++) {
        const int b = act[ib];
        const double *Gb = Gq[b];
        for (int i = 0; i < 3; i++) {
          double *Kr = Ke + (3 * a + i) * ndof + 3 * b;
          const double *Ti = T[i];
          Kr[0] += Ti[0] * Gb[0] + Ti[1] * Gb[1] + Ti[2] * Gb[2];
          Kr[1] += Ti[3] * Gb[0] + Ti[4] * Gb[1] + Ti[5] * Gb[2];
          Kr[2] += Ti[6] * Gb[0] + Ti[7] * Gb[1] + Ti[8] * Gb[2];
        }
      }
    }
  }
  out->energy = energy;
  if (!want_K) return 0;
  double s = (d2U - ks) / V;
  for (int r = 0; r < ndof; r++) {
    double br = s * bv[r];
    double *Kr = Ke + r * ndof;
    for (int c = sym ? 3 * (r / 3) : 0; c < ndof; c++) Kr[c] += br * bv[c];
  }
  if (sym)
    for (int r = 0; r < ndof; r++)
      for (int c = 3 * (r / 3) + 3; c < ndof; c++) Ke[c * ndof + r] = Ke[r * ndof + c];
  return 0;
}

int fem_element_stress(FemElemType t, const double *X, const double *x, const FemMaterial *mat,
                       const double *hist, double sigma[9], double lam[3])
{
  const int nen = (int)t, nh = mat->nhist;
  ElemGeom g;
  ELEM_GEOM(t, X, mat, &g);
  const int nq = g.nq;
  double *wq = g.w, Fq[FEM_KQ_MAX_QP][9], Jq[FEM_KQ_MAX_QP];
  double V = 0, v = 0, Fa[9] = {0}, scratch[FEM_MAT_MAX_HIST];
  for (int q = 0; q < nq; q++) {
    def_grad(nen, x, (const double(*)[3])g.G[q], Fq[q]);
    Jq[q] = fem_kt_det(Fq[q]);
    SA_REQUIRE(Jq[q] > 0, SA_ERR_INVERTED, "inverted element: det F = %g", Jq[q]);
    V += wq[q];
    v += wq[q] * Jq[q];
    for (int i = 0; i < 9; i++) Fa[i] += wq[q] * Fq[q][i];
  }
  double theta = v / V, dU, ks = fem_material_kappa_fluct(mat);
  fem_material_eval_vol(mat, theta, NULL, &dU, NULL);
  /* sigma = (1/v) int sigma dv = (1/v) sum_q w_q Pt_q F_q^T; the volumetric part gives
   * p = U'(theta) + ks (1/v) sum_q w_q J_q (J_q - theta). */
  for (int i = 0; i < 9; i++) sigma[i] = 0;
  for (int q = 0; q < nq; q++) {
    double W, P[9];
    FemLawCtx lc = {0.0, 0.0, -1, q, NULL};
    SA_CHECK(law_eval(mat, &lc, Fq[q], nh ? hist + q * nh : NULL, nh ? scratch : NULL, &W, P,
                      NULL));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double s = 0;
        for (int K = 0; K < 3; K++) s += P[3 * i + K] * Fq[q][3 * j + K];
        sigma[3 * i + j] += wq[q] * s / v;
      }
  }
  double pv = 0;
  for (int q = 0; q < nq; q++) pv += wq[q] * Jq[q] * (Jq[q] - theta);
  for (int i = 0; i < 3; i++) sigma[4 * i] += dU + ks * pv / v;
  /* Principal stretches of the volume-averaged F, rescaled so that det F = theta (the element's
   * volume ratio in the mixed formulation); exact for a homogeneous deformation. */
  double dFa = fem_kt_det(Fa) / (V * V * V);
  SA_REQUIRE(dFa > 0, SA_ERR_INVERTED, "inverted element: det of mean F = %g", dFa);
  double sc = cbrt(theta / dFa) / V, C[9], ev[3];
  for (int i = 0; i < 9; i++) Fa[i] *= sc;
  for (int I = 0; I < 3; I++)
    for (int J = 0; J < 3; J++) {
      double s = 0;
      for (int k = 0; k < 3; k++) s += Fa[3 * k + I] * Fa[3 * k + J];
      C[3 * I + J] = s;
    }
  fem_kt_sym_eig(C, ev);
  for (int i = 0; i < 3; i++) lam[i] = sqrt(fmax(ev[i], 0));
  return 0;
}

void fem_element_lumped_mass_mat(FemElemType t, const double *X, const FemMaterial *mat,
                                 double *m)
{
  if (!is_composite(t, mat)) {
    fem_element_lumped_mass(t, X, mat->rho, m);
    return;
  }
  /* composite: each sub-tet's mass rho V_q / 4 to its corners (its linear functions' row sums) */
  ElemGeom g;
  for (int a = 0; a < 10; a++) m[a] = 0;
  if (!(elem_geom(t, X, mat, &g) > 0)) return; /* degenerate: fem_mesh_check reports it */
  for (int q = 0; q < 8; q++)
    for (int k = 0; k < 4; k++) m[composite_sub[q][k]] += 0.25 * mat->rho * g.w[q];
}

void fem_element_lumped_mass(FemElemType t, const double *X, double rho, double *m)
{
  const int nen = (int)t;
  const FemKqRule *R = t == FEM_TET4 ? &fem_kq_tet1 : &fem_kq_tet14;
  double diag[10] = {0}, V = 0, sd = 0;
  for (int q = 0; q < R->n; q++) {
    double G[10][3], w, N[10];
    if (!(tet_geom(nen, X, R->L[q], R->w[q], G, &w) > 0)) {
      for (int a = 0; a < nen; a++) m[a] = 0; /* degenerate: fem_mesh_check reports it */
      return;
    }
    fem_kq_tet_shape(nen, R->L[q], N, NULL);
    V += w;
    for (int a = 0; a < nen; a++) diag[a] += w * N[a] * N[a];
  }
  if (t == FEM_TET4) {
    for (int a = 0; a < 4; a++) m[a] = 0.25 * rho * V;
    return;
  }
  /* HRZ: scale the consistent-mass diagonal to the element mass. */
  for (int a = 0; a < nen; a++) sd += diag[a];
  for (int a = 0; a < nen; a++) m[a] = rho * V * diag[a] / sd;
}

static void face_frame(int nfn, const double *x, const double L[3], double *N, double (*dN)[2],
                       double t1[3], double t2[3], double n[3])
{
  fem_kq_tri_shape(nfn, L, N, dN);
  for (int k = 0; k < 3; k++) t1[k] = t2[k] = 0;
  for (int a = 0; a < nfn; a++)
    for (int k = 0; k < 3; k++) {
      t1[k] += x[3 * a + k] * dN[a][0];
      t2[k] += x[3 * a + k] * dN[a][1];
    }
  n[0] = t1[1] * t2[2] - t1[2] * t2[1];
  n[1] = t1[2] * t2[0] - t1[0] * t2[2];
  n[2] = t1[0] * t2[1] - t1[1] * t2[0];
}

/* S(v)_ik = e_ikm v_m. */
static inline void skew(const double v[3], double S[9])
{
  S[0] = 0, S[1] = v[2], S[2] = -v[1];
  S[3] = -v[2], S[4] = 0, S[5] = v[0];
  S[6] = v[1], S[7] = -v[0], S[8] = 0;
}

void fem_face_pressure(int nfn, const double *x, double p, double *fe, double *Ke)
{
  const FemKqRule *R = nfn == 3 ? &fem_kq_tri3 : &fem_kq_tri6;
  const int nd = 3 * nfn;
  memset(fe, 0, sizeof(double) * nd);
  if (Ke) memset(Ke, 0, sizeof(double) * nd * nd);
  for (int q = 0; q < R->n; q++) {
    double N[6], dN[6][2], t1[3], t2[3], n[3];
    face_frame(nfn, x, R->L[q], N, dN, t1, t2, n);
    double pw = p * R->w[q];
    for (int a = 0; a < nfn; a++)
      for (int i = 0; i < 3; i++) fe[3 * a + i] -= pw * N[a] * n[i];
    if (!Ke) continue;
    for (int b = 0; b < nfn; b++) {
      double vb[3], S[9];
      for (int m = 0; m < 3; m++) vb[m] = dN[b][0] * t2[m] - dN[b][1] * t1[m];
      skew(vb, S); /* dn_i/dx_bk = S_ik */
      for (int a = 0; a < nfn; a++) {
        double c = pw * N[a];
        for (int i = 0; i < 3; i++)
          for (int k = 0; k < 3; k++) Ke[(3 * a + i) * nd + 3 * b + k] += c * S[3 * i + k];
      }
    }
  }
}

double fem_face_volume(int nfn, const double *x, double *dv, double *d2v)
{
  const FemKqRule *R = nfn == 3 ? &fem_kq_tri3 : &fem_kq_tri6;
  const int nd = 3 * nfn;
  double vol = 0;
  if (dv) memset(dv, 0, sizeof(double) * nd);
  if (d2v) memset(d2v, 0, sizeof(double) * nd * nd);
  for (int q = 0; q < R->n; q++) {
    double N[6], dN[6][2], t1[3], t2[3], n[3], xq[3] = {0, 0, 0};
    face_frame(nfn, x, R->L[q], N, dN, t1, t2, n);
    for (int a = 0; a < nfn; a++)
      for (int k = 0; k < 3; k++) xq[k] += N[a] * x[3 * a + k];
    double c = -R->w[q] / 3;
    vol += c * (xq[0] * n[0] + xq[1] * n[1] + xq[2] * n[2]);
    if (!dv && !d2v) continue;
    double S[6][9]; /* dn_i/dx_bk for each node b */
    for (int b = 0; b < nfn; b++) {
      double vb[3];
      for (int m = 0; m < 3; m++) vb[m] = dN[b][0] * t2[m] - dN[b][1] * t1[m];
      skew(vb, S[b]);
    }
    if (dv)
      for (int b = 0; b < nfn; b++)
        for (int k = 0; k < 3; k++) {
          double s = N[b] * n[k];
          for (int i = 0; i < 3; i++) s += xq[i] * S[b][3 * i + k];
          dv[3 * b + k] += c * s;
        }
    if (!d2v) continue;
    double Sx[9];
    skew(xq, Sx); /* e_ikj x_j */
    for (int a = 0; a < nfn; a++)
      for (int b = 0; b < nfn; b++) {
        double cr = dN[a][0] * dN[b][1] - dN[b][0] * dN[a][1];
        for (int i = 0; i < 3; i++)
          for (int k = 0; k < 3; k++)
            d2v[(3 * a + i) * nd + 3 * b + k] +=
                c * (N[b] * S[a][3 * k + i] + N[a] * S[b][3 * i + k] + cr * Sx[3 * i + k]);
      }
  }
  return vol;
}
