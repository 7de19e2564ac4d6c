/* test_contact_patch - contact patch test: two blocks with non-matching meshes pressed together
 * by a uniform pressure must carry it uniformly.
 *
 * Lower block [0, a]^2 x [-a, 0] (tet4, 3 x 3 x 2 cells), upper block [0, a]^2 x [0, a]
 * (4 x 4 x 3 cells): the interface meshes do not match. Both: E = 1 MPa, nu = 0.3, rollers on
 * x = 0 and y = 0 (each block), the lower block's base on rollers in z; the upper block's top
 * carries the nodal forces of a uniform pressure p = 10 Pa (strain 1e-5: finite-strain terms
 * 1e-5 relative). Exact solution: uniform sigma_zz = -p, other stresses zero, contact pressure
 * p at every slave node, both blocks expanding laterally alike (no tangential slip, so the
 * result does not depend on mu).
 *
 * Node-to-surface, single pass, does not pass this test: the slave's nodal forces A_k p are
 * consistent for its own mesh, but the master receives them at the slave points through its
 * shape functions, which differ from the master's consistent loads when the meshes do not
 * match; the master's interface stresses are then not uniform, its surface not flat, and the
 * slave's gaps (pressures) vary. Two-pass (each side slave once, half the penalty each) cancels
 * the first-order error and approaches the exact state as the penalty grows (Taylor &
 * Papadopoulos 1991). Measured at this commit (mu = 0.3; eps = alpha E / h, h = a/4), max over
 * elements |sigma_zz + p| / p:
 *   alpha            0.1     1      10     100
 *   fine slave       0.20    0.16   0.13   0.13
 *   coarse slave     0.44    0.26   0.19   0.19
 *   two-pass         0.21    0.087  0.029  0.0083
 * Checks (bounds on what the method gives, with margin, not the exact patch test):
 *   - total contact force = p a^2 to 1e-8 in every variant (equilibrium);
 *   - alpha = 10: single pass sigma_zz error <= 0.25, two-pass <= 0.05;
 *   - alpha = 100, two-pass: <= 0.015 (the patch test passed in the penalty limit).
 * PATCH_ALPHA / PATCH_MU override alpha and mu for a study (CONTACT_VERBOSE=1 prints). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cutil.h"
#include "fem.h"
#include "fem_contact.h"
#include "sa_log.h"
#include "tutil.h"

static const double E = 1e6, NU = 0.3, A = 0.01, P = 10.0;

/* variant 0: fine (upper) slave on coarse master; 1: coarse (lower) slave on fine master;
 * 2: two-pass (both, each with half the penalty: the interface stiffness of one pass). */
static int patch(int variant, double alpha_in, double *err_tn, double *err_szz, double *err_sxx, double *err_F) {
  FemMesh *m = NULL;
  FemSolver *s;
  TU_CHECK(cu_patch_setup(1, 0, 0, A, E, NU, 1e-10, &m, &s));
  double h = A / 4;
  FemContactParams cp = fem_contact_params_default();
  double alpha = alpha_in > 0 ? alpha_in : getenv("PATCH_ALPHA") ? atof(getenv("PATCH_ALPHA")) : 10.0;
  cp.penalty = alpha * E / h * (variant == 2 ? 0.5 : 1.0);
  cp.friction = getenv("PATCH_MU") ? atof(getenv("PATCH_MU")) : 0.3;
  cp.search_radius = h;
  FemContact *c[2] = {NULL, NULL};
  int nc = 0;
  if (variant == 0 || variant == 2) {
    TU_CHECK(fem_contact_create(m, "ubot", &cp, &c[nc]));
    TU_CHECK(fem_contact_set_master(c[nc], "ltop"));
    TU_CHECK(fem_contact_attach(c[nc++], s));
  }
  if (variant == 1 || variant == 2) {
    TU_CHECK(fem_contact_create(m, "ltop", &cp, &c[nc]));
    TU_CHECK(fem_contact_set_master(c[nc], "ubot"));
    TU_CHECK(fem_contact_attach(c[nc++], s));
  }
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *top = fem_mesh_find_surface(m, "top");
  double *f = malloc(sizeof(double) * 3 * top->nnodes);
  cu_traction(m, top, (double[3]){0, 0, -P}, f);
  TU_CHECK(fem_solver_set_nodal_forces(s, top->nnodes, top->nodes, f));
  free(f);
  TU_CHECK(fem_solver_solve(s));
  /* slave pressures (two-pass: the pressure of a node is the sum over the passes only where
   * both passes' nodes coincide; report the first pass's nodes times 2) */
  *err_tn = 0;
  double Fz = 0;
  for (int k = 0; k < nc; k++) {
    const double *tn, *area;
    int ns = fem_contact_slaves(c[k], NULL, &area, NULL, &tn, NULL, NULL);
    FemContactStats st;
    fem_contact_stats(c[k], &st);
    Fz += fabs(st.force[2]);
    if (k > 0) continue;
    for (int i = 0; i < ns; i++) {
      double e = fabs(tn[i] * (variant == 2 ? 2 : 1) - P) / P;
      if (e > *err_tn) *err_tn = e;
    }
  }
  *err_F = fabs(Fz - P * A * A) / (P * A * A);
  double *sig = malloc(sizeof(double) * 9 * m->nelem);
  TU_CHECK(fem_solver_element_stress(s, sig, NULL, NULL));
  *err_szz = *err_sxx = 0;
  for (int e = 0; e < m->nelem; e++) {
    double ez = fabs(sig[9 * e + 8] + P) / P;
    double ex = fmax(fabs(sig[9 * e]), fmax(fabs(sig[9 * e + 4]), fabs(sig[9 * e + 1]))) / P;
    if (ez > *err_szz) *err_szz = ez;
    if (ex > *err_sxx) *err_sxx = ex;
  }
  free(sig);
  fem_solver_destroy(&s);
  for (int k = 0; k < nc; k++) fem_contact_destroy(&c[k]);
  smesh_free(&m);
  return 0;
}

int main(void) {
  sa_log_set_level(getenv("CONTACT_VERBOSE") ? SA_LOG_INFO : SA_LOG_WARN);
  int fail = 0, study = getenv("PATCH_ALPHA") != NULL;
  const char *vn[4] = {"single pass, fine slave", "single pass, coarse slave", "two-pass",
                       "two-pass, alpha 100"};
  const double bound[4] = {0.25, 0.25, 0.05, 0.015};
  for (int v = 0; v < (study ? 3 : 4); v++) {
    double etn, ezz, exx, eF;
    TU_CHECK(patch(v < 3 ? v : 2, v < 3 ? -1 : 100, &etn, &ezz, &exx, &eF));
    if (getenv("CONTACT_VERBOSE"))
      fprintf(stderr, "%s: max |t_N - p|/p %.3e, max |s_zz + p|/p %.3e, max |s_xx,yy,xy|/p %.3e, "
              "|F - p a^2|/(p a^2) %.3e\n", vn[v], etn, ezz, exx, eF);
    char w[160];
    snprintf(w, sizeof w, "%s: total contact force", vn[v]);
    fail |= tu_close(w, eF, 0, 1e-8, 0);
    if (study) continue;
    snprintf(w, sizeof w, "%s: max |sigma_zz + p| / p", vn[v]);
    fail |= tu_close(w, ezz, 0, bound[v], 0);
  }
  return fail;
}
