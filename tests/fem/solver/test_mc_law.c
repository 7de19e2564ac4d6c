/* test_mc_law - the Mohr-Coulomb kernel as the law object "mohr_coulomb" (fem_law.h) through the
 * element, the assembly, the Newton solver and the linear-solver choice.
 *
 * Model: a unit cube of 2 x 2 x 2 Kuhn-split cells (48 tet10) whose whole boundary is prescribed
 * to u = (F - I) X with F = diag(1 + ux, 1 + uy, 1 + uz) (ramped linearly by the solver). The
 * exact solution is homogeneous, so every quadrature point must carry the kernel's answer for
 * that F. (Rollers with free tangential motion are not enough: on an edge of the yield surface
 * the tangent has no stiffness for shear in the plane of the two equal principal stresses, and
 * the elements then shear freely.) The ramp is substepped by the solver (path-dependent plasticity),
 * so the reference runs the kernel fem_mc_eval in lockstep: a monitor called after every
 * converged substep reads F from the positions, evaluates the kernel from the reference
 * history, and compares with the solver's element stress and read-back history.
 *  1. Stress (Cauchy = tau / J) against the kernel: |diff| <= 1e-8 max|sigma| (Newton stops at
 *     rtol 1e-10, the homogeneous state is reproduced to that level).
 *  2. History (C_p^-1 and equivalent plastic strain) against the kernel: 1e-8.
 *  3. fem_solver_check_tangent at a trial state INSIDE the plastic region (the first Newton
 *     trial of a substep, taken in the domain hook): the converged state itself sits on the
 *     yield surface, where central differences straddle the elastic/plastic kink. Error <= 1e-6
 *     (h = 1e-8 on displacements of 1e-2: truncation ~h^2 |A''|, round-off 1e-16/h relative).
 *  4. Solver choice follows the law's flag: non-associated (psi < phi) factorises by UMFPACK only
 *     (no CHOLMOD attempt); associated flow goes through the symmetric path (CHOLMOD first).
 *  5. Paths that end on the plane (distinct lateral strains) and on the compression edge (equal
 *     lateral strains), associated and non-associated, and Tresca (phi = 0): the final region
 *     read back from the history is the one the path was built for.
 *  6. The law's parameter check names the case key: friction_angle 95 deg, cohesion -1,
 *     dilation_angle > friction_angle. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "fem_law.h"
#include "fem_mohr_coulomb.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static void map_cube(const double xi[3], const void *ctx, double X[3]) {
  (void)ctx;
  for (int k = 0; k < 3; k++) X[k] = xi[k];
}

typedef struct {
  FemMohrCoulomb p;
  double hist[FEM_MC_NHIST];
  double err_sig, err_hist, tan_err;
  int tan_checked, ncalls, nsteps;
  const FemMesh *m;
} Ref;

/* F of the homogeneous state from the corner (1, 1, 1). */
static void corner_F(const FemSolver *s, const FemMesh *m, double F[9]) {
  const double *x = fem_solver_positions(s);
  int c = -1;
  for (int a = 0; a < m->nnodes; a++)
    if (m->xyz[3 * a] == 1 && m->xyz[3 * a + 1] == 1 && m->xyz[3 * a + 2] == 1) c = a;
  memset(F, 0, 9 * sizeof *F);
  for (int k = 0; k < 3; k++) F[4 * k] = x[3 * c + k];
}

static int monitor(FemSolver *s, void *ctx) {
  Ref *r = ctx;
  double F[9], P[9], tau[9], hn[FEM_MC_NHIST];
  corner_F(s, r->m, F);
  int rc = fem_mc_eval(&r->p, F, r->hist, hn, P, NULL, tau);
  if (rc) return rc;
  memcpy(r->hist, hn, sizeof hn);
  double J = F[0] * F[4] * F[8];
  int ne = r->m->nelem;
  double *sig = malloc((size_t)9 * ne * sizeof *sig), smax = 0;
  fem_solver_element_stress(s, sig, NULL, NULL);
  for (int i = 0; i < 9; i++) smax = fmax(smax, fabs(tau[i] / J));
  for (int e = 0; e < ne; e++) {
    for (int i = 0; i < 9; i++)
      r->err_sig = fmax(r->err_sig, fabs(sig[9 * e + i] - tau[i] / J) / smax);
    int nh;
    const double *h = fem_solver_history(s, e, &nh);
    for (int q = 0; q < 4; q++) /* straight tet10: 4 points used */
      for (int i = 0; i < 7; i++) r->err_hist = fmax(r->err_hist, fabs(h[q * nh + i] - hn[i]));
  }
  free(sig);
  r->nsteps++;
  return 0;
}

/* Domain hook: at the first Newton trial of the 3rd substep onwards that is plastic, check the
 * assembled tangent there (a state strictly inside the plastic region). */
static int hook(const FemSolver *s, const double *x, void *ctx) {
  (void)x;
  Ref *r = ctx;
  if (r->tan_checked || r->nsteps < 3) return 0;
  double F[9], P[9];
  FemMcReturn info;
  corner_F(s, r->m, F);
  (void)P;
  double hn[FEM_MC_NHIST];
  if (fem_mc_eval(&r->p, F, r->hist, hn, P, NULL, NULL)) return 0;
  (void)info;
  if (!(hn[6] > r->hist[6] + 1e-6)) return 0; /* elastic trial: nothing to learn */
  r->tan_checked = 1;
  if (fem_solver_check_tangent((FemSolver *)s, 1e-8, &r->tan_err)) r->tan_err = INFINITY;
  return 0;
}

static int run(const char *what, const FemMesh *m, double phi, double c, double psi,
               const double u[3], int expect_region, int expect_sym) {
  const char *nm[] = {"young", "poisson", "friction_angle", "cohesion", "dilation_angle"};
  double par[] = {10e6, 0.3, phi, c, psi};
  FemMaterial mat;
  TU_CHECK(fem_material_from_law("mohr_coulomb", 5, nm, par, 1500, &mat));
  if (fem_material_symmetric(&mat) != expect_sym) {
    fprintf(stderr, "%s: symmetric flag %d, expected %d\n", what, fem_material_symmetric(&mat),
            expect_sym);
    return 1;
  }
  FemSolverParams prm = fem_solver_params_default();
  prm.rtol = 1e-10;
  prm.threads = 1;
  prm.dl_init = 0.05;
  prm.dl_max = 0.05;
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  const char *side[] = {"x0", "x1", "y0", "y1", "z0", "z1"};
  for (int k = 0; k < 6; k++) TU_CHECK(fem_solver_fix_surface(s, side[k], FEM_XYZ));
  TU_CHECK(fem_solver_setup(s));
  Ref r = {{10e6, 0.3, phi * M_PI / 180, c, psi * M_PI / 180, 0, 0}, {0}, 0, 0, 0, 0, 0, 0, m};
  fem_mc_hist_init(&r.p, NULL, r.hist);
  fem_solver_set_monitor(s, monitor, &r);
  fem_solver_set_domain_check(s, hook, &r);
  for (int k = 0; k < 6; k++) {
    const FemSurface *f = fem_mesh_find_surface(m, side[k]);
    for (int a = 0; a < f->nnodes; a++)
      for (int d = 0; d < 3; d++)
        TU_CHECK(fem_solver_set_prescribed(s, 1, &f->nodes[a], d, u[d] * m->xyz[3 * f->nodes[a] + d]));
  }
  TU_CHECK(fem_solver_solve(s));
  int fails = 0;
  char buf[200];
  snprintf(buf, sizeof buf, "%s: element stress vs kernel (rel. max|sigma|)", what);
  fails += tu_close(buf, r.err_sig, 0, 1e-8, 0);
  snprintf(buf, sizeof buf, "%s: history vs kernel", what);
  fails += tu_close(buf, r.err_hist, 0, 1e-8, 0);
  if (!r.tan_checked) fprintf(stderr, "%s: no plastic trial state seen\n", what), fails++;
  snprintf(buf, sizeof buf, "%s: assembled tangent vs FD at a plastic trial state", what);
  fails += tu_close(buf, r.tan_err, 0, 1e-6, 0);
  int nh;
  const double *h = fem_solver_history(s, 0, &nh);
  snprintf(buf, sizeof buf, "%s: final return region", what);
  fails += tu_close(buf, h[7], expect_region, 0, 0);
  if (!(h[6] > 0)) fprintf(stderr, "%s: no plastic strain\n", what), fails++;
  FemSolverStats st;
  fem_solver_stats(s, &st);
  if (!expect_sym && (st.n_chol != 0 || st.n_lu == 0))
    fprintf(stderr, "%s: unsymmetric law but %d CHOLMOD / %d LU factorisations\n", what,
            st.n_chol, st.n_lu), fails++;
  if (expect_sym && st.n_chol == 0)
    fprintf(stderr, "%s: symmetric law never used CHOLMOD\n", what), fails++;
  if (getenv("SA_TEST_VERBOSE"))
    fprintf(stderr, "%s: %d substeps, stress %.2e hist %.2e tangent %.2e region %g eps_p %.4g "
            "chol %d lu %d\n", what, r.nsteps, r.err_sig, r.err_hist, r.tan_err, h[7], h[6],
            st.n_chol, st.n_lu);
  fem_solver_destroy(&s);
  return fails;
}

static int bad(const char *what, double phi, double c, double psi, const char *key) {
  const char *nm[] = {"young", "poisson", "friction_angle", "cohesion", "dilation_angle"};
  double par[] = {10e6, 0.3, phi, c, psi};
  FemMaterial mat;
  TU_CHECK(fem_material_from_law("mohr_coulomb", 5, nm, par, 1500, &mat));
  int rc = fem_material_check(&mat);
  const char *msg = sa_error_message();
  int ok = rc == SA_ERR_INPUT && msg && strstr(msg, key);
  if (!ok) fprintf(stderr, "%s: rc %d, message '%s' does not name %s\n", what, rc, msg ? msg : "", key);
  sa_error_clear();
  return !ok;
}

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_ERROR);
  if (!fem_law_find("mohr_coulomb")) {
    fprintf(stderr, "law mohr_coulomb not registered\n");
    return 1;
  }
  SmeshBlock blk = {{2, 2, 2}, map_cube, NULL, {"x0", "x1", "y0", "y1", "z0", "z1"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  int fails = 0;
  /* plane: the middle strain halfway between the others keeps s2 strictly between s1 and s3
   * (exactly for Tresca, whose flow leaves s2 alone); edge: equal lateral strains */
  const double plane[3] = {0.02, 0.0, -0.02}, edge[3] = {0.004, 0.004, -0.02};
  fails += run("associated, plane", m, 30, 20e3, 30, plane, FEM_MC_PLANE, 1);
  fails += run("associated, compression edge", m, 30, 20e3, 30, edge, FEM_MC_EDGE_LEFT, 1);
  fails += run("non-associated, plane", m, 30, 20e3, 5, plane, FEM_MC_PLANE, 0);
  fails += run("non-associated, compression edge", m, 30, 20e3, 5, edge, FEM_MC_EDGE_LEFT, 0);
  fails += run("Tresca, plane", m, 0, 20e3, 0, plane, FEM_MC_PLANE, 1);
  fails += bad("friction_angle 95", 95, 1e3, 0, "friction_angle");
  fails += bad("cohesion -1", 30, -1, 0, "cohesion");
  fails += bad("dilation_angle 40 > friction_angle 30", 30, 1e3, 40, "dilation_angle");
  smesh_free(&m);
  return fails ? 1 : 0;
}
