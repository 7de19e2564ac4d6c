/* fem_triaxial.c - drained triaxial compression of a Mohr-Coulomb cube (scene [triaxial],
 * cases/mc_triaxial.ini; fem_fill.h).
 *
 * Model: a cube of edge `size` (one Kuhn-split cell of 6 tet4: the exact solution is homogeneous,
 * so linear elements carry it exactly) on rollers at x = 0, y = 0 and z = 0, a follower pressure
 * equal to the confining pressure sc on x = size and y = size (the lateral Cauchy stress is sc
 * exactly), and a prescribed vertical displacement of the top face.
 *   stage 1: isotropic consolidation, the pressure ramped to sc with the top moved to the
 *            isotropic elastic state (Kirchhoff tau = -sc J, Hencky strain tau / 3K each way);
 *   stage 2: axial compression, `steps` equal displacement increments to the axial (log)
 *            strain `axial_strain` (0: four times the elastic strain to failure, q_cf / E).
 * The faces x = size and y = size each move as one (a penalty tie of every node's normal
 * displacement to the face's first node, stiffness 100 E size, a contributor): on the
 * compression edge of the yield surface (sigma1 = sigma2, the lateral stresses) the consistent
 * tangent has no stiffness for shear in the lateral plane, so without the ties the free lateral
 * faces let the elements shear in a non-unique, inhomogeneous pattern (q then wanders by 1e-4
 * and the volume read from a corner is wrong). The homogeneous solution carries no tie force.
 * Each output step is a solve with the solver's own cut-backs (a failed substep is cut and
 * retried, never accepted). The axial Cauchy stress is the support force on the top face over
 * its current area (reactions: the law enters only through equilibrium), q = sigma_a - sc
 * (compression positive) and peak_q its maximum.
 *
 * Reference (drained compression, Mohr-Coulomb, compression positive):
 *   sigma1 = sigma3 N + 2 c sqrt(N), N = (1 + sin phi) / (1 - sin phi),
 *   q_cf = sigma1 - sigma3 = sc (N - 1) + 2 c sqrt(N).
 * The kernel's yield surface is in Kirchhoff stress; in Cauchy stress the cohesion acts as c / J,
 * an error of 2 c sqrt(N) |1/J - 1| / q (docs/mohr_coulomb.md), far below the 1 % asked.
 * The dilatancy rate -d eps_v / d eps_a at the end (log strains) is reported next to its plastic
 * closed form 2 sin psi / (1 - sin psi) (exact for the plastic part; the elastic part changes a
 * little with J at constant Cauchy confinement).
 *
 * Outputs: triaxial.csv (axial strain, q, volumetric strain, ...), q_axial_strain.png,
 * volumetric_strain.png, triaxial_NNNN.vtk + triaxial.vtk.series (displacement, Cauchy stress,
 * equivalent plastic strain, return region), summary.ini. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_actuator.h"
#include "fem_contrib.h"
#include "fem_fill.h"
#include "fem_mohr_coulomb.h"
#include "sa_csv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_plot.h"
#include "sa_vtk.h"

typedef struct {
  double confining_pressure, axial_strain, size;
  int steps, vtk_every;
} TriaxParams;

#define P(f) offsetof(TriaxParams, f)
static const SaParam triax_params[] = {
    {"confining_pressure", SA_PARAM_REAL, P(confining_pressure), "Pa", "0", 0, INFINITY, 0, NULL,
     "cell pressure sigma3 (compression positive); required: the case must set it"},
    {"axial_strain", SA_PARAM_REAL, P(axial_strain), "-", "0", 0, 0.5, 0, NULL,
     "final axial log strain of the compression stage (0 = 4 x the elastic strain to failure)"},
    {"steps", SA_PARAM_INT, P(steps), "-", "40", 2, 10000, 0, NULL,
     "output steps of the compression stage (the solver substeps itself when needed)"},
    {"size", SA_PARAM_REAL, P(size), "m", "0.05", 0, 10, SA_MIN_OPEN, NULL, "edge of the cube"},
    {"vtk_every", SA_PARAM_INT, P(vtk_every), "-", "10", 0, 100000, 0, NULL,
     "write a VTK file every this many steps (0 = none; the last step is always written)"},
};
#undef P
static const SaParamTable triax_table = {"triaxial", "fem",
                                         "drained triaxial compression of a Mohr-Coulomb cube",
                                         triax_params, SA_NPARAMS(triax_params)};
static const SaParamTable *const triax_tables[] = {&triax_table, &fem_fill_table,
                                                   &fem_actuator_solver_table};

typedef struct {
  TriaxParams tx;
  FemFillParams fill;
  FemActuatorCase act; /* only .solver is used ([solver] table) */
} TriaxScene;

/* q at failure, compression positive [Pa] */
static double q_closed_form(const FemFillParams *f, double sc) {
  double s = sin(f->friction_angle * M_PI / 180), N = (1 + s) / (1 - s);
  return sc * (N - 1) + 2 * f->cohesion * sqrt(N);
}

static int triax_check(const SaCase *c, void **out) {
  *out = NULL;
  TriaxScene *s;
  SA_CALLOC(s, 1);
  char w[SA_STR_MAX];
  int rc = sa_params_load(&triax_table, c, &s->tx);
  if (!rc && !strcmp(sa_case_origin(c, "triaxial", "confining_pressure", w), "default"))
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [triaxial] confining_pressure is missing: a triaxial test "
                  "needs its cell pressure [Pa], a real number in [0, inf)", sa_case_path(c));
  if (!rc) rc = fem_fill_load(c, &s->fill);
  if (!rc) rc = sa_params_load(&fem_actuator_solver_table, c, &s->act.solver);
  if (!rc && !(q_closed_form(&s->fill, s->tx.confining_pressure) > 0))
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [fill] cohesion = 0 with [triaxial] confining_pressure = "
                  "0: the sample has no strength; expected cohesion > 0 or confining_pressure > 0",
                  sa_case_path(c));
  if (rc) {
    free(s);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = s;
  return 0;
}

static void triax_write_resolved(const void *scene, FILE *f) {
  const TriaxScene *s = scene;
  sa_params_write(&triax_table, &s->tx, f);
  fprintf(f, "\n");
  sa_params_write(&fem_fill_table, &s->fill, f);
  fprintf(f, "\n");
  sa_params_write(&fem_actuator_solver_table, &s->act.solver, f);
  fprintf(f, "\n");
}

static void triax_destroy(void **scene) {
  if (!scene) return;
  free(*scene);
  *scene = NULL;
}

typedef struct {
  double L;
  void *unused;
} CubeCtx;

static void map_cube(const double xi[3], const void *ctx, double X[3]) {
  const CubeCtx *c = ctx;
  for (int k = 0; k < 3; k++) X[k] = c->L * xi[k];
}

/* Normal displacement of every node of a face tied to that of its first node (penalty). */
typedef struct {
  int n[2], *nodes[2];
  double k;
  const FemMesh *m;
} Ties;

static int ties_candidates(void *ctx, const FemMesh *m, FemPairSink *sink) {
  (void)m;
  Ties *t = ctx;
  for (int f = 0; f < 2; f++)
    for (int i = 1; i < t->n[f]; i++) fem_pairs_add(sink, t->nodes[f][i], t->nodes[f][0]);
  return 0;
}

static int ties_eval(void *ctx, FemAsmView *v) {
  Ties *t = ctx;
  const double *x = fem_asm_positions(v), *X = t->m->xyz;
  for (int f = 0; f < 2; f++) { /* face 0: x-component, face 1: y-component */
    int r = t->nodes[f][0];
    for (int i = 1; i < t->n[f]; i++) {
      int a = t->nodes[f][i];
      double d = (x[3 * a + f] - X[3 * a + f]) - (x[3 * r + f] - X[3 * r + f]);
      double fa[3] = {0, 0, 0}, K[9] = {0}, mK[9] = {0};
      fa[f] = t->k * d;
      fem_asm_add_force(v, a, fa);
      fa[f] = -fa[f];
      fem_asm_add_force(v, r, fa);
      K[4 * f] = t->k;
      mK[4 * f] = -t->k;
      fem_asm_add_block(v, a, a, K);
      fem_asm_add_block(v, r, r, K);
      fem_asm_add_block(v, a, r, mK);
      fem_asm_add_block(v, r, a, mK);
    }
  }
  return 0;
}

typedef struct {
  const TriaxScene *sc;
  const SaRun *run;
  FemSolver *s;
  FemMesh *m;
  const FemSurface *top;
  int corner, step, *cell_types, *cell_off;
  double *react, *sigma, *vm, *epsp, *region;
  SaCsv *csv;
  SaVtkSeries *series;
  double H_c, V_c, q_cf, peak_q, peak_q_tau, peak_q_tau_cf, J, eps_at_peak, q_last, q_prev, ea_last, ea_prev, ev_last, ev_prev;
} Tx;

/* Axial Cauchy stress (compression positive) from the support forces on the top face. */
static int axial_stress(Tx *t, double *sig_a, double *ea, double *ev) {
  *sig_a = *ea = *ev = 0;
  SA_CHECK(fem_solver_reactions(t->s, t->react));
  double Fz = 0;
  for (int k = 0; k < t->top->nnodes; k++) Fz += t->react[3 * t->top->nodes[k] + 2];
  const double *x = fem_solver_positions(t->s);
  double a = x[3 * t->corner], b = x[3 * t->corner + 1], h = x[3 * t->corner + 2];
  *sig_a = -Fz / (a * b);
  *ea = t->H_c > 0 ? log(t->H_c / h) : 0;
  *ev = t->V_c > 0 ? log(t->V_c / (a * b * h)) : 0;
  double L = t->sc->tx.size;
  t->J = a * b * h / (L * L * L);
  return 0;
}

static int write_vtk(Tx *t) {
  char name[64], path[SA_STR_MAX];
  snprintf(name, sizeof name, "triaxial_%04d.vtk", t->step);
  SA_CHECK(sa_run_path(t->run, name, path));
  SA_CHECK(fem_solver_element_stress(t->s, t->sigma, t->vm, NULL));
  fem_fill_history_mean(t->s, 6, t->epsp);
  fem_fill_history_mean(t->s, 7, t->region);
  SaVtk *v;
  SA_CHECK(sa_vtk_grid_open(path, t->run->vtk, "softact triaxial", t->m->nnodes,
                            fem_solver_positions(t->s), t->m->nelem, t->cell_types, t->cell_off,
                            t->m->conn, &v));
  int rc = sa_vtk_point_data(v, "displacement", 3, fem_solver_displacements(t->s));
  if (!rc) rc = sa_vtk_cell_data(v, "cauchy_stress", 9, t->sigma);
  if (!rc) rc = sa_vtk_cell_data(v, "von_mises", 1, t->vm);
  if (!rc) rc = sa_vtk_cell_data(v, "eq_plastic_strain", 1, t->epsp);
  if (!rc) rc = sa_vtk_cell_data(v, "yield_region", 1, t->region);
  if (rc) {
    sa_vtk_abort(&v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  SA_CHECK(sa_vtk_commit(&v));
  SA_CHECK(sa_vtk_series_add(t->series, name, t->step));
  return 0;
}

static int output_step(Tx *t, int last) {
  double sa, ea, ev;
  SA_CHECK(axial_stress(t, &sa, &ea, &ev));
  double sc = t->sc->tx.confining_pressure, q = sa - sc;
  fem_fill_history_mean(t->s, 6, t->epsp);
  double ep = 0;
  for (int e = 0; e < t->m->nelem; e++) ep += t->epsp[e] / t->m->nelem;
  FemSolveReport rep;
  fem_solver_report(t->s, &rep);
  double row[] = {t->step, ea, q, q / 1e3, ev, sa, sc, ep, t->q_cf, rep.newton_iters};
  SA_CHECK(sa_csv_row(t->csv, row));
  if (t->step > 0 && q > t->peak_q) t->peak_q = q, t->eps_at_peak = ea, t->peak_q_tau = t->J * q,
    t->peak_q_tau_cf = t->q_cf + (t->J - 1) * (t->q_cf - q_closed_form(&t->sc->fill, 0));
  t->q_prev = t->q_last, t->q_last = q;
  t->ea_prev = t->ea_last, t->ea_last = ea;
  t->ev_prev = t->ev_last, t->ev_last = ev;
  int every = t->sc->tx.vtk_every;
  if ((every > 0 && t->step % every == 0) || last) SA_CHECK(write_vtk(t));
  sa_log(SA_LOG_INFO, "fem", "triaxial step %3d: axial strain %.5f, q = %.6g Pa (closed form "
         "%.6g), volumetric strain %+.5f, eps_p %.3g", t->step, ea, q, t->q_cf, ev, ep);
  return 0;
}

/* gnuplot runs in the results folder (sa_plot.c), beside the CSV: named without a folder */
static int make_plots(const SaRun *run) {
  char png[SA_STR_MAX];
  SA_CHECK(sa_run_path(run, "q_axial_strain.png", png));
  char body[4 * SA_STR_MAX];
  snprintf(body, sizeof body,
           "set datafile separator ','\nset key bottom right\nset grid\n"
           "set title 'Drained triaxial compression (Mohr-Coulomb)'\n"
           "set xlabel 'axial strain (log) [-]'\nset ylabel 'q = sigma1 - sigma3 [kPa]'\n"
           "plot '%s' using 2:4 skip 1 with linespoints pt 7 ps 0.6 title 'FEM (reaction / area)', "
           "'' using 2:($9/1000) skip 1 with lines dt 2 lw 2 title 'closed form "
           "sigma3 (N-1) + 2 c sqrt(N)'\n", "triaxial.csv");
  int rc = sa_plot_script(png, body);
  SA_CHECK(sa_run_path(run, "volumetric_strain.png", png));
  snprintf(body, sizeof body,
           "set datafile separator ','\nset key top left\nset grid\n"
           "set title 'Volumetric strain (compression positive)'\n"
           "set xlabel 'axial strain (log) [-]'\nset ylabel 'volumetric strain (log) [-]'\n"
           "plot '%s' using 2:5 skip 1 with linespoints pt 7 ps 0.6 title 'FEM'\n", "triaxial.csv");
  int rc2 = sa_plot_script(png, body);
  if (rc || rc2) sa_error_clear(); /* plots are optional; the data is in the CSV */
  return 0;
}

static int run_stages(Tx *t) {
  const TriaxParams *P = &t->sc->tx;
  const FemFillParams *f = &t->sc->fill;
  double sc = P->confining_pressure, L = P->size;
  double K = f->young / (3 * (1 - 2 * f->poisson)), J = 1;
  for (int i = 0; i < 100; i++) J = exp(-sc * J / K); /* isotropic: Kirchhoff -sc J = K ln J */
  double lam = cbrt(J), uz_iso = L * (lam - 1);
  SA_CHECK(fem_solver_set_pressure(t->s, sc));
  SA_CHECK(fem_solver_set_prescribed(t->s, t->top->nnodes, t->top->nodes, 2, uz_iso));
  SA_CHECK(fem_solver_solve(t->s));
  const double *x = fem_solver_positions(t->s);
  t->H_c = x[3 * t->corner + 2];
  t->V_c = x[3 * t->corner] * x[3 * t->corner + 1] * t->H_c;
  t->step = 0;
  SA_CHECK(output_step(t, 0));
  double ea_end = P->axial_strain > 0 ? P->axial_strain : 4 * t->q_cf / f->young;
  for (t->step = 1; t->step <= P->steps; t->step++) {
    if (sa_interrupted()) return SA_ERROR(SA_ERR_INTERRUPTED, "interrupted at step %d", t->step);
    double h = t->H_c * exp(-ea_end * t->step / P->steps);
    SA_CHECK(fem_solver_set_prescribed(t->s, t->top->nnodes, t->top->nodes, 2, h - L));
    int rc = fem_solver_solve(t->s);
    if (rc) {
      sa_log(rc == SA_ERR_INTERRUPTED ? SA_LOG_WARN : SA_LOG_ERROR, "fem", "compression stopped "
             "at step %d; results up to step %d are written", t->step, t->step - 1);
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
    SA_CHECK(output_step(t, t->step == P->steps));
  }
  return 0;
}

static int triax_run(void *scene, SaRun *run) {
  TriaxScene *sc = scene;
  double t_start = sa_time_now();
  Tx t = {.sc = sc, .run = run};
  t.q_cf = q_closed_form(&sc->fill, sc->tx.confining_pressure);
  t.peak_q = -INFINITY;
  CubeCtx cc = {sc->tx.size, NULL};
  FemMeshBlock blk = {{1, 1, 1}, map_cube, &cc, {"x0", "x1", "y0", "y1", "bottom", "top"}};
  SA_CHECK(fem_mesh_blocks(1, &blk, 1, 1e-9 * sc->tx.size, &t.m));
  FemMaterial mat;
  int rc = fem_fill_material(&sc->fill, &mat);
  FemSolverParams prm = fem_actuator_solver_params(&sc->act, 1);
  if (!rc) rc = fem_solver_create(t.m, &mat, &prm, &t.s);
  if (!rc) rc = fem_solver_fix_surface(t.s, "x0", FEM_X);
  if (!rc) rc = fem_solver_fix_surface(t.s, "y0", FEM_Y);
  if (!rc) rc = fem_solver_fix_surface(t.s, "bottom", FEM_Z);
  if (!rc) rc = fem_solver_fix_surface(t.s, "top", FEM_Z);
  if (!rc) rc = fem_solver_add_pressure_surface(t.s, "x1");
  if (!rc) rc = fem_solver_add_pressure_surface(t.s, "y1");
  const FemSurface *fx = fem_mesh_find_surface(t.m, "x1"), *fy = fem_mesh_find_surface(t.m, "y1");
  Ties ties = {{fx->nnodes, fy->nnodes}, {fx->nodes, fy->nodes}, 100 * sc->fill.young * cc.L, t.m};
  FemContributor tc = {"lateral face ties", ties_candidates, ties_eval, &ties, NULL};
  if (!rc) rc = fem_solver_add_contributor(t.s, &tc);
  if (!rc) rc = fem_solver_setup(t.s);
  int ne = t.m->nelem;
  t.top = fem_mesh_find_surface(t.m, "top");
  t.corner = -1;
  for (int a = 0; a < t.m->nnodes; a++) {
    const double *X = t.m->xyz + 3 * a;
    if (fabs(X[0] - cc.L) + fabs(X[1] - cc.L) + fabs(X[2] - cc.L) < 1e-9 * cc.L) t.corner = a;
  }
  t.react = malloc(sizeof(double) * 3 * t.m->nnodes);
  t.sigma = malloc(sizeof(double) * 9 * ne);
  t.vm = malloc(sizeof(double) * ne);
  t.epsp = malloc(sizeof(double) * ne);
  t.region = malloc(sizeof(double) * ne);
  t.cell_types = malloc(sizeof(int) * ne);
  t.cell_off = malloc(sizeof(int) * (ne + 1));
  if (!rc && !(t.react && t.sigma && t.vm && t.epsp && t.region && t.cell_types && t.cell_off))
    rc = SA_ERROR(SA_ERR_MEMORY, "output buffers");
  if (!rc && t.corner < 0) rc = SA_ERROR(SA_ERR_INTERNAL, "cube corner node not found");
  if (!rc) {
    for (int e = 0; e < ne; e++) t.cell_types[e] = SA_VTK_TETRA, t.cell_off[e] = 4 * e;
    t.cell_off[ne] = 4 * ne;
  }
  char path[SA_STR_MAX];
  const char *names[] = {"step", "axial_strain", "q", "q_kpa", "volumetric_strain",
                         "sigma_axial", "sigma_lateral", "eq_plastic_strain", "q_closed_form",
                         "newton_iterations"};
  const char *units[] = {"-", "-", "Pa", "kPa", "-", "Pa", "Pa", "-", "Pa", "-"};
  if (!rc) rc = sa_run_path(run, "triaxial.csv", path);
  if (!rc) rc = sa_csv_open(path, 10, names, units, &t.csv);
  if (!rc) rc = sa_run_path(run, "triaxial.vtk.series", path);
  if (!rc) rc = sa_vtk_series_open(path, &t.series);
  if (!rc) rc = run_stages(&t);
  int rc_run = rc;
  if (t.csv) {
    int r2 = sa_csv_commit(&t.csv);
    if (!rc) rc = r2;
  }
  sa_vtk_series_close(&t.series);
  if (!rc && run->params.plots) rc = make_plots(run);

  if (t.s && t.step > 0) {
    FemSolverStats st;
    fem_solver_stats(t.s, &st);
    double s = sin(sc->fill.dilation_angle * M_PI / 180);
    double dil = -(t.ev_last - t.ev_prev) / (t.ea_last - t.ea_prev);
    /* failure reached: q flat over the last step (perfect plasticity) and every element plastic */
    fem_fill_history_mean(t.s, 6, t.epsp);
    int plastic = 1;
    for (int e = 0; e < ne; e++) plastic &= t.epsp[e] > 0;
    int reached = plastic && fabs(t.q_last - t.q_prev) <= 1e-3 * fabs(t.q_cf);
    SaFile *f = NULL;
    if (sa_run_path(run, "summary.ini", path) == 0 && sa_file_open(path, &f) == 0) {
      FILE *fp = sa_file_stream(f);
      fprintf(fp, "; softact drained triaxial compression (Mohr-Coulomb) summary\n"
              "; q = sigma1 - sigma3, Cauchy, compression positive; strains are log strains\n");
      fprintf(fp, "confining_pressure = %.9g ; Pa\nfriction_angle = %.9g ; deg\ncohesion = %.9g "
              "; Pa\ndilation_angle = %.9g ; deg\n", sc->tx.confining_pressure,
              sc->fill.friction_angle, sc->fill.cohesion, sc->fill.dilation_angle);
      fprintf(fp, "peak_q = %.12g ; Pa\npeak_q_closed_form = %.12g ; Pa, sigma3 (N - 1) + 2 c "
              "sqrt(N)\npeak_q_rel_error = %.3e\naxial_strain_at_peak = %.6g\nfailure_reached = %d\n",
              t.peak_q, t.q_cf, (t.peak_q - t.q_cf) / t.q_cf, t.eps_at_peak, reached);
      fprintf(fp, "peak_q_kirchhoff = %.12g ; Pa, J q at the peak (the yield surface is written in "
              "Kirchhoff stress tau = J sigma)\npeak_q_kirchhoff_closed_form = %.12g ; Pa, J sigma3 "
              "(N - 1) + 2 c sqrt(N): exact up to the solver tolerance; the Cauchy peak_q differs "
              "from its closed form by about 2 c sqrt(N) |1/J - 1| / q\n"
              "peak_q_kirchhoff_rel_error = %.3e\n", t.peak_q_tau, t.peak_q_tau_cf,
              (t.peak_q_tau - t.peak_q_tau_cf) / t.peak_q_tau_cf);
      fprintf(fp, "final_volumetric_strain = %.6g\ndilatancy_rate = %.6g ; -d eps_v / d eps_a "
              "over the last step, total strains\ndilatancy_rate_closed_form = %.6g ; plastic "
              "strains: 2 sin psi / (1 - sin psi); the elastic strains change too when J does "
              "(constant Cauchy confinement), noticeably when the stresses are not small against E\n",
              t.ev_last, dil, 2 * s / (1 - s));
      fprintf(fp, "nodes = %d\nelements = %d\nelement = tet4\nsteps = %d\n"
              "factorisations = %d\ncholesky = %d\nlu = %d\nwall_s = %.3f\nstatus = %s\n",
              st.nnodes, st.nelem, t.step, st.n_factor, st.n_chol, st.n_lu,
              sa_time_now() - t_start, rc_run ? "stopped early" : "completed");
      if (sa_file_commit(&f)) sa_error_clear();
    } else {
      sa_error_clear();
    }
    if (!reached)
      sa_log(SA_LOG_WARN, "fem", "failure not reached (q still changing or an element elastic): "
             "raise [triaxial] axial_strain");
    sa_log(SA_LOG_INFO, "fem", "peak q = %.6g Pa, closed form %.6g Pa (%+.2e relative)",
           t.peak_q, t.q_cf, (t.peak_q - t.q_cf) / t.q_cf);
  }
  if (t.csv) sa_csv_abort(&t.csv);
  fem_solver_destroy(&t.s);
  free(t.react);
  free(t.sigma);
  free(t.vm);
  free(t.epsp);
  free(t.region);
  free(t.cell_types);
  free(t.cell_off);
  fem_mesh_destroy(&t.m);
  return rc ? sa_error_push(rc, __func__, __FILE__, __LINE__) : 0;
}

const SaModule fem_triaxial_module = {
    .name = "triaxial",
    .trigger = "triaxial",
    .help = "drained triaxial compression of a Mohr-Coulomb sample (verification)",
    .tables = triax_tables,
    .ntables = 3,
    .check = triax_check,
    .write_resolved = triax_write_resolved,
    .run = triax_run,
    .destroy = triax_destroy,
};
