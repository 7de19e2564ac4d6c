/* fem_ramp - time to accuracy of the reference actuator's pressure ramp (issue 14; not a test).
 *
 * Ramps the follower pressure on cavity_wall of meshes/actuator.geo (rings on, Yeoh c10 = 0.11
 * MPa, c20 = 0.02 MPa, K/mu = 500, band E = 1 GPa, rings E = 2 GPa: cases/pressure_bending.ini)
 * from 0 to p_max in n_out equal output steps and prints the bending angle (docs/fem.md) at every
 * output step, the solver counts (factorisations, Cholesky/LU, not-positive-definite attempts,
 * modified tangents, Newton iterations, substeps, cuts, energy backtracks), the phase times
 * and the wall and CPU time (getrusage, both threads) of the ramp. In the same process it
 * measures one CHOLMOD factorisation of the default 4/2/2 mm mesh (mean over the Cholesky
 * factorisations of a 2 kPa solve, before and after the ramp: the tangent is positive definite
 * there) and reports the ramp's wall time in units of it (issue 14's metric).
 *
 *   fem_ramp [key=value ...]   keys: h hb hr (mesh [m]), tg (thin_grow [m], 0: the .geo's),
 *     hc (h_corner [m], 0: no grading toward the ring corners), gc (corner_grade),
 *     p_max [Pa], n_out, merit (lazy|energy),
 *     indefinite (lu|modify), predictor (new_load|equilibrium|reuse), reuse_rate, dl_init,
 *     easy_iter, grow, max_iter, max_stall, ls_memory, rtol, dl_max, krylov_max, krylov_rtol,
 *     ref (1: measure the reference factorisation, 0: skip),
 *     swept (1: the ramp's mesh is [mesh] kind = swept: h, hb, hr and hrad (h_radial [m], 0: hb),
 *     grade; the reference stays the default Gmsh mesh)
 * Output: one line per output step ("step p_kPa angle_deg"), then key = value lines. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "fem.h"
#include "fem_blas.h"
#include "sa_error.h"
#include "sa_log.h"

#ifndef SOFTACT_MESH_DIR
#define SOFTACT_MESH_DIR "meshes"
#endif

static double cpu_now(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_utime.tv_sec + 1e-6 * ru.ru_utime.tv_usec + ru.ru_stime.tv_sec +
         1e-6 * ru.ru_stime.tv_usec;
}

/* tg > 0: thin_grow of actuator.geo (the distance over which the band and ring sizes grow
 * back to h; the .geo's default is h). */
static double g_hc = 0, g_gc = 0.5; /* ring-corner grading (actuator.geo h_corner, corner_grade) */
/* swept > 0: the ramp's mesh is fem_mesh_actuator_swept with h_radial g_hrad and grade g_grade */
static int g_swept = 0;
static double g_hrad = 0, g_grade = 1.5;
static int make_mesh(double h, double hb, double hr, double tg, FemMesh **m, FemMaterial *mats) {
  FemGeoParam gp[5] = {{"h_band", hb}, {"h_ring", hr}};
  int np = 2;
  if (tg > 0) gp[np++] = (FemGeoParam){"thin_grow", tg};
  if (g_hc > 0) {
    gp[np++] = (FemGeoParam){"h_corner", g_hc};
    gp[np++] = (FemGeoParam){"corner_grade", g_gc};
  }
  if (g_swept) {
    FemSweptActuator p = fem_swept_actuator_default(h, g_hrad > 0 ? g_hrad : hb, hb, hr, 1);
    p.grade = g_grade;
    SA_CHECK(fem_mesh_actuator_swept(&p, 2, m));
  } else {
    SA_CHECK(fem_mesh_generate(SOFTACT_MESH_DIR "/actuator.geo", np, gp, h, 2, m));
  }
  for (int r = 0; r < (*m)->nregions; r++) {
    if (!strcmp((*m)->region_names[r], "silicone"))
      mats[r] = (FemMaterial){.kind = FEM_MAT_YEOH, .c10 = 0.11e6, .c20 = 0.02e6,
                              .kappa = 500 * 0.22e6, .rho = 1130};
    else if (!strcmp((*m)->region_names[r], "strain_limit"))
      mats[r] = fem_material_from_e_nu(1000e6, 0.3, 1000);
    else
      mats[r] = fem_material_from_e_nu(2000e6, 0.3, 1300);
  }
  return 0;
}

static int make_solver(const FemMesh *m, const FemMaterial *mats, const FemSolverParams *prm,
                       FemSolver **s) {
  SA_CHECK(fem_solver_create(m, mats, prm, s));
  SA_CHECK(fem_solver_fix_surface(*s, "fixed_end", FEM_XYZ));
  SA_CHECK(fem_solver_add_pressure_surface(*s, "cavity_wall"));
  SA_CHECK(fem_solver_setup(*s));
  return 0;
}

/* Mean wall time of a Cholesky factorisation of the default mesh (2 kPa solve), and its CPU
 * time estimated as the solve's CPU time times the factorisation's share of its wall time
 * (on a loaded machine the wall time includes waiting; the CPU time does not). */
static int ref_factor(const FemMesh *m, const FemMaterial *mats, double *tw, double *tc, int *nf) {
  FemSolverParams prm = fem_solver_params_default();
  FemSolver *s;
  SA_CHECK(make_solver(m, mats, &prm, &s));
  SA_CHECK(fem_solver_set_pressure(s, 2e3));
  double c0 = cpu_now();
  SA_CHECK(fem_solver_solve(s));
  double c1 = cpu_now() - c0;
  FemSolverStats st;
  fem_solver_stats(s, &st);
  *tw = st.t_factor / st.n_factor;
  *tc = c1 * st.t_factor / (st.t_assemble + st.t_factor + st.t_solve) / st.n_factor;
  *nf = st.n_factor;
  fem_solver_destroy(&s);
  return 0;
}

static const char *arg(int argc, char **argv, const char *key, const char *def) {
  size_t n = strlen(key);
  for (int i = 1; i < argc; i++)
    if (!strncmp(argv[i], key, n) && argv[i][n] == '=') return argv[i] + n + 1;
  return def;
}

int main(int argc, char **argv) {
  fem_blas_select_kernels(argv); /* OPENBLAS_CORETYPE=Prescott measures the generic kernels */
  sa_log_set_level(getenv("FEM_RAMP_DEBUG") ? SA_LOG_DEBUG : SA_LOG_WARN);
  double h = atof(arg(argc, argv, "h", "4e-3")), hb = atof(arg(argc, argv, "hb", "2e-3")),
         hr = atof(arg(argc, argv, "hr", "2e-3")), p_max = atof(arg(argc, argv, "p_max", "120e3"));
  double tg = atof(arg(argc, argv, "tg", "0"));
  int n_out = atoi(arg(argc, argv, "n_out", "12")), want_ref = atoi(arg(argc, argv, "ref", "1"));
  FemSolverParams prm = fem_solver_params_default();
  prm.merit = !strcmp(arg(argc, argv, "merit", "lazy"), "energy") ? FEM_MERIT_ENERGY
                                                                   : FEM_MERIT_LAZY;
  prm.indefinite = !strcmp(arg(argc, argv, "indefinite", "lu"), "modify") ? FEM_INDEFINITE_MODIFY
                                                                           : FEM_INDEFINITE_LU;
  const char *pr = arg(argc, argv, "predictor", "new_load");
  prm.predictor = !strcmp(pr, "equilibrium") ? FEM_PREDICT_EQUILIBRIUM
                  : !strcmp(pr, "reuse")     ? FEM_PREDICT_REUSE
                  : !strcmp(pr, "extrapolate") ? FEM_PREDICT_EXTRAPOLATE
                                             : FEM_PREDICT_NEW_LOAD;
  prm.reuse_rate = atof(arg(argc, argv, "reuse_rate", "0"));
  prm.dl_init = atof(arg(argc, argv, "dl_init", "1"));
  prm.easy_iter = atoi(arg(argc, argv, "easy_iter", "5"));
  prm.grow = atof(arg(argc, argv, "grow", "1.5"));
  prm.max_iter = atoi(arg(argc, argv, "max_iter", "25"));
  prm.dl_max = atof(arg(argc, argv, "dl_max", "1"));
  prm.krylov_max = atoi(arg(argc, argv, "krylov_max", "0"));
  prm.krylov_rtol = atof(arg(argc, argv, "krylov_rtol", "1e-3"));
  prm.max_stall = atoi(arg(argc, argv, "max_stall", "6"));
  prm.ls_memory = atoi(arg(argc, argv, "ls_memory", "1"));
  prm.rtol = atof(arg(argc, argv, "rtol", "1e-8"));

  FemMaterial mref[8], mats[8];
  FemMesh *m0 = NULL, *m = NULL;
  double tf0 = 0, tf1 = 0, tc0 = 0, tc1 = 0;
  int nf0 = 0, nf1 = 0;
  if (want_ref) {
    SA_CHECK(make_mesh(4e-3, 2e-3, 2e-3, 0.0, &m0, mref));
    if (ref_factor(m0, mref, &tf0, &tc0, &nf0)) goto fail;
  }
  /* the reference mesh above is the default one, never graded */
  g_hc = atof(arg(argc, argv, "hc", "0"));
  g_gc = atof(arg(argc, argv, "gc", "0.5"));
  g_swept = atoi(arg(argc, argv, "swept", "0"));
  g_hrad = atof(arg(argc, argv, "hrad", "0"));
  g_grade = atof(arg(argc, argv, "grade", "1.5"));
  if (make_mesh(h, hb, hr, tg, &m, mats)) goto fail;
  FemSolver *s;
  if (make_solver(m, mats, &prm, &s)) goto fail;
  double w0 = sa_time_now(), c0 = cpu_now(), ang[1000] = {0};
  int rc = 0, k, iters_total = 0, substeps_total = 0, cuts_total = 0;
  FemSolveReport rep;
  for (k = 1; k <= n_out && k < 1000; k++) {
    SA_CHECK(fem_solver_set_pressure(s, p_max * k / n_out));
    rc = fem_solver_solve(s);
    fem_solver_report(s, &rep);
    iters_total += rep.newton_iters;
    substeps_total += rep.substeps;
    cuts_total += rep.cuts;
    if (rc) break;
    SA_CHECK(fem_bending_angle(m, "tip", fem_solver_positions(s), &ang[k]));
    printf("step %d p_kPa %.3f angle_deg %.6f\n", k, 1e-3 * p_max * k / n_out, ang[k]);
    fflush(stdout);
  }
  double wall = sa_time_now() - w0, cpu = cpu_now() - c0;
  if (rc) {
    sa_error_print();
    sa_error_clear();
  }
  FemSolverStats st;
  fem_solver_stats(s, &st);
  if (want_ref && ref_factor(m0, mref, &tf1, &tc1, &nf1)) goto fail;
  double tref = want_ref ? 0.5 * (tf0 + tf1) : NAN;
  printf("thin_grow = %.2f mm\n", 1e3 * tg);
  printf("h_corner = %.3f mm\ncorner_grade = %.3f\n", 1e3 * g_hc, g_gc);
  if (g_swept) printf("swept = 1\nh_radial = %.3f mm\ngrade = %.3f\n", 1e3 * g_hrad, g_grade);
  printf("mesh = %.2f/%.2f/%.2f mm\nnfree = %d\nnelem = %d\ncompleted = %d\n", 1e3 * h, 1e3 * hb,
         1e3 * hr, st.nfree, st.nelem, rc == 0);
  printf("factorisations = %d\ncholesky = %d\nlu = %d\nnot_pd_attempts = %d\nmodified = %d\n"
         "assemblies = %d\ntangent_assemblies = %d\nreused = %d\nenergy_backtracks = %d\n"
         "krylov_directions = %d\nkrylov_iterations = %d\nkrylov_failed = %d\n"
         "indef_backtracks = %d\nnewton_iterations = %d\nsubsteps = %d\ncuts = %d\n",
         st.n_factor, st.n_chol, st.n_lu, st.n_not_pd, st.n_modified, st.n_assemble,
         st.n_assemble_tangent, st.n_reuse, st.n_ls_energy, st.n_krylov, st.n_krylov_it,
         st.n_krylov_fail, st.n_indef_backtrack, iters_total, substeps_total, cuts_total);
  printf("t_assemble = %.2f\nt_factor = %.2f\nt_solve = %.2f\nwall = %.2f\ncpu = %.2f\n",
         st.t_assemble, st.t_factor, st.t_solve, wall, cpu);
  printf("ref_factor_wall = %.4f (%d + %d factorisations: %.4f before, %.4f after)\n", tref, nf0,
         nf1, tf0, tf1);
  double cref = want_ref ? 0.5 * (tc0 + tc1) : NAN;
  printf("ref_factor_cpu = %.4f (%.4f before, %.4f after)\n", cref, tc0, tc1);
  printf("ratio = %.1f\nratio_cpu = %.1f\nblas_kernels = %s\n", wall / tref, cpu / cref, fem_blas_kernels());
  for (int j = 1; j < k && j <= n_out; j++) {
    double p = p_max * j / n_out;
    if (fabs(fmod(p, 30e3)) < 1e-6) printf("angle_%.0f = %.6f\n", 1e-3 * p, ang[j]);
  }
  fem_solver_destroy(&s);
  fem_mesh_destroy(&m);
  fem_mesh_destroy(&m0);
  return rc ? 2 : 0;
fail:
  sa_error_print();
  return 1;
}
