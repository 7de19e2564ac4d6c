/* fem_bench - cost of a Newton iteration on the reference actuator (not a test).
 *
 * For three mesh sizes: generate meshes/actuator.geo (tet10), set up the solver (pattern +
 * CHOLMOD symbolic analysis, timed), then solve one pressure step (5 kPa, a follower load on
 * cavity_wall, fixed_end clamped) and report per Newton iteration the time in assembly
 * (residual + tangent), numeric factorisation and triangular solves, nnz(K), nnz(L) and the
 * factorisation fill. With "threads" as the second argument it repeats the middle mesh with 1
 * and 2 assembly threads. Wall-clock times (on a shared machine they include waiting).
 *   fem_bench [GEO] [threads]          GEO defaults to meshes/actuator.geo in the source tree */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "sa_error.h"
#include "sa_log.h"

#ifndef SOFTACT_MESH_DIR
#define SOFTACT_MESH_DIR "meshes"
#endif

static int run(const char *geo, double h, double hb, double hr, int threads) {
  FemGeoParam gp[] = {{"h_band", hb}, {"h_ring", hr}};
  FemMesh *m;
  double t0 = sa_time_now();
  SA_CHECK(fem_mesh_generate(geo, 2, gp, h, 2, &m));
  double t_mesh = sa_time_now() - t0;
  FemMaterial mats[8];
  for (int r = 0; r < m->nregions; r++) {
    if (!strcmp(m->region_names[r], "silicone"))
      mats[r] = (FemMaterial){.kind = FEM_MAT_YEOH, .c10 = 0.11e6, .c20 = 0.02e6,
                              .kappa = 500 * 0.22e6, .rho = 1130};
    else if (!strcmp(m->region_names[r], "strain_limit"))
      mats[r] = fem_material_from_e_nu(1000e6, 0.3, 1000);
    else
      mats[r] = fem_material_from_e_nu(2000e6, 0.3, 1300);
  }
  FemSolverParams prm = fem_solver_params_default();
  prm.threads = threads;
  prm.dl_init = 0.5;
  FemSolver *s;
  SA_CHECK(fem_solver_create(m, mats, &prm, &s));
  SA_CHECK(fem_solver_fix_surface(s, "fixed_end", FEM_XYZ));
  SA_CHECK(fem_solver_add_pressure_surface(s, "cavity_wall"));
  t0 = sa_time_now();
  SA_CHECK(fem_solver_setup(s));
  double t_setup = sa_time_now() - t0;
  SA_CHECK(fem_solver_set_pressure(s, 5e3));
  SA_CHECK(fem_solver_solve(s));
  FemSolverStats st;
  fem_solver_stats(s, &st);
  double ta = st.t_assemble / st.n_assemble, tf = st.t_factor / st.n_factor,
         ts = st.t_solve / st.n_solve;
  printf("| %.1f/%.1f/%.1f | %d | %d | %d | %.3g | %.3g | %.1f | %.2f | %.2f | %.3f | %.3f | %.3f "
         "| %d | %d/%d |\n",
         1e3 * h, 1e3 * hb, 1e3 * hr, st.nelem, st.nfree, threads, (double)st.nnz_k, st.nnz_l,
         st.nnz_l / (0.5 * (st.nnz_k + st.nfree)), t_mesh, t_setup, ta, tf, ts, st.n_factor,
         st.n_chol, st.n_lu);
  fflush(stdout);
  fem_solver_destroy(&s);
  fem_mesh_destroy(&m);
  return 0;
}

int main(int argc, char **argv) {
  const char *geo = argc > 1 ? argv[1] : SOFTACT_MESH_DIR "/actuator.geo";
  int threads_study = argc > 2 && !strcmp(argv[2], "threads");
  sa_log_set_level(SA_LOG_WARN);
  printf("| h/h_band/h_ring [mm] | tet10 | free dofs | threads | nnz(K) | nnz(L) | fill | mesh [s] "
         "| setup+symbolic [s] | assemble/it [s] | factorise/it [s] | solve/it [s] | "
         "factorisations | Cholesky/LU |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  int rc = 0;
  if (threads_study) {
    rc = run(geo, 4e-3, 2e-3, 2e-3, 1);
    if (!rc) rc = run(geo, 4e-3, 2e-3, 2e-3, 2);
  } else {
    rc = run(geo, 6e-3, 3e-3, 3e-3, 2);
    if (!rc) rc = run(geo, 4e-3, 2e-3, 2e-3, 2);
    if (!rc) rc = run(geo, 3e-3, 1e-3, 2e-3, 2);
  }
  if (rc) sa_error_print();
  return rc ? 1 : 0;
}
