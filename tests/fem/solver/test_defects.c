/* test_defects - regression tests of the solver defects listed in issue 11 (each failed before
 * its fix):
 * 1. fem_solver_set_nodal_forces / clear_nodal_forces before setup: no NULL dereference, and
 *    the forces set before setup are the ones solved for (same u as when set after setup,
 *    to round-off: identical computation).
 * 2. A static solve with a static interval dt leaves the velocities (u - u_start)/dt, not zeros
 *    (exact up to round-off), and advances time by dt.
 * 3. fem_solver_create runs the validators: a material with kappa <= 0 and an inverted element
 *    are rejected with SA_ERR_INPUT naming the problem.
 * 4. The read-back getters do not overwrite the work arrays Newton uses: a dynamic step whose
 *    first iteration reuses the last factors (predictor REUSE, forced LU: UMFPACK refines
 *    against the values it factorised, which include the mass term) gives bitwise the same
 *    displacements whether or not fem_solver_reactions/pressure_forces/tangent_asymmetry/
 *    check_tangent were called before it.
 * 5. Directions from reused factors assemble no tangent (n_assemble_tangent == n_factor with
 *    modified Newton and no line search), and a dynamic step with modified Newton and forced LU
 *    (UMFPACK refines against the matrix it factorised, incl. the mass term) reaches the same
 *    state as full Newton (both to rtol 1e-10: 1e-7 relative in u). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_log.h"
#include "smesh.h"
#include "tutil.h"

static const FemMaterial mat = {.kind = FEM_MAT_NEOHOOKE, .c10 = 0.5, .kappa = 50, .rho = 1};

static int make(const FemMesh *m, const FemSolverParams *prm, int pressure, FemSolver **s) {
  TU_CHECK(fem_solver_create(m, &mat, prm, s));
  TU_CHECK(fem_solver_fix_surface(*s, "clamp", FEM_XYZ));
  if (pressure) TU_CHECK(fem_solver_add_pressure_surface(*s, "top"));
  return 0;
}

static double maxdiff(const double *a, const double *b, int n, double *amax) {
  double d = 0, u = 0;
  for (int k = 0; k < n; k++) {
    d = fmax(d, fabs(a[k] - b[k]));
    u = fmax(u, fabs(b[k]));
  }
  if (amax) *amax = u;
  return d;
}

int main(void) {
  if (!getenv("SA_TEST_VERBOSE")) sa_log_set_level(SA_LOG_ERROR);
  SmeshBlock blk = {{8, 2, 2}, smesh_map_bar, NULL,
                    {"clamp", "end", "front", "back", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &blk, 2, 1e-9, &m));
  int N = m->nnodes, n3 = 3 * N, fails = 0;
  const FemSurface *end = fem_mesh_find_surface(m, "end");
  double *f = calloc((size_t)3 * end->nnodes, sizeof *f);
  for (int k = 0; k < end->nnodes; k++) f[3 * k + 2] = -2e-3 / end->nnodes;

  /* 1. nodal forces before setup */
  FemSolver *a, *b;
  TU_CHECK(make(m, NULL, 0, &a));
  fem_solver_clear_nodal_forces(a);
  TU_CHECK(fem_solver_set_nodal_forces(a, end->nnodes, end->nodes, f));
  TU_CHECK(fem_solver_setup(a));
  TU_CHECK(fem_solver_solve(a));
  TU_CHECK(make(m, NULL, 0, &b));
  TU_CHECK(fem_solver_setup(b));
  TU_CHECK(fem_solver_set_nodal_forces(b, end->nnodes, end->nodes, f));
  TU_CHECK(fem_solver_solve(b));
  double umax;
  double d = maxdiff(fem_solver_displacements(a), fem_solver_displacements(b), n3, &umax);
  fails += tu_close("forces set before setup: max |u_a - u_b|", d, 0.0, 1e-14, 0.0);
  if (!(umax > 1e-3)) fprintf(stderr, "deflection %g too small\n", umax), fails++;

  /* 2. static interval: velocities over the solve */
  double *u0 = malloc(sizeof(double) * n3);
  memcpy(u0, fem_solver_displacements(b), sizeof(double) * n3);
  for (int k = 0; k < end->nnodes; k++) f[3 * k + 2] *= 1.5;
  TU_CHECK(fem_solver_set_static_interval(b, 0.01));
  TU_CHECK(fem_solver_set_nodal_forces(b, end->nnodes, end->nodes, f));
  double t0 = fem_solver_time(b);
  TU_CHECK(fem_solver_solve(b));
  const double *u1 = fem_solver_displacements(b), *v1 = fem_solver_velocities(b);
  double vmax = 0, verr = 0;
  for (int k = 0; k < n3; k++) {
    double vex = (u1[k] - u0[k]) / 0.01;
    vmax = fmax(vmax, fabs(vex));
    verr = fmax(verr, fabs(v1[k] - vex));
  }
  fails += tu_close("static solve: velocities (u - u_start)/dt", verr, 0.0, 1e-12 * vmax, 0.0);
  if (!(vmax > 0)) fprintf(stderr, "no motion in the static interval\n"), fails++;
  fails += tu_close("static solve advances time by dt", fem_solver_time(b) - t0, 0.01, 1e-15,
                    0.0);
  fem_solver_destroy(&a);
  fem_solver_destroy(&b);

  /* 3. validators in create */
  FemMaterial bad = mat;
  bad.kappa = -1;
  FemSolver *c = NULL;
  int rc = fem_solver_create(m, &bad, NULL, &c);
  if (rc != SA_ERR_INPUT || !strstr(sa_error_message(), "kappa") || c) {
    fprintf(stderr, "kappa < 0 accepted by fem_solver_create (rc %d, '%s')\n", rc,
            sa_error_message());
    fails++;
  }
  sa_error_clear();
  int e0[10];
  memcpy(e0, m->conn, sizeof e0);
  m->conn[0] = e0[1], m->conn[1] = e0[0]; /* swap two corners: inverted */
  rc = fem_solver_create(m, &mat, NULL, &c);
  if (rc != SA_ERR_INPUT || !strstr(sa_error_message(), "element 0") || c) {
    fprintf(stderr, "inverted element accepted by fem_solver_create (rc %d, '%s')\n", rc,
            sa_error_message());
    fails++;
  }
  sa_error_clear();
  memcpy(m->conn, e0, sizeof e0);

  /* 4. getters between solves change nothing Newton uses */
  FemSolverParams prm = fem_solver_params_default();
  prm.predictor = FEM_PREDICT_REUSE;
  prm.linsolver = FEM_LINSOLVER_LU; /* UMFPACK refines against the borrowed values */
  double *ra = malloc(sizeof(double) * n3), *ua = malloc(sizeof(double) * n3);
  for (int pass = 0; pass < 2; pass++) {
    FemSolver *s;
    TU_CHECK(make(m, &prm, 1, &s));
    TU_CHECK(fem_solver_setup(s));
    TU_CHECK(fem_solver_set_pressure(s, 2e-3));
    TU_CHECK(fem_solver_step_dynamic(s, 0.2));
    if (pass == 1) {
      TU_CHECK(fem_solver_reactions(s, ra));
      TU_CHECK(fem_solver_pressure_forces(s, ra));
      (void)fem_solver_tangent_asymmetry(s);
      double rel;
      TU_CHECK(fem_solver_check_tangent(s, 1e-7, &rel));
    }
    TU_CHECK(fem_solver_step_dynamic(s, 0.2));
    if (pass == 0) memcpy(ua, fem_solver_displacements(s), sizeof(double) * n3);
    else {
      d = maxdiff(fem_solver_displacements(s), ua, n3, NULL);
      if (d != 0.0) {
        fprintf(stderr, "getters between solves changed the next solve: max |du| %.3g\n", d);
        fails++;
      }
    }
    fem_solver_destroy(&s);
  }

  /* 5. reused factors: no tangent assembly; dynamics with LU and modified Newton */
  double *udyn = malloc(sizeof(double) * n3);
  for (int pass = 0; pass < 2; pass++) {
    FemSolverParams p2 = fem_solver_params_default();
    p2.rtol = 1e-10;
    p2.linsolver = FEM_LINSOLVER_LU;
    p2.line_search = 0;
    if (pass == 1) p2.reuse_rate = 0.5;
    FemSolver *s;
    TU_CHECK(make(m, &p2, 1, &s));
    TU_CHECK(fem_solver_setup(s));
    TU_CHECK(fem_solver_set_pressure(s, 3e-3));
    for (int k = 0; k < 4; k++) TU_CHECK(fem_solver_step_dynamic(s, 0.2));
    FemSolverStats st;
    fem_solver_stats(s, &st);
    if (pass == 0) memcpy(udyn, fem_solver_displacements(s), sizeof(double) * n3);
    else {
      double um;
      d = maxdiff(fem_solver_displacements(s), udyn, n3, &um);
      fails += tu_close("dynamics, modified Newton + LU vs full Newton: max |du|", d, 0.0,
                        1e-7 * um, 0.0);
      if (st.n_reuse == 0) fprintf(stderr, "no reused direction\n"), fails++;
      if (st.n_assemble_tangent != st.n_factor) {
        fprintf(stderr, "%d tangent assemblies for %d factorisations (%d reused directions)\n",
                st.n_assemble_tangent, st.n_factor, st.n_reuse);
        fails++;
      }
    }
    fem_solver_destroy(&s);
  }
  free(f);
  free(u0);
  free(ra);
  free(ua);
  free(udyn);
  smesh_free(&m);
  return fails != 0;
}
