/* fem_mohr_coulomb.c - Mohr-Coulomb finite-strain elastoplasticity kernel (see
 * fem_mohr_coulomb.h and docs/mohr_coulomb.md). Tension positive.
 *
 * Principal return (de Souza Neto, Peric & Owen 2008, section 8.2), perfect plasticity, trial
 * principal elastic strains e1 >= e2 >= e3, s^T = D e, D = lambda 1 (x) 1 + 2 G I:
 *   plane 13:  s = s^T - dg D n13,      dg = f13(s^T) / (a13 . D n13)
 *   edge:      s = s^T - dga D n13 - dgb D nb,  [a13.Dn13 a13.Dnb; ab.Dn13 ab.Dnb] dg = f(s^T)
 *              (b = 12 on the right (extension) edge, b = 23 on the left (compression) edge)
 *   apex:      s = c cot(phi) (1, 1, 1)
 * with a_ij = (1 + sin phi) e_i - (1 - sin phi) e_j (yield normals) and
 * n_ij = (1 + sin psi) e_i - (1 - sin psi) e_j (flow vectors). Every return is linear (no
 * hardening), so the multipliers are exact, not iterated. A candidate is accepted when its
 * multipliers are >= 0 and the returned stresses keep the trial ordering; plane, then the edge
 * the trial points to, then the other edge, then the apex. For psi < phi the apex doubles as a
 * tension cut: trial states that no flow-consistent return reaches go to the apex.
 * Consistent tangent: D - sum_ij D n_i (M^-1)_ij (D a_j)^T, zero at the apex (or, with
 * apex_stiffness = a > 0, a D there: not consistent, but a point at the apex then keeps some
 * stiffness, so nodes surrounded by such points are not left floating in Newton's system).
 *
 * Finite strain (section 14): b_e^tr = F C_p^-1 F^T = sum l_a m_a (x) m_a, e_a = ln(l_a)/2, the
 * principal return gives tau_a, tau = sum tau_a m_a (x) m_a, P = tau F^-T, and the new history
 * C_p^-1 = F^-1 b_e F^-T with b_e = sum exp(2 (e_a - deps_p,a)) m_a (x) m_a.
 * Tangent: with db = dF C_p^-1 F^T + F C_p^-1 dF^T and db'_ab = m_a . db m_b,
 *   dtau'_aa = sum_b D_ab db'_bb / (2 l_b),   dtau'_ab = theta_ab db'_ab (a != b),
 *   theta_ab = (tau_a - tau_b) / (l_a - l_b),
 *   dP = dtau F^-T - P dF^T F^-T.
 * theta_ab is evaluated as 2 G [(e_a - e_b) - (deps_a - deps_b)] / (e_a - e_b) * (e_a - e_b) /
 * (l_a - l_b), which has no cancellation of the hydrostatic part, is exactly 0 for the pair of an
 * active edge (tau_a = tau_b identically there) and at the apex, and takes the limit
 * (D_aa - D_ba) / (2 l) for coincident eigenvalues. */
#include "fem_mohr_coulomb.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "fem_kernel_tensor.h"
#include "fem_law.h"
#include "sa_error.h"

typedef struct {
  double lam, G, K, sf, cf, sp, c, apex, w;
} McConst;

static void mc_const(const FemMohrCoulomb *p, McConst *m)
{
  double E = p->young, nu = p->poisson;
  m->G = E / (2 * (1 + nu));
  m->K = E / (3 * (1 - 2 * nu));
  m->lam = m->K - 2 * m->G / 3;
  m->sf = sin(p->phi);
  m->cf = cos(p->phi);
  m->sp = sin(p->psi);
  m->c = p->c;
  m->apex = p->apex_stiffness;
  m->w = p->tau_over_dt;
}

int fem_mc_check(const FemMohrCoulomb *p)
{
  SA_REQUIRE(p, SA_ERR_INPUT, "mohr_coulomb: NULL parameters");
  SA_REQUIRE(isfinite(p->young) && p->young > 0, SA_ERR_INPUT,
             "mohr_coulomb: young = %g Pa must be > 0", p->young);
  SA_REQUIRE(isfinite(p->poisson) && p->poisson > -1 && p->poisson < 0.5, SA_ERR_INPUT,
             "mohr_coulomb: poisson = %g must be in (-1, 0.5)", p->poisson);
  SA_REQUIRE(isfinite(p->phi) && p->phi >= 0 && p->phi < M_PI / 2, SA_ERR_INPUT,
             "mohr_coulomb: phi = %g rad (%g deg) must be in [0, pi/2) rad", p->phi,
             p->phi * 180 / M_PI);
  SA_REQUIRE(isfinite(p->c) && p->c >= 0, SA_ERR_INPUT, "mohr_coulomb: c = %g Pa must be >= 0",
             p->c);
  SA_REQUIRE(p->phi > 0 || p->c > 0, SA_ERR_INPUT,
             "mohr_coulomb: c = %g Pa must be > 0 when phi = 0 (no strength at all)", p->c);
  SA_REQUIRE(isfinite(p->psi) && p->psi >= 0 && p->psi <= p->phi, SA_ERR_INPUT,
             "mohr_coulomb: psi = %g rad must be in [0, phi = %g] rad", p->psi, p->phi);
  SA_REQUIRE(isfinite(p->apex_stiffness) && p->apex_stiffness >= 0 && p->apex_stiffness <= 1,
             SA_ERR_INPUT, "mohr_coulomb: apex_stiffness = %g must be in [0, 1]",
             p->apex_stiffness);
  SA_REQUIRE(isfinite(p->tau_over_dt) && p->tau_over_dt >= 0, SA_ERR_INPUT,
             "mohr_coulomb: tau_over_dt = %g must be >= 0", p->tau_over_dt);
  return 0;
}

int fem_mc_symmetric(const FemMohrCoulomb *p) { return p->psi == p->phi; }

static void mc_Dv(const McConst *m, const double v[3], double out[3])
{
  double tr = v[0] + v[1] + v[2];
  for (int i = 0; i < 3; i++) out[i] = m->lam * tr + 2 * m->G * v[i];
}

static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Duvaut-Lions viscoplasticity (Simo and Hughes 1998, section 2.7, backward Euler): with
 * w = tau / dt the stress is (s_inviscid + w s_trial) / (1 + w), the plastic strain increment
 * deps_p / (1 + w) and the tangent (D_inviscid + w D_e) / (1 + w); w = 0 leaves the inviscid
 * return as it is. s, deps_p (may be NULL) and D (may be NULL) [in/out], e [in] the trial
 * elastic strains in the same order. */
static void mc_viscous(const McConst *m, double w, const double e[3], double s[3],
                       double deps_p[3], double D[9])
{
  if (!(w > 0)) return;
  double a = 1 / (1 + w), b = w / (1 + w), sT[3];
  mc_Dv(m, e, sT);
  for (int i = 0; i < 3; i++) {
    s[i] = a * s[i] + b * sT[i];
    if (deps_p) deps_p[i] *= a;
  }
  if (D)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        D[3 * i + j] = a * D[3 * i + j] + b * (m->lam + (i == j ? 2 * m->G : 0));
}

/* Two-plane (edge) candidate; right = 1: planes 13 and 12, else 13 and 23. Returns 1 when
 * admissible (multipliers >= 0, ordering kept) and fills s, D, r. */
static int mc_edge(const McConst *m, const double e[3], const double sT[3], double fa, int right,
                   const double aa[3], const double na[3], double s[3], double D[9],
                   FemMcReturn *r)
{
  double ab[3], nb[3], fb, G2 = 2 * m->G;
  if (right) {
    ab[0] = 1 + m->sf, ab[1] = -(1 - m->sf), ab[2] = 0;
    nb[0] = 1 + m->sp, nb[1] = -(1 - m->sp), nb[2] = 0;
    fb = G2 * (e[0] - e[1]) + (sT[0] + sT[1]) * m->sf - 2 * m->c * m->cf;
  } else {
    ab[0] = 0, ab[1] = 1 + m->sf, ab[2] = -(1 - m->sf);
    nb[0] = 0, nb[1] = 1 + m->sp, nb[2] = -(1 - m->sp);
    fb = G2 * (e[1] - e[2]) + (sT[1] + sT[2]) * m->sf - 2 * m->c * m->cf;
  }
  double Dna[3], Dnb[3], Daa[3], Dab[3];
  mc_Dv(m, na, Dna), mc_Dv(m, nb, Dnb), mc_Dv(m, aa, Daa), mc_Dv(m, ab, Dab);
  double M00 = dot3(aa, Dna), M01 = dot3(aa, Dnb), M10 = dot3(ab, Dna), M11 = dot3(ab, Dnb);
  double det = M00 * M11 - M01 * M10;
  if (!(fabs(det) > 1e-14 * fabs(M00 * M11))) return 0;
  double i00 = M11 / det, i01 = -M01 / det, i10 = -M10 / det, i11 = M00 / det;
  double dga = i00 * fa + i01 * fb, dgb = i10 * fa + i11 * fb;
  double gtol = 1e-13 * (fabs(dga) + fabs(dgb));
  if (dga < -gtol || dgb < -gtol) return 0;
  double dep[3], etol = 1e-13 * (e[0] - e[2]);
  for (int i = 0; i < 3; i++) dep[i] = dga * na[i] + dgb * nb[i];
  /* the free difference: s1 - s2 (right) or s2 - s3 (left) must stay >= 0 */
  double gap = right ? (e[0] - e[1]) - (dep[0] - dep[1]) : (e[1] - e[2]) - (dep[1] - dep[2]);
  if (gap < -etol) return 0;
  for (int i = 0; i < 3; i++) s[i] = sT[i] - dga * Dna[i] - dgb * Dnb[i];
  int p = right ? 1 : 0; /* the equal pair (p, p + 1) */
  double avg = 0.5 * (s[p] + s[p + 1]);
  s[p] = s[p + 1] = avg;
  if (D) {
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        D[3 * i + j] -= Dna[i] * (i00 * Daa[j] + i01 * Dab[j]) +
                        Dnb[i] * (i10 * Daa[j] + i11 * Dab[j]);
    for (int j = 0; j < 3; j++) {
      double a = 0.5 * (D[3 * p + j] + D[3 * (p + 1) + j]);
      D[3 * p + j] = D[3 * (p + 1) + j] = a;
    }
  }
  r->region = right ? FEM_MC_EDGE_RIGHT : FEM_MC_EDGE_LEFT;
  r->dgamma[0] = dga, r->dgamma[1] = dgb;
  memcpy(r->deps_p, dep, sizeof dep);
  return 1;
}

/* Principal return for sorted trial strains e[0] >= e[1] >= e[2]. D [out] 9 (may be NULL). */
static int mc_return_sorted(const McConst *m, const double e[3], double s[3], double D[9],
                            FemMcReturn *r)
{
  double sT[3], G2 = 2 * m->G;
  mc_Dv(m, e, sT);
  double d13 = G2 * (e[0] - e[2]);
  double fT = d13 + (sT[0] + sT[2]) * m->sf - 2 * m->c * m->cf;
  double fscale = fabs(d13) + fabs(sT[0] + sT[2]) * m->sf + 2 * m->c * m->cf;
  double De[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) De[3 * i + j] = m->lam + (i == j ? G2 : 0);
  if (D) memcpy(D, De, sizeof De);
  memset(r, 0, sizeof *r);
  if (fT <= 1e-14 * fscale) {
    memcpy(s, sT, 3 * sizeof *s);
    r->region = FEM_MC_ELASTIC;
    return 0;
  }
  double aa[3] = {1 + m->sf, 0, -(1 - m->sf)}, na[3] = {1 + m->sp, 0, -(1 - m->sp)};
  double Dna[3], Daa[3];
  mc_Dv(m, na, Dna), mc_Dv(m, aa, Daa);
  double denom = dot3(aa, Dna), dg = fT / denom, etol = 1e-13 * (e[0] - e[2]);
  /* plane: ordering s1 >= s2 >= s3 after the return, in strains (no hydrostatic cancellation) */
  if ((e[0] - e[1]) - dg * (na[0] - na[1]) >= -etol && (e[1] - e[2]) - dg * (na[1] - na[2]) >= -etol) {
    for (int i = 0; i < 3; i++) s[i] = sT[i] - dg * Dna[i];
    if (D)
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) D[3 * i + j] -= Dna[i] * Daa[j] / denom;
    r->region = FEM_MC_PLANE;
    r->dgamma[0] = dg;
    for (int i = 0; i < 3; i++) r->deps_p[i] = dg * na[i];
  } else {
    /* the edge the plane return crossed first (de Souza Neto et al. box 8.5), then the other */
    int right = (1 - m->sp) * e[0] - 2 * e[1] + (1 + m->sp) * e[2] > 0;
    int ok = mc_edge(m, e, sT, fT, right, aa, na, s, D, r);
    if (!ok) {
      if (D) memcpy(D, De, sizeof De);
      ok = mc_edge(m, e, sT, fT, !right, aa, na, s, D, r);
    }
    if (!ok) {
      if (!(m->sf > 0))
        return SA_ERROR(SA_ERR_NOT_CONVERGED,
                        "mohr_coulomb: no admissible return (phi = 0, trial %g %g %g)", e[0],
                        e[1], e[2]);
      double pa = m->c * m->cf / m->sf, ea = pa / (3 * m->K);
      for (int i = 0; i < 3; i++) s[i] = pa, r->deps_p[i] = e[i] - ea;
      if (D)
        for (int i = 0; i < 9; i++) D[i] = m->apex * De[i];
      r->region = FEM_MC_APEX;
    }
  }
  double f = (s[0] - s[2]) + (s[0] + s[2]) * m->sf - 2 * m->c * m->cf, tol = 1e-10 * fscale;
  if (!(fabs(f) <= tol && s[0] - s[1] >= -tol && s[1] - s[2] >= -tol))
    return SA_ERROR(SA_ERR_NOT_CONVERGED,
                    "mohr_coulomb: return (region %d) left f = %g (scale %g), s = %g %g %g",
                    (int)r->region, f, fscale, s[0], s[1], s[2]);
  return 0;
}

/* Descending order of v: v[ord[0]] >= v[ord[1]] >= v[ord[2]]. */
static void mc_order(const double v[3], int ord[3])
{
  ord[0] = 0, ord[1] = 1, ord[2] = 2;
  for (int i = 0; i < 2; i++)
    for (int j = i + 1; j < 3; j++)
      if (v[ord[j]] > v[ord[i]]) {
        int t = ord[i];
        ord[i] = ord[j], ord[j] = t;
      }
}

int fem_mc_return_principal(const FemMohrCoulomb *p, const double eps_trial[3], double sig[3],
                            double D[9], FemMcReturn *info)
{
  SA_REQUIRE(isfinite(eps_trial[0]) && isfinite(eps_trial[1]) && isfinite(eps_trial[2]),
             SA_ERR_DOMAIN, "mohr_coulomb: non-finite trial strain");
  McConst m;
  mc_const(p, &m);
  int o[3];
  mc_order(eps_trial, o);
  double e[3] = {eps_trial[o[0]], eps_trial[o[1]], eps_trial[o[2]]}, s[3], Ds[9];
  FemMcReturn r;
  SA_CHECK(mc_return_sorted(&m, e, s, D ? Ds : NULL, &r));
  mc_viscous(&m, m.w, e, s, r.deps_p, D ? Ds : NULL);
  for (int a = 0; a < 3; a++) sig[o[a]] = s[a];
  if (D)
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) D[3 * o[a] + o[b]] = Ds[3 * a + b];
  if (info) {
    *info = r;
    for (int a = 0; a < 3; a++) info->deps_p[o[a]] = r.deps_p[a];
  }
  return 0;
}

/* Symmetric eigen-decomposition by cyclic Jacobi: ev [out] descending, Q [out] row-major with
 * the eigenvectors as columns (S = Q diag(ev) Q^T). */
static void mc_sym_eig(const double S[9], double ev[3], double Q[9])
{
  double a[3][3], V[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) a[i][j] = 0.5 * (S[3 * i + j] + S[3 * j + i]);
  for (int sweep = 0; sweep < 50; sweep++) {
    double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-32 * diag || off == 0) break;
    for (int p = 0; p < 2; p++)
      for (int q = p + 1; q < 3; q++) {
        if (a[p][q] == 0) continue;
        double th = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        double t = (th >= 0 ? 1 : -1) / (fabs(th) + sqrt(th * th + 1));
        double c = 1 / sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; k++) {
          double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; k++) {
          double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; k++) {
          double vkp = V[k][p], vkq = V[k][q];
          V[k][p] = c * vkp - s * vkq;
          V[k][q] = s * vkp + c * vkq;
        }
      }
  }
  double d[3] = {a[0][0], a[1][1], a[2][2]};
  int o[3];
  mc_order(d, o);
  for (int b = 0; b < 3; b++) {
    ev[b] = d[o[b]];
    for (int k = 0; k < 3; k++) Q[3 * k + b] = V[k][o[b]];
  }
}

static void mc_voigt_to_mat(const double v[6], double M[9])
{
  M[0] = v[0], M[4] = v[1], M[8] = v[2];
  M[5] = M[7] = v[3];
  M[2] = M[6] = v[4];
  M[1] = M[3] = v[5];
}

static void mc_mat_to_voigt(const double M[9], double v[6])
{
  v[0] = M[0], v[1] = M[4], v[2] = M[8];
  v[3] = 0.5 * (M[5] + M[7]);
  v[4] = 0.5 * (M[2] + M[6]);
  v[5] = 0.5 * (M[1] + M[3]);
}

/* C = A B (transA: A^T B; transB: A B^T), 3x3 row-major. */
static void mc_mm(const double A[9], int transA, const double B[9], int transB, double C[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0;
      for (int k = 0; k < 3; k++)
        s += (transA ? A[3 * k + i] : A[3 * i + k]) * (transB ? B[3 * j + k] : B[3 * k + j]);
      C[3 * i + j] = s;
    }
}

/* Q diag(d) Q^T */
static void mc_spectral(const double Q[9], const double d[3], double M[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      M[3 * i + j] = Q[3 * i] * d[0] * Q[3 * j] + Q[3 * i + 1] * d[1] * Q[3 * j + 1] +
                     Q[3 * i + 2] * d[2] * Q[3 * j + 2];
}

int fem_mc_eval(const FemMohrCoulomb *p, const double F[9], const double *hist_n,
                double *hist_new, double P[9], double A[81], double tau_out[9])
{
  static const double virgin[FEM_MC_NHIST] = {1, 1, 1, 0, 0, 0, 0, 0};
  const double *h = hist_n ? hist_n : virgin;
  for (int i = 0; i < 9; i++)
    SA_REQUIRE(isfinite(F[i]), SA_ERR_DOMAIN, "mohr_coulomb: non-finite F[%d]", i);
  for (int i = 0; i < 7; i++)
    SA_REQUIRE(isfinite(h[i]), SA_ERR_DOMAIN, "mohr_coulomb: non-finite history[%d]", i);
  double Fi[9];
  double J = fem_kt_inv(F, Fi);
  if (!(J > 0)) return SA_ERROR(SA_ERR_INVERTED, "mohr_coulomb: det F = %g <= 0", J);
  McConst m;
  mc_const(p, &m);
  double Cpi[9], FC[9], b[9], lam[3], Q[9];
  mc_voigt_to_mat(h, Cpi);
  mc_mm(F, 0, Cpi, 0, FC); /* F C_p^-1 */
  mc_mm(FC, 0, F, 1, b);   /* b_e^tr */
  mc_sym_eig(b, lam, Q);
  SA_REQUIRE(lam[2] > 0, SA_ERR_DOMAIN,
             "mohr_coulomb: trial b_e not positive definite (eigenvalue %g): bad history", lam[2]);
  double e[3] = {0.5 * log(lam[0]), 0.5 * log(lam[1]), 0.5 * log(lam[2])}, t[3], D[9];
  FemMcReturn r;
  SA_CHECK(mc_return_sorted(&m, e, t, A ? D : NULL, &r));
  /* viscous: stress, tangent and the history's increment blended; theta below from the
   * inviscid return, blended the same way */
  double dp[3] = {r.deps_p[0], r.deps_p[1], r.deps_p[2]};
  mc_viscous(&m, m.w, e, t, dp, A ? D : NULL);
  double tau[9];
  mc_spectral(Q, t, tau);
  mc_mm(tau, 0, Fi, 1, P); /* P = tau F^-T */
  if (tau_out) memcpy(tau_out, tau, sizeof tau);
  if (hist_new) {
    double be[3], Bn[9], T1[9], Cn[9], dp2 = 0;
    for (int a = 0; a < 3; a++) be[a] = exp(2 * (e[a] - dp[a])), dp2 += dp[a] * dp[a];
    mc_spectral(Q, be, Bn);
    mc_mm(Fi, 0, Bn, 0, T1);
    mc_mm(T1, 0, Fi, 1, Cn); /* F^-1 b_e F^-T */
    mc_mat_to_voigt(Cn, hist_new);
    hist_new[6] = h[6] + sqrt(2.0 / 3.0 * dp2);
    hist_new[7] = (double)r.region;
  }
  if (!A) return 0;
  /* theta_ab (a != b) including the factor (e_a - e_b)/(l_a - l_b): see the file comment */
  double th[3][3] = {{0}}, escale = fabs(e[0]) + fabs(e[1]) + fabs(e[2]);
  for (int a = 0; a < 3; a++)
    for (int c = 0; c < 3; c++) {
      if (a == c) continue;
      double x = (lam[a] - lam[c]) / lam[c], gap = 0.5 * log1p(x);
      double ratio = fabs(x) < 1e-8 ? (1 - 0.5 * x + x * x / 3) / (2 * lam[c])
                                    : gap / (lam[a] - lam[c]);
      int lo = a < c ? a : c, hi = a < c ? c : a;
      int edge_pair = (r.region == FEM_MC_EDGE_LEFT && lo == 0 && hi == 1) ||
                      (r.region == FEM_MC_EDGE_RIGHT && lo == 1 && hi == 2);
      double q;
      int from_D = 0; /* D is already the viscous blend */
      if (edge_pair)
        q = 0;
      else if (r.region == FEM_MC_APEX)
        q = m.apex * 2 * m.G; /* the elastic shear modulus' share (apex_stiffness, 0: exact) */
      else if (fabs(gap) <= 1e-12 * escale || gap == 0)
        q = D[3 * a + a] - D[3 * c + a], from_D = 1;
      else
        q = 2 * m.G * (gap - (r.deps_p[a] - r.deps_p[c])) / gap;
      if (m.w > 0 && !from_D) q = (q + m.w * 2 * m.G) / (1 + m.w); /* (inviscid + w elastic) / (1 + w) */
      th[a][c] = q * ratio;
    }
  for (int k = 0; k < 3; k++)
    for (int L = 0; L < 3; L++) {
      /* db = e_k (x) g + g (x) e_k with g = (F C_p^-1) column L; in the eigenbasis
         db'_ab = q_a h_b + h_a q_b, q_a = Q_ka, h = Q^T g */
      double qv[3], hv[3], dbp[3][3], dtp[3][3];
      for (int a = 0; a < 3; a++) {
        qv[a] = Q[3 * k + a];
        hv[a] = Q[a] * FC[L] + Q[3 + a] * FC[3 + L] + Q[6 + a] * FC[6 + L];
      }
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) dbp[a][c] = qv[a] * hv[c] + hv[a] * qv[c];
      for (int a = 0; a < 3; a++) {
        double s = 0;
        for (int c = 0; c < 3; c++) s += D[3 * a + c] * dbp[c][c] / (2 * lam[c]);
        dtp[a][a] = s;
        for (int c = 0; c < 3; c++)
          if (c != a) dtp[a][c] = th[a][c] * dbp[a][c];
      }
      double dt[9], T1[9], dtl[9], dPc[9];
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) dtl[3 * a + c] = dtp[a][c];
      mc_mm(Q, 0, dtl, 0, T1);
      mc_mm(T1, 0, Q, 1, dt);   /* Q dtau' Q^T */
      mc_mm(dt, 0, Fi, 1, dPc); /* dtau F^-T */
      for (int i = 0; i < 3; i++)
        for (int Jj = 0; Jj < 3; Jj++) {
          double v = dPc[3 * i + Jj] - P[3 * i + L] * Fi[3 * Jj + k];
          A[9 * (3 * i + Jj) + 3 * k + L] = v;
        }
    }
  return 0;
}

int fem_mc_hist_init(const FemMohrCoulomb *p, const double tau0[6], double hist[FEM_MC_NHIST])
{
  memset(hist, 0, FEM_MC_NHIST * sizeof *hist);
  hist[0] = hist[1] = hist[2] = 1;
  if (!tau0) return 0;
  for (int i = 0; i < 6; i++)
    SA_REQUIRE(isfinite(tau0[i]), SA_ERR_INPUT, "mohr_coulomb: non-finite initial stress");
  McConst m;
  mc_const(p, &m);
  double T[9], t[3], Q[9];
  mc_voigt_to_mat(tau0, T);
  mc_sym_eig(T, t, Q);
  double f = (t[0] - t[2]) + (t[0] + t[2]) * m.sf - 2 * m.c * m.cf;
  double fscale = fabs(t[0] - t[2]) + fabs(t[0] + t[2]) * m.sf + 2 * m.c * m.cf;
  SA_REQUIRE(f <= 1e-12 * fscale, SA_ERR_INPUT,
             "mohr_coulomb: initial stress (principal %g %g %g Pa) violates the yield "
             "condition, f = %g Pa > 0",
             t[0], t[1], t[2], f);
  double nu = p->poisson, tr = t[0] + t[1] + t[2], be[3], B[9];
  for (int a = 0; a < 3; a++) be[a] = exp(2 * ((1 + nu) * t[a] - nu * tr) / p->young);
  mc_spectral(Q, be, B);
  mc_mat_to_voigt(B, hist);
  return 0;
}

int fem_mc_hist_init_at(const FemMohrCoulomb *p, const double F[9], const double tau0[6],
                        double hist[FEM_MC_NHIST])
{
  double eps_p = hist[6]; /* the equivalent plastic strain so far stays */
  SA_CHECK(fem_mc_hist_init(p, tau0, hist));
  double Fi[9], B[9], T1[9], C[9];
  double J = fem_kt_inv(F, Fi);
  SA_REQUIRE(J > 0 && isfinite(J), SA_ERR_INPUT, "mohr_coulomb: initial stress at det F = %g", J);
  mc_voigt_to_mat(hist, B); /* b_e of tau0 */
  mc_mm(Fi, 0, B, 0, T1);
  mc_mm(T1, 0, Fi, 1, C); /* C_p^-1 = F^-1 b_e F^-T, so that F C_p^-1 F^T = b_e */
  mc_mat_to_voigt(C, hist);
  hist[6] = eps_p;
  return 0;
}

/* ------------------------------------------------------------------ the law object (fem_law.h)
 * Parameters in case-file units: young [Pa], poisson [-], friction_angle [deg], cohesion [Pa],
 * dilation_angle [deg]. Kind FULL (the kernel returns the whole P, pressure included), history
 * FEM_MC_NHIST with C_p^-1 = I at the start (a zero history would be a corrupt C_p^-1), no
 * energy (W = 0: plasticity is not a potential). Symmetric exactly when the flow is associated
 * (dilation_angle == friction_angle); the solver then tries CHOLMOD, else it goes to UMFPACK. */

static FemMohrCoulomb mc_law_params(const double *par)
{
  const double d = M_PI / 180;
  return (FemMohrCoulomb){par[0], par[1], par[2] * d, par[3], par[4] * d, par[5], 0};
}

static void mc_law_init(const double *par, double *hist)
{
  (void)par;
  fem_mc_hist_init(&(FemMohrCoulomb){1, 0, 0, 1, 0, 0, 0}, NULL, hist); /* stress-free: C_p^-1 = I */
}

static int mc_law_eval(const double *par, const FemLawCtx *ctx, const double F[9],
                       const double *hist_old, double *hist_new, double *W, double P[9],
                       double A[81])
{
  FemMohrCoulomb p = mc_law_params(par);
  /* relaxation_time tau > 0: Duvaut-Lions over the evaluation's time step; a state without one
   * (a static solve that stands for no time) is rate-independent */
  if (par[6] > 0 && ctx && ctx->dt > 0) p.tau_over_dt = par[6] / ctx->dt;
  *W = 0;
  int rc = fem_mc_eval(&p, F, hist_old, hist_new, P, A, NULL);
  return rc == SA_ERR_NOT_CONVERGED ? SA_ERR_DOMAIN : rc; /* recoverable either way */
}

/* The case keys' names and units in the messages ([fill] friction_angle in deg ...). */
static int mc_law_check(const double *par)
{
  SA_REQUIRE(isfinite(par[0]) && par[0] > 0, SA_ERR_INPUT,
             "mohr_coulomb: young = %g Pa must be > 0", par[0]);
  SA_REQUIRE(isfinite(par[1]) && par[1] > -1 && par[1] < 0.5, SA_ERR_INPUT,
             "mohr_coulomb: poisson = %g must be in (-1, 0.5)", par[1]);
  SA_REQUIRE(isfinite(par[2]) && par[2] >= 0 && par[2] < 90, SA_ERR_INPUT,
             "mohr_coulomb: friction_angle = %g deg must be in [0, 90)", par[2]);
  SA_REQUIRE(isfinite(par[3]) && par[3] >= 0, SA_ERR_INPUT,
             "mohr_coulomb: cohesion = %g Pa must be >= 0", par[3]);
  SA_REQUIRE(par[2] > 0 || par[3] > 0, SA_ERR_INPUT,
             "mohr_coulomb: cohesion must be > 0 when friction_angle = 0 (no strength at all)");
  SA_REQUIRE(isfinite(par[4]) && par[4] >= 0 && par[4] <= par[2], SA_ERR_INPUT,
             "mohr_coulomb: dilation_angle = %g deg must be in [0, friction_angle = %g deg]",
             par[4], par[2]);
  SA_REQUIRE(isfinite(par[5]) && par[5] >= 0 && par[5] <= 1, SA_ERR_INPUT,
             "mohr_coulomb: apex_stiffness = %g must be in [0, 1]", par[5]);
  SA_REQUIRE(isfinite(par[6]) && par[6] >= 0, SA_ERR_INPUT,
             "mohr_coulomb: relaxation_time = %g s must be >= 0", par[6]);
  FemMohrCoulomb p = mc_law_params(par);
  return fem_mc_check(&p);
}

static int mc_law_symmetric(const double *par) { return par[4] == par[2]; }

static double mc_law_mu0(const double *par) { return par[0] / (2 * (1 + par[1])); }

static const char *const mc_law_names[] = {"young", "poisson", "friction_angle", "cohesion",
                                           "dilation_angle", "apex_stiffness",
                                           "relaxation_time"};
static const double mc_law_defaults[] = {NAN, NAN, NAN, NAN, NAN, 0, 0};
const FemLaw fem_law_mohr_coulomb = {"mohr_coulomb", 7, mc_law_names, FEM_MC_NHIST, 0,
                                     FEM_LAW_FULL, mc_law_init, mc_law_eval, mc_law_check,
                                     mc_law_mu0, mc_law_symmetric, mc_law_defaults};
