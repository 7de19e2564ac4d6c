/* test_mohr_coulomb_return.c - principal-stress return mapping of the Mohr-Coulomb kernel
 * against hand-built closed forms (tension positive, s1 >= s2 >= s3):
 *  - every plastic trial is built backwards from its answer: a point s* on the plane, on the left
 *    (s1 = s2) or right (s2 = s3) edge, or the apex c cot(phi) (1,1,1), plus D times a positive
 *    combination of the flow vectors n_ij = (1 + sin psi) e_i - (1 - sin psi) e_j; the return must
 *    give back s*, the region and the multipliers, f = 0 on every active plane (1e-10 of the
 *    stress scale), and D^-1 (s^T - s) = dg_a n_a + dg_b n_b (flow direction, to 1e-9);
 *  - plane: dg = f(s^T) / [4 G (1 + sin phi sin psi / 3) + 4 K sin phi sin psi] (de Souza Neto
 *    et al. 2008 eq. 8.41, written independently of the kernel's dot products);
 *  - apex stress c cos(phi) / sin(phi) (hydrostatic), zero tangent;
 *  - consistent tangent d s / d e^T against central differences, step 1e-8 on strains of order
 *    1e-3 (the return is piecewise linear, so only round-off, ~1e-11 relative, remains); tol 1e-6;
 *  - symmetry of the tangent for psi = phi, asymmetry for psi < phi;
 *  - 20000 random trials (any region, any order): return code 0, admissible result, ordering kept;
 *  - associated and non-associated flow, c = 0, and phi = 0 (Tresca, no apex);
 *  - fem_mc_check rejects each bad parameter with a message naming it.
 * Pass -v to print the largest errors (reported in docs/mohr_coulomb.md). */
#include <stdio.h>
#include <string.h>

#include "fem_mohr_coulomb.h"
#include "kt_util.h"
#include "sa_error.h"

static int verbose = 0;
static double err_s[5], err_fd[5], err_dg[5], err_flow[5]; /* per region, relative */

typedef struct {
  double G, K, lam, sf, cf, sp;
} Consts;

static Consts consts(const FemMohrCoulomb *p)
{
  Consts k;
  k.G = p->young / (2 * (1 + p->poisson));
  k.K = p->young / (3 * (1 - 2 * p->poisson));
  k.lam = k.K - 2 * k.G / 3;
  k.sf = sin(p->phi), k.cf = cos(p->phi), k.sp = sin(p->psi);
  return k;
}

static void Dv(const Consts *k, const double v[3], double o[3])
{
  double tr = v[0] + v[1] + v[2];
  for (int i = 0; i < 3; i++) o[i] = k->lam * tr + 2 * k->G * v[i];
}

/* e = D^-1 s = ((1 + nu) s - nu tr(s) 1) / E */
static void compliance(const FemMohrCoulomb *p, const double s[3], double e[3])
{
  double tr = s[0] + s[1] + s[2], nu = p->poisson;
  for (int i = 0; i < 3; i++) e[i] = ((1 + nu) * s[i] - nu * tr) / p->young;
}

/* plane ij of the yield function and the flow vector n_ij */
static double f_ij(const FemMohrCoulomb *p, const double s[3], int i, int j)
{
  return (s[i] - s[j]) + (s[i] + s[j]) * sin(p->phi) - 2 * p->c * cos(p->phi);
}

static double f_max(const FemMohrCoulomb *p, const double s[3])
{
  double f = -INFINITY;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      if (i != j && f_ij(p, s, i, j) > f) f = f_ij(p, s, i, j);
  return f;
}

static void n_ij(double sn, int i, int j, double n[3])
{
  n[0] = n[1] = n[2] = 0;
  n[i] = 1 + sn, n[j] = -(1 - sn);
}

static void track(double *e, double v)
{
  if (v > *e) *e = v;
}

/* Return of trial strain e (shuffled by a random permutation), checked against s_ref,
 * region and multipliers; FD check of the tangent. */
static void check_case(const char *name, const FemMohrCoulomb *p, const double sT[3],
                       const double s_ref[3], FemMcRegion region, double dga, double dgb)
{
  char what[200];
  Consts k = consts(p);
  int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  int *o = perm[(int)kt_rand(0, 6) % 6];
  double eT_sorted[3], eT[3], sref[3], s[3], D[9];
  compliance(p, sT, eT_sorted);
  for (int a = 0; a < 3; a++) eT[o[a]] = eT_sorted[a], sref[o[a]] = s_ref[a];
  FemMcReturn info;
  int rc = fem_mc_return_principal(p, eT, s, D, &info);
  if (rc) {
    fprintf(stderr, "%s: return failed (%d): %s\n", name, rc, sa_error_message());
    sa_error_clear();
    kt_fail++;
    return;
  }
  if (info.region != region) {
    fprintf(stderr, "%s: region %d, expected %d\n", name, (int)info.region, (int)region);
    kt_fail++;
  }
  double scale = kt_maxabs(sT, 3) + p->c;
  for (int a = 0; a < 3; a++) {
    snprintf(what, sizeof what, "%s: s[%d] vs closed form", name, a);
    kt_close(what, s[a], sref[a], 1e-10 * scale, 0);
    track(&err_s[region], fabs(s[a] - sref[a]) / scale);
  }
  /* f = 0 on the active planes (sorted indices 0 = s1, 2 = s3) */
  double ss[3] = {s[o[0]], s[o[1]], s[o[2]]};
  if (region != FEM_MC_ELASTIC) {
    snprintf(what, sizeof what, "%s: f13 on the surface", name);
    kt_close(what, f_ij(p, ss, 0, 2), 0, 1e-10 * scale, 0);
  }
  if (region == FEM_MC_EDGE_LEFT) {
    snprintf(what, sizeof what, "%s: f23 on the surface", name);
    kt_close(what, f_ij(p, ss, 1, 2), 0, 1e-10 * scale, 0);
  }
  if (region == FEM_MC_EDGE_RIGHT) {
    snprintf(what, sizeof what, "%s: f12 on the surface", name);
    kt_close(what, f_ij(p, ss, 0, 1), 0, 1e-10 * scale, 0);
  }
  snprintf(what, sizeof what, "%s: admissible", name);
  kt_close(what, f_max(p, s) > 0 ? f_max(p, s) : 0, 0, 1e-10 * scale, 0);
  /* multipliers and flow direction */
  if (region == FEM_MC_PLANE || region == FEM_MC_EDGE_LEFT || region == FEM_MC_EDGE_RIGHT) {
    snprintf(what, sizeof what, "%s: dgamma_a", name);
    kt_close(what, info.dgamma[0], dga, 1e-9 * (dga + dgb), 0);
    snprintf(what, sizeof what, "%s: dgamma_b", name);
    kt_close(what, info.dgamma[1], dgb, 1e-9 * (dga + dgb), 0);
    track(&err_dg[region], (fabs(info.dgamma[0] - dga) + fabs(info.dgamma[1] - dgb)) / (dga + dgb));
    double na[3], nb[3] = {0, 0, 0}, ds[3], dep[3];
    n_ij(k.sp, 0, 2, na);
    if (region == FEM_MC_EDGE_LEFT) n_ij(k.sp, 1, 2, nb);
    if (region == FEM_MC_EDGE_RIGHT) n_ij(k.sp, 0, 1, nb);
    for (int a = 0; a < 3; a++) ds[a] = sT[a] - ss[a];
    compliance(p, ds, dep);
    double emax = kt_maxabs(dep, 3);
    for (int a = 0; a < 3; a++) {
      double ref = info.dgamma[0] * na[a] + info.dgamma[1] * nb[a];
      snprintf(what, sizeof what, "%s: D^-1 (sT - s)[%d] = dg_a n_a + dg_b n_b", name, a);
      kt_close(what, dep[a], ref, 1e-9 * emax, 0);
      snprintf(what, sizeof what, "%s: deps_p[%d]", name, a);
      kt_close(what, info.deps_p[o[a]], ref, 1e-9 * emax, 0);
      track(&err_flow[region], fabs(dep[a] - ref) / emax);
    }
    if (region == FEM_MC_PLANE) { /* de Souza Neto eq. 8.41 */
      double sf = sin(p->phi), sp = sin(p->psi), fT = f_ij(p, sT, 0, 2);
      double dg = fT / (4 * k.G * (1 + sf * sp / 3) + 4 * k.K * sf * sp);
      snprintf(what, sizeof what, "%s: dgamma vs closed form", name);
      kt_close(what, info.dgamma[0], dg, 0, 1e-11);
    }
  }
  if (region == FEM_MC_APEX) {
    double pa = p->c * cos(p->phi) / sin(p->phi);
    for (int a = 0; a < 3; a++) {
      snprintf(what, sizeof what, "%s: apex stress c cot(phi)", name);
      kt_close(what, s[a], pa, 1e-12 * scale, 0);
      snprintf(what, sizeof what, "%s: apex tangent", name);
      kt_close(what, kt_maxabs(D, 9), 0, 0, 0);
    }
    /* apex_stiffness a: the same stress, tangent a (lambda 1 (x) 1 + 2 G I) */
    FemMohrCoulomb pax = *p;
    pax.apex_stiffness = 0.25;
    double sa[3], Da[9];
    fem_mc_return_principal(&pax, eT, sa, Da, NULL);
    for (int a = 0; a < 3; a++) {
      snprintf(what, sizeof what, "%s: apex stress with apex_stiffness", name);
      kt_close(what, sa[a], s[a], 0, 0);
      for (int b = 0; b < 3; b++) {
        snprintf(what, sizeof what, "%s: apex tangent with apex_stiffness [%d][%d]", name, a, b);
        kt_close(what, Da[3 * a + b], 0.25 * (k.lam + (a == b ? 2 * k.G : 0)),
                 1e-14 * (k.lam + 2 * k.G), 0);
      }
    }
  }
  /* tangent by central differences (piecewise linear: round-off only) */
  double Dmax = 2 * k.G + 3 * k.K, h = 1e-8, fd_err = 0;
  for (int b = 0; b < 3; b++) {
    double ep[3], em[3], sp[3], sm[3];
    memcpy(ep, eT, sizeof ep), memcpy(em, eT, sizeof em);
    ep[b] += h, em[b] -= h;
    fem_mc_return_principal(p, ep, sp, NULL, NULL);
    fem_mc_return_principal(p, em, sm, NULL, NULL);
    for (int a = 0; a < 3; a++) {
      double fd = (sp[a] - sm[a]) / (2 * h);
      snprintf(what, sizeof what, "%s: D[%d][%d] vs FD", name, a, b);
      kt_close(what, D[3 * a + b], fd, 1e-6 * Dmax, 0);
      if (fabs(D[3 * a + b] - fd) / Dmax > fd_err) fd_err = fabs(D[3 * a + b] - fd) / Dmax;
    }
  }
  track(&err_fd[region], fd_err);
  double asym = 0;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) asym = fmax(asym, fabs(D[3 * a + b] - D[3 * b + a]) / Dmax);
  if (fem_mc_symmetric(p) && asym > 1e-12) {
    fprintf(stderr, "%s: associated flow but unsymmetric tangent (%g)\n", name, asym);
    kt_fail++;
  }
  if (!fem_mc_symmetric(p) && region == FEM_MC_PLANE && asym < 1e-6 * p->phi) {
    fprintf(stderr, "%s: non-associated flow but symmetric tangent\n", name);
    kt_fail++;
  }
}

/* x on f13 = 0 for s3 = y: x = (2 c cos phi + y (1 - sin phi)) / (1 + sin phi) */
static double plane_x(const FemMohrCoulomb *p, double y)
{
  return (2 * p->c * cos(p->phi) + y * (1 - sin(p->phi))) / (1 + sin(p->phi));
}

static void check_material(const char *name, const FemMohrCoulomb *p)
{
  char what[160];
  if (fem_mc_check(p)) {
    fprintf(stderr, "%s: valid parameters rejected: %s\n", name, sa_error_message());
    sa_error_clear();
    kt_fail++;
    return;
  }
  Consts k = consts(p);
  for (int trial = 0; trial < 20; trial++) {
    double y = -kt_rand(5e3, 200e3), x = plane_x(p, y), st[3], sT[3], d1[3], d2[3], n1[3], n2[3];
    double ta = kt_rand(1e-4, 5e-3), tb = ta * kt_rand(0.05, 0.95);
    /* elastic: a point strictly inside (scaled towards the mean of a surface point) */
    double s_in[3] = {x, y + 0.3 * (x - y), y}, m = y; /* y (1,1,1) is strictly inside */
    for (int a = 0; a < 3; a++) s_in[a] = m + 0.7 * (s_in[a] - m);
    snprintf(what, sizeof what, "%s elastic %d", name, trial);
    check_case(what, p, s_in, s_in, FEM_MC_ELASTIC, 0, 0);
    /* plane */
    double w = kt_rand(0.1, 0.9);
    double sp_[3] = {x, y + w * (x - y), y};
    n_ij(k.sp, 0, 2, n1), Dv(&k, n1, d1);
    for (int a = 0; a < 3; a++) sT[a] = sp_[a] + ta * d1[a];
    snprintf(what, sizeof what, "%s plane %d", name, trial);
    check_case(what, p, sT, sp_, FEM_MC_PLANE, ta, 0);
    /* left edge (triaxial compression) s1 = s2 */
    st[0] = st[1] = x, st[2] = y;
    n_ij(k.sp, 1, 2, n2), Dv(&k, n2, d2);
    for (int a = 0; a < 3; a++) sT[a] = st[a] + ta * d1[a] + tb * d2[a];
    snprintf(what, sizeof what, "%s left edge %d", name, trial);
    check_case(what, p, sT, st, FEM_MC_EDGE_LEFT, ta, tb);
    /* right edge (triaxial extension) s2 = s3 */
    st[0] = x, st[1] = st[2] = y;
    n_ij(k.sp, 0, 1, n2), Dv(&k, n2, d2);
    for (int a = 0; a < 3; a++) sT[a] = st[a] + ta * d1[a] + tb * d2[a];
    snprintf(what, sizeof what, "%s right edge %d", name, trial);
    check_case(what, p, sT, st, FEM_MC_EDGE_RIGHT, ta, tb);
    if (p->phi > 0) {
      /* apex: apex + D (positive combination of all six flow vectors) */
      double pa = p->c * k.cf / k.sf, ap[3] = {pa, pa, pa}, v[3] = {0, 0, 0}, n[3], dv[3];
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          if (i != j) {
            n_ij(k.sp, i, j, n);
            double wij = kt_rand(0, 3e-3);
            for (int a = 0; a < 3; a++) v[a] += wij * n[a];
          }
      Dv(&k, v, dv);
      for (int a = 0; a < 3; a++) sT[a] = pa + dv[a];
      if (k.sp > 0) { /* inside the flow-consistent cone only when psi > 0 */
        snprintf(what, sizeof what, "%s apex %d", name, trial);
        check_case(what, p, (double[3]){fmax(fmax(sT[0], sT[1]), sT[2]),
                                        sT[0] + sT[1] + sT[2] - fmax(fmax(sT[0], sT[1]), sT[2]) -
                                            fmin(fmin(sT[0], sT[1]), sT[2]),
                                        fmin(fmin(sT[0], sT[1]), sT[2])},
                   ap, FEM_MC_APEX, 0, 0);
      }
      /* hydrostatic tension beyond the apex: the tension cut for any psi */
      double ph = pa + kt_rand(1e3, 1e5), sh[3] = {ph, ph, ph};
      snprintf(what, sizeof what, "%s apex hydrostatic %d", name, trial);
      check_case(what, p, sh, ap, FEM_MC_APEX, 0, 0);
    }
  }
  /* random sweep: every trial resolves to an admissible, order-preserving state */
  for (int trial = 0; trial < 20000; trial++) {
    double e[3], s[3], D[9], amp = pow(10, kt_rand(-6, -1));
    for (int a = 0; a < 3; a++) e[a] = kt_rand(-amp, amp);
    if (trial % 7 == 0) e[1] = e[0];
    if (trial % 11 == 0) e[2] = e[1];
    FemMcReturn info;
    int rc = fem_mc_return_principal(p, e, s, D, &info);
    if (rc) {
      if (kt_fail < 40)
        fprintf(stderr, "%s sweep %d: rc %d: %s\n", name, trial, rc, sa_error_message());
      sa_error_clear();
      kt_fail++;
      continue;
    }
    double scale = 2 * k.G * kt_maxabs(e, 3) + 3 * k.K * kt_maxabs(e, 3) + p->c, f = f_max(p, s);
    snprintf(what, sizeof what, "%s sweep %d: admissible", name, trial);
    kt_close(what, f > 0 ? f : 0, 0, 1e-10 * scale, 0);
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++)
        if (e[a] > e[b] && s[a] < s[b] - 1e-10 * scale) {
          fprintf(stderr, "%s sweep %d: order of stresses not that of strains\n", name, trial);
          kt_fail++;
        }
    if (info.dgamma[0] < 0 || info.dgamma[1] < 0) {
      fprintf(stderr, "%s sweep %d: negative multiplier\n", name, trial);
      kt_fail++;
    }
  }
}

static void expect_bad(const char *what, FemMohrCoulomb p, const char *param)
{
  int rc = fem_mc_check(&p);
  if (rc != SA_ERR_INPUT || !strstr(sa_error_message(), param)) {
    fprintf(stderr, "bad %s: rc %d, message '%s' (should name '%s')\n", what, rc,
            sa_error_message(), param);
    kt_fail++;
  }
  sa_error_clear();
}

int main(int argc, char **argv)
{
  verbose = argc > 1 && !strcmp(argv[1], "-v");
  const double deg = M_PI / 180;
  FemMohrCoulomb assoc = {20e6, 0.3, 30 * deg, 10e3, 30 * deg, 0, 0};
  FemMohrCoulomb nonassoc = {20e6, 0.3, 30 * deg, 10e3, 10 * deg, 0, 0};
  FemMohrCoulomb psi0 = {20e6, 0.25, 40 * deg, 1e3, 0, 0, 0};
  FemMohrCoulomb cohesionless = {5e6, 0.2, 35 * deg, 0, 35 * deg, 0, 0};
  FemMohrCoulomb cohesionless_na = {5e6, 0.2, 35 * deg, 0, 5 * deg, 0, 0};
  FemMohrCoulomb tresca = {20e6, 0.45, 0, 10e3, 0, 0, 0};
  FemMohrCoulomb steep = {20e6, 0.3, 60 * deg, 50e3, 45 * deg, 0, 0};
  check_material("associated", &assoc);
  check_material("non-associated", &nonassoc);
  check_material("psi = 0", &psi0);
  check_material("c = 0", &cohesionless);
  check_material("c = 0 non-associated", &cohesionless_na);
  check_material("Tresca (phi = 0)", &tresca);
  check_material("phi = 60 deg", &steep);

  FemMohrCoulomb g = assoc, b;
  b = g, b.phi = -0.1, expect_bad("phi < 0", b, "phi");
  b = g, b.phi = M_PI / 2, expect_bad("phi = 90 deg", b, "phi");
  b = g, b.psi = g.phi + 0.01, expect_bad("psi > phi", b, "psi");
  b = g, b.psi = -0.01, expect_bad("psi < 0", b, "psi");
  b = g, b.poisson = 0.5, expect_bad("poisson = 0.5", b, "poisson");
  b = g, b.poisson = -1, expect_bad("poisson = -1", b, "poisson");
  b = g, b.young = 0, expect_bad("young = 0", b, "young");
  b = g, b.young = -1, expect_bad("young < 0", b, "young");
  b = g, b.c = -1, expect_bad("c < 0", b, "c =");
  b = g, b.c = 0, b.phi = b.psi = 0, expect_bad("c = 0 with phi = 0", b, "c =");
  b = g, b.young = NAN, expect_bad("young NaN", b, "young");
  b = g, b.apex_stiffness = -0.1, expect_bad("apex_stiffness < 0", b, "apex_stiffness");
  b = g, b.apex_stiffness = 1.5, expect_bad("apex_stiffness > 1", b, "apex_stiffness");

  if (verbose) {
    const char *rn[5] = {"elastic", "plane", "right edge", "left edge", "apex"};
    for (int r = 0; r < 5; r++)
      printf("%-10s  stress %.2e  dgamma %.2e  flow %.2e  tangent-FD %.2e\n", rn[r], err_s[r],
             err_dg[r], err_flow[r], err_fd[r]);
  }
  if (kt_fail) fprintf(stderr, "%d checks failed\n", kt_fail);
  return kt_fail != 0;
}
