/* test_fill_k0 - the K0 initial stress of the Mohr-Coulomb fill (fem_fill_k0_stress) in a
 * rigid frictionless tube under gravity: the settled state keeps the imposed lateral ratio.
 *
 * Model: the Janssen test's column (tests/fem/solver/test_contact_janssen.c): tube D = 16 mm,
 * fill H = 52 mm, tet4 6 x 6 x 24, density 1550 kg/m^3, E = 20 MPa, nu = 0.3, the actuator's
 * Mohr-Coulomb fill (phi 28 deg, c 100 Pa, psi 3 deg); wall: rigid frictionless cylinder,
 * penalty alpha E / h; floor: rollers. The fill starts at F = I with sv = -rho g (H - z) and
 * sh = K0 sv (Jaky, K0 = 1 - sin 28 deg = 0.531, inside the Rankine range 0.361 .. 2.77, so
 * elastic), then gravity is switched on and the state is solved.
 *
 * References (independent of the code):
 *  - equilibrium of a slice with a frictionless wall: the slice-averaged vertical stress is
 *    rho g depth; checked to 2 % over the slices below the top one (the top slice's stress is
 *    piecewise constant per element, sampled at the centroids);
 *  - lateral ratio: sigma_v is fixed by slice equilibrium, and the wall pressure needs a
 *    penetration u_r = p_w / eps_N; the radial expansion e = u_r / R at fixed sigma_v (the
 *    axial strain free, -2 lambda e / (lambda + 2 G)) relieves the lateral stress by
 *    2 G (3 lambda + 2 G) / (lambda + 2 G) e = E / (1 - nu) e (linear elasticity), so
 *    K = p_w / sv = K0 / (1 + E / ((1 - nu) eps_N R)) (0.511 for alpha = 10); the mean over the
 *    slices away from the top and the floor within 3 %;
 *  - the same column started stress-free settles to the confined-elastic ratio (about nu /
 *    (1 - nu) = 0.43, test_contact_janssen): the K0 run's ratio must differ from it by more than
 *    its 3 % tolerance, so the test sees the initial stress and not the elasticity;
 *  - a K0 below the active Rankine ratio (0.2) is refused with SA_ERR_INPUT;
 *  - fem_mc_hist_init_at (the K0 procedure on a deformed fill): at a general F the law returns
 *    the imposed Kirchhoff stress to 1e-9 relative and keeps the plastic strain.
 * K0_VERBOSE=1 prints the profile. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cutil.h"
#include "fem.h"
#include "fem_contact.h"
#include "fem_fill.h"
#include "fem_law.h"
#include "fem_mohr_coulomb.h"
#include "sa_error.h"
#include "sa_log.h"
#include "tutil.h"

#define NBIN 13

static const double D = 16e-3, H = 52e-3, RHO = 1550, G = 9.81, E = 20e6, NU = 0.3;

static double tet_vol(const double *X, const int *c) {
  double a[3], b[3], d[3];
  for (int i = 0; i < 3; i++) {
    a[i] = X[3 * c[1] + i] - X[3 * c[0] + i];
    b[i] = X[3 * c[2] + i] - X[3 * c[0] + i];
    d[i] = X[3 * c[3] + i] - X[3 * c[0] + i];
  }
  return fabs(a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
              a[2] * (b[0] * d[1] - b[1] * d[0])) / 6;
}

/* k0 < 0: no initial stress. Returns the mean lateral ratio in *K, the largest slice error of
 * sigma_v against rho g depth (relative) in *sv_err, the closed-form K in *K_cf; -1 when the
 * initial stress was refused with SA_ERR_INPUT. */
static int column(double k0, double *K, double *sv_err, double *K_cf) {
  double cc[3] = {0.5 * D, H, 0};
  SmeshBlock b = {{6, 6, 24}, cu_map_cyl, cc, {"s0", "s1", "s2", "s3", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &b, 1, 1e-12, &m));
  FemFillParams fp = {.friction_angle = 28, .cohesion = 100, .dilation_angle = 3, .young = E,
                      .poisson = NU, .density = RHO};
  FemMaterial mat;
  TU_CHECK(fem_fill_material(&fp, &mat));
  FemSolverParams prm = fem_solver_params_default();
  prm.rtol = 1e-9;
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  double h = H / 24;
  FemContactParams cp = fem_contact_params_default();
  cp.penalty = 10.0 * E / h;
  cp.friction = 0;
  FemContact *wall[4];
  TU_CHECK(cu_tube_setup(m, s, &cp, 0.5 * D, wall));
  TU_CHECK(fem_solver_fix_surface(s, "bottom", FEM_Z));
  TU_CHECK(fem_solver_setup(s));
  int rc = 0;
  if (k0 >= 0) {
    int nset = 0;
    rc = fem_fill_k0_stress(s, 0, &fp, H, k0, G, &nset);
    if (rc == SA_ERR_INPUT) {
      fprintf(stderr, "k0 = %g refused as expected: %s\n", k0, sa_error_message());
      sa_error_clear();
    } else {
      TU_CHECK(rc);
      if (nset != m->nelem) {
        fprintf(stderr, "k0: %d of %d elements stressed\n", nset, m->nelem);
        rc = 1;
      }
    }
  }
  if (!rc) {
    TU_CHECK(fem_solver_set_gravity(s, (double[3]){0, 0, -G}));
    TU_CHECK(fem_solver_solve(s));
    double area_b[NBIN] = {0}, pn_b[NBIN] = {0}, binh = H / NBIN;
    for (int k = 0; k < 4; k++) {
      const int *node;
      const double *area, *tn;
      int ns = fem_contact_slaves(wall[k], &node, &area, NULL, &tn, NULL, NULL);
      for (int i = 0; i < ns; i++) {
        int q = (int)floor((H - m->xyz[3 * node[i] + 2]) / binh);
        q = q < 0 ? 0 : q >= NBIN ? NBIN - 1 : q;
        area_b[q] += area[i];
        pn_b[q] += area[i] * tn[i];
      }
    }
    double *sig = malloc(sizeof(double) * 9 * m->nelem);
    TU_CHECK(fem_solver_element_stress(s, sig, NULL, NULL));
    double sv_b[NBIN] = {0}, vol_b[NBIN] = {0}, dep_b[NBIN] = {0};
    for (int e = 0; e < m->nelem; e++) {
      const int *c = m->conn + 4 * e;
      double zc = 0;
      for (int a = 0; a < 4; a++) zc += 0.25 * m->xyz[3 * c[a] + 2];
      int q = (int)floor((H - zc) / binh);
      double v = tet_vol(m->xyz, c);
      sv_b[q] -= v * sig[9 * e + 8];
      vol_b[q] += v;
      dep_b[q] += v * (H - zc);
    }
    free(sig);
    double Km = 0, err = 0, svm = 0;
    int nK = 0;
    for (int q = 0; q < NBIN; q++) {
      double sv = sv_b[q] / vol_b[q], ref = RHO * G * dep_b[q] / vol_b[q];
      double pw = pn_b[q] / area_b[q];
      if (q >= 1) err = fmax(err, fabs(sv - ref) / ref);
      if (q >= 2 && q < NBIN - 2) Km += pw / sv, svm += sv, nK++;
      if (getenv("K0_VERBOSE"))
        fprintf(stderr, "  depth %6.2f mm  sigma_v %9.3f Pa (rho g depth %9.3f)  p_w %9.3f  K %.4f\n",
                1e3 * dep_b[q] / vol_b[q], sv, ref, pw, pw / sv);
    }
    *K = Km / nK;
    *sv_err = err;
    /* the wall's compliance, c = 1 / (eps_N R): the expansion e = p_w c at fixed sigma_v (slice
     * equilibrium) relieves the lateral stress by E / (1 - nu) e (eps_z free) */
    double c = 1 / (cp.penalty * 0.5 * D), kk = k0 > 0 ? k0 : fem_fill_k0_jaky(28);
    *K_cf = kk / (1 + E / (1 - NU) * c);
    (void)svm;
  }
  fem_solver_destroy(&s);
  for (int k = 0; k < 4; k++) fem_contact_destroy(&wall[k]);
  smesh_free(&m);
  return rc == SA_ERR_INPUT ? -1 : rc;
}

/* fem_mc_hist_init_at: a point given tau0 at a deformed F carries tau0 there (the law's P F^T
 * is the Kirchhoff stress; the state is elastic, so no return changes it), and keeps its
 * equivalent plastic strain. */
static int hist_at_check(void) {
  const FemLaw *law = fem_law_find("mohr_coulomb");
  double par[5] = {E, NU, 28, 100, 3};
  FemMohrCoulomb mc = {E, NU, 28 * M_PI / 180, 100, 3 * M_PI / 180, 0, 0};
  /* a general F near the settled fill's (stretch, shear, rotation by 0.3 rad about x) */
  double c = cos(0.3), sn = sin(0.3), U[9] = {1 + 2e-4, 3e-5, -1e-5, 3e-5, 1 - 1e-4, 2e-5, -1e-5, 2e-5, 1 - 3e-4};
  double R[9] = {1, 0, 0, 0, c, -sn, 0, sn, c}, F[9], tau0[6] = {-300, -350, -600, 20, -10, 15};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      F[3 * i + j] = 0;
      for (int k = 0; k < 3; k++) F[3 * i + j] += R[3 * i + k] * U[3 * k + j];
    }
  double h[FEM_MC_NHIST] = {0}, hn[FEM_MC_NHIST], W, P[9], A[81];
  h[6] = 0.0123;
  TU_CHECK(fem_mc_hist_init_at(&mc, F, tau0, h));
  TU_CHECK(law->eval(par, NULL, F, h, hn, &W, P, A));
  /* tau = P F^T in Voigt xx, yy, zz, yz, xz, xy */
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      T[3 * i + j] = 0;
      for (int k = 0; k < 3; k++) T[3 * i + j] += P[3 * i + k] * F[3 * j + k];
    }
  double tv[6] = {T[0], T[4], T[8], T[5], T[2], T[1]}, err = 0;
  for (int k = 0; k < 6; k++) err = fmax(err, fabs(tv[k] - tau0[k]));
  fprintf(stderr, "hist_init_at: max |tau - tau0| = %.3g Pa at a rotated, stretched F\n", err);
  int fail = tu_close("hist_init_at: Kirchhoff stress at F vs imposed, max |diff| / 600 Pa",
                      err / 600, 0, 1e-9, 0);
  fail |= tu_close("hist_init_at: equivalent plastic strain kept", h[6], 0.0123, 0, 0);
  return fail;
}

int main(void) {
  sa_log_set_level(getenv("K0_VERBOSE") ? SA_LOG_INFO : SA_LOG_WARN);
  int fail = hist_at_check();
  double K0 = fem_fill_k0_jaky(28), ka, kp;
  fem_fill_rankine(28, &ka, &kp);
  fail |= tu_close("Jaky K0 = 1 - sin 28 deg", K0, 1 - sin(28 * M_PI / 180), 1e-14, 0);
  fail |= tu_close("Rankine active (1 - sin) / (1 + sin)", ka, 0.36103, 0, 1e-4);
  double K, err, Kcf, Kel, err_el, dummy;
  if (column(0, &K, &err, &Kcf)) return 1;
  fprintf(stderr, "K0 column: K = %.4f (closed form %.4f, Jaky %.4f), max |sigma_v - rho g "
          "depth| / rho g depth %.4f\n", K, Kcf, K0, err);
  fail |= tu_close("K0 column: slice sigma_v vs rho g depth (relative)", err, 0, 0.02, 0);
  fail |= tu_close("K0 column: lateral ratio vs K0 with the wall compliance", K, Kcf, 0, 0.03);
  if (column(-1, &Kel, &err_el, &dummy)) return 1;
  fprintf(stderr, "stress-free column: K = %.4f (nu/(1-nu) = %.4f)\n", Kel, NU / (1 - NU));
  if (!(fabs(Kel - K) > 0.03 * K)) {
    fprintf(stderr, "the stress-free column's K %.4f is within 3 %% of the K0 column's %.4f: the "
            "test cannot tell the initial stress from the elasticity\n", Kel, K);
    fail = 1;
  }
  if (column(0.2, &K, &err, &Kcf) != -1) {
    fprintf(stderr, "k0 = 0.2 (below the active ratio %.4f) was not refused\n", ka);
    fail = 1;
  }
  return fail;
}
