/* fem_scene.c - the fem module: case-file tables and the pressure-bending scene.
 *
 * Scene (cases/pressure_bending.ini): the reference actuator (meshes/actuator.geo,
 * /work/shared/ACTUATOR.md) clamped on `fixed_end`, a follower pressure on `cavity_wall`,
 * ramped in n_steps. control = pressure: load control (stops at a limit point); volume: the
 * cavity volume is ramped instead and the pressure is the unknown; auto: pressure control, and
 * at a limit point the ramp continues under volume control with the volume increment of the
 * last pressure step. The ramp also stops once the bending angle reaches angle_stop.
 * Outputs in the run folder:
 *   bending.csv           step, pressure, bending angle, cavity volume and its change, tip
 *   bending_angle.png     angle versus pressure; volume.png  volume change versus pressure
 *   centerline_NNNN.csv   deformed centre-line per step (fem_centerline)
 *   fem_NNNN.vtk + fem.vtk.series   tet10 (or tet4) cells: displacement; Cauchy stress,
 *                         von Mises stress, principal stretches (element averages), region
 *   summary.ini           mesh, solver statistics and timings (key = value, as every scene) */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "fem_actuator.h"
#include "sa_csv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_plot.h"
#include "sa_vtk.h"

typedef struct {
  char control[SA_STR_MAX];
  double p_max, volume_ratio_max, angle_stop;
  int n_steps, max_steps, gravity;
  char pressure_surface[SA_STR_MAX], fixed_surface[SA_STR_MAX];
} FemLoadParams;

typedef struct {
  int vtk_every, centerline_slices;
  char tip_surface[SA_STR_MAX];
} FemOutParams;

#define P(f) offsetof(FemLoadParams, f)
static const SaParam load_params[] = {
    {"control", SA_PARAM_CHOICE, P(control), "-", "auto", 0, 0, 0, "auto|pressure|volume",
     "pressure (load) control, cavity-volume control, or pressure then volume past a limit point"},
    {"p_max", SA_PARAM_REAL, P(p_max), "Pa", "60e3", 0, INFINITY, SA_MIN_OPEN, NULL,
     "final cavity pressure (pressure/auto control)"},
    {"volume_ratio_max", SA_PARAM_REAL, P(volume_ratio_max), "-", "4", 1, 100, SA_MIN_OPEN, NULL,
     "final cavity volume / initial (volume control; cap of the auto continuation)"},
    {"n_steps", SA_PARAM_INT, P(n_steps), "-", "12", 1, 10000, 0, NULL,
     "output steps of the ramp (the solver substeps itself when needed)"},
    {"max_steps", SA_PARAM_INT, P(max_steps), "-", "60", 1, 100000, 0, NULL,
     "cap on the output steps including the volume-control continuation"},
    {"angle_stop", SA_PARAM_REAL, P(angle_stop), "deg", "150", 0, 180, SA_MIN_OPEN, NULL,
     "stop the ramp once the bending angle reaches this"},
    {"gravity", SA_PARAM_BOOL, P(gravity), "-", "0", 0, 0, 0, NULL,
     "apply gravity (-z, 9.81 m/s^2) with the pressure"},
    {"pressure_surface", SA_PARAM_STRING, P(pressure_surface), "-", "cavity_wall", 0, 0, 0, NULL,
     "mesh surface carrying the follower pressure"},
    {"fixed_surface", SA_PARAM_STRING, P(fixed_surface), "-", "fixed_end", 0, 0, 0, NULL,
     "mesh surface clamped in x, y and z"},
};
#undef P
#define P(f) offsetof(FemOutParams, f)
static const SaParam out_params[] = {
    {"vtk_every", SA_PARAM_INT, P(vtk_every), "-", "1", 0, 100000, 0, NULL,
     "write a VTK file every this many steps (0 = none; the last step is always written)"},
    {"centerline_slices", SA_PARAM_INT, P(centerline_slices), "-", "42", 2, 10000, 0, NULL,
     "slices of the deformed centre-line"},
    {"tip_surface", SA_PARAM_STRING, P(tip_surface), "-", "tip", 0, 0, 0, NULL,
     "surface whose mean normal defines the bending angle"},
};
#undef P

static const SaParamTable load_table = {"loading", "fem", "FEM loads, supports and ramp control",
                                        load_params, SA_NPARAMS(load_params)};
static const SaParamTable out_table = {"output", "fem", "FEM outputs", out_params,
                                       SA_NPARAMS(out_params)};
static const SaParamTable *const fem_tables[] = {
    &fem_actuator_mesh_table, &fem_actuator_material_table, &load_table,
    &fem_actuator_solver_table, &out_table};

typedef struct {
  FemActuatorCase act;
  FemLoadParams load;
  FemOutParams out;
} FemScene;

static int fem_check(const SaCase *c, void **out) {
  *out = NULL;
  FemScene *s;
  SA_CALLOC(s, 1);
  int rc = fem_actuator_load(c, &s->act);
  if (!rc) rc = sa_params_load(&load_table, c, &s->load);
  if (!rc) rc = sa_params_load(&out_table, c, &s->out);
  if (!rc && s->load.max_steps < s->load.n_steps)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [loading] max_steps = %d < n_steps = %d", sa_case_path(c),
                  s->load.max_steps, s->load.n_steps);
  if (rc) {
    free(s);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = s;
  return 0;
}

static void fem_write_resolved(const void *scene, FILE *f) {
  const FemScene *s = scene;
  /* section order as in the tables: mesh, material, loading, solver, output */
  sa_params_write(&fem_actuator_mesh_table, &s->act.mesh, f);
  fprintf(f, "\n");
  sa_params_write(&fem_actuator_material_table, &s->act.mat, f);
  fprintf(f, "\n");
  sa_params_write(&load_table, &s->load, f);
  fprintf(f, "\n");
  sa_params_write(&fem_actuator_solver_table, &s->act.solver, f);
  fprintf(f, "\n");
  sa_params_write(&out_table, &s->out, f);
  fprintf(f, "\n");
}

static void fem_destroy(void **scene) {
  if (!scene) return;
  free(*scene);
  *scene = NULL;
}

typedef struct {
  const FemScene *sc;
  const SaRun *run;
  FemSolver *s;
  const FemMesh *m;
  SaCsv *csv;
  SaVtkSeries *series;
  int step, *cell_types, *cell_off;
  double V0, angle, angle_prev, z_lo, z_hi;
  double *sigma, *vm, *lam, *reg;
  double tip0[3];
} Out;

static void tip_centroid(const FemMesh *m, const char *tip, const double *x, double c[3]) {
  const FemSurface *t = fem_mesh_find_surface(m, tip);
  c[0] = c[1] = c[2] = 0;
  if (!t || !t->nnodes) return;
  for (int k = 0; k < t->nnodes; k++)
    for (int i = 0; i < 3; i++) c[i] += x[3 * t->nodes[k] + i] / t->nnodes;
}

static int write_vtk(Out *o) {
  const FemMesh *m = o->m;
  char name[64], path[SA_STR_MAX];
  snprintf(name, sizeof name, "fem_%04d.vtk", o->step);
  SA_CHECK(sa_run_path(o->run, name, path));
  SA_CHECK(fem_solver_element_stress(o->s, o->sigma, o->vm, o->lam));
  SaVtk *v;
  char title[128];
  snprintf(title, sizeof title, "softact fem step %d p = %.6g Pa", o->step,
           fem_solver_pressure(o->s));
  SA_CHECK(sa_vtk_grid_open(path, o->run->vtk, title, m->nnodes, fem_solver_positions(o->s),
                            m->nelem, o->cell_types, o->cell_off, m->conn, &v));
  int rc = sa_vtk_point_data(v, "displacement", 3, fem_solver_displacements(o->s));
  if (!rc) rc = sa_vtk_cell_data(v, "cauchy_stress", 9, o->sigma);
  if (!rc) rc = sa_vtk_cell_data(v, "von_mises", 1, o->vm);
  if (!rc) rc = sa_vtk_cell_data(v, "principal_stretch", 3, o->lam);
  if (!rc) rc = sa_vtk_cell_data(v, "region", 1, o->reg);
  if (rc) {
    sa_vtk_abort(&v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  SA_CHECK(sa_vtk_commit(&v));
  /* the series' time is the load ParaView users scrub through: the cavity pressure [kPa] */
  SA_CHECK(sa_vtk_series_add(o->series, name, fem_solver_pressure(o->s) / 1e3));
  return 0;
}

/* After every output step: CSV row, centre-line, VTK. */
static int output_step(Out *o, int last) {
  const FemMesh *m = o->m;
  const double *x = fem_solver_positions(o->s);
  double ang;
  SA_CHECK(fem_bending_angle(m, o->sc->out.tip_surface, x, &ang));
  /* unwrap across +-180 */
  while (ang - o->angle_prev > 180) ang -= 360;
  while (ang - o->angle_prev < -180) ang += 360;
  o->angle = o->angle_prev = ang;
  double V = fem_solver_cavity_volume(o->s), p = fem_solver_pressure(o->s), tc[3];
  tip_centroid(m, o->sc->out.tip_surface, x, tc);
  FemSolveReport rep;
  fem_solver_report(o->s, &rep);
  double row[] = {o->step, p, p / 1e3, ang, V, V - o->V0, V / o->V0 - 1, tc[0] - o->tip0[0],
                  tc[2] - o->tip0[2], rep.newton_iters};
  SA_CHECK(sa_csv_row(o->csv, row));

  int ns = o->sc->out.centerline_slices;
  double *zr = malloc(sizeof(double) * ns), *cl = malloc(sizeof(double) * 3 * ns);
  SA_REQUIRE(zr && cl, SA_ERR_MEMORY, "centre-line buffers");
  int rc = fem_centerline(m, x, o->z_lo, o->z_hi, ns, zr, cl);
  char name[64], path[SA_STR_MAX];
  snprintf(name, sizeof name, "centerline_%04d.csv", o->step);
  if (!rc) rc = sa_run_path(o->run, name, path);
  SaCsv *c = NULL;
  const char *cn[] = {"z_ref", "x", "y", "z"}, *cu[] = {"m", "m", "m", "m"};
  if (!rc) rc = sa_csv_open(path, 4, cn, cu, &c);
  for (int k = ns - 1; k >= 0 && !rc; k--) { /* from the clamped top to the tip */
    double r4[4] = {zr[k], cl[3 * k], cl[3 * k + 1], cl[3 * k + 2]};
    rc = sa_csv_row(c, r4);
  }
  if (!rc) rc = sa_csv_commit(&c);
  else sa_csv_abort(&c);
  free(zr);
  free(cl);
  SA_CHECK(rc);
  int every = o->sc->out.vtk_every;
  if ((every > 0 && o->step % every == 0) || last) SA_CHECK(write_vtk(o));
  sa_log(SA_LOG_INFO, "fem", "step %3d: p = %8.3f kPa, bending angle %7.2f deg, cavity volume "
         "%+.2f %% (%d Newton iterations, %d substeps)", o->step, p / 1e3, ang,
         100 * (V / o->V0 - 1), rep.newton_iters, rep.substeps);
  return 0;
}

static int make_plots(const SaRun *run) {
  char csv[SA_STR_MAX], png[SA_STR_MAX];
  SA_CHECK(sa_run_path(run, "bending.csv", csv));
  SA_CHECK(sa_run_path(run, "bending_angle.png", png));
  SaPlotAxes ax = {"Bending angle of the pressurised actuator", "cavity pressure [kPa]",
                   "bending angle [deg]", 0, 0, 0, 0};
  SaPlotSeries sr = {csv, 3, 4, "FEM (tet mixed, follower pressure)", "linespoints pt 7 ps 0.6"};
  int rc = sa_plot_lines(png, &ax, 1, &sr);
  SA_CHECK(sa_run_path(run, "volume.png", png));
  SaPlotAxes ax2 = {"Cavity volume change", "cavity pressure [kPa]", "V/V0 - 1 [-]", 0, 0, 0, 0};
  SaPlotSeries sr2 = {csv, 3, 7, "FEM", "linespoints pt 7 ps 0.6"};
  int rc2 = sa_plot_lines(png, &ax2, 1, &sr2);
  if (rc || rc2) sa_error_clear(); /* plots are optional; the data is in the CSV */
  return 0;
}

static int run_ramp(Out *o) {
  const FemLoadParams *L = &o->sc->load;
  FemSolver *s = o->s;
  int volume = !strcmp(L->control, "volume"), autoc = !strcmp(L->control, "auto");
  double V0 = o->V0, dV = 0, Vlast = V0;
  if (volume) {
    SA_CHECK(fem_solver_set_control(s, FEM_CONTROL_VOLUME));
    dV = V0 * (L->volume_ratio_max - 1) / L->n_steps;
  }
  for (o->step = 1; o->step <= L->max_steps; o->step++) {
    if (sa_interrupted()) return SA_ERROR(SA_ERR_INTERRUPTED, "interrupted at step %d", o->step);
    if (!volume && o->step > L->n_steps) break;
    if (volume) {
      double Vt = Vlast + dV;
      if (Vt > L->volume_ratio_max * V0 * (1 + 1e-12)) break;
      SA_CHECK(fem_solver_set_volume(s, Vt));
    } else {
      SA_CHECK(fem_solver_set_pressure(s, L->p_max * o->step / L->n_steps));
    }
    int rc = fem_solver_solve(s);
    if (rc == SA_ERR_LIMIT_POINT && autoc && !volume) {
      FemSolveReport rep;
      fem_solver_report(s, &rep);
      sa_log(SA_LOG_WARN, "fem", "%s", rep.reason);
      sa_log(SA_LOG_INFO, "fem", "control = auto: continuing under volume control");
      sa_error_clear();
      SA_CHECK(fem_solver_set_control(s, FEM_CONTROL_VOLUME));
      volume = 1;
      double Vnow = fem_solver_cavity_volume(s);
      dV = fmax(Vnow - Vlast, 0.02 * V0);
      if (Vnow > Vlast * (1 + 1e-9)) { /* the partial step converged: report it */
        Vlast = Vnow;
        SA_CHECK(output_step(o, 0));
      } else {
        o->step--;
      }
      continue;
    }
    if (rc) {
      sa_log(rc == SA_ERR_INTERRUPTED ? SA_LOG_WARN : SA_LOG_ERROR, "fem",
             "ramp stopped at step %d; results up to step %d are written", o->step, o->step - 1);
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
    Vlast = fem_solver_cavity_volume(s);
    int last = (!volume && o->step == L->n_steps);
    SA_CHECK(output_step(o, last));
    if (o->angle >= L->angle_stop) {
      sa_log(SA_LOG_INFO, "fem", "bending angle %.1f deg >= angle_stop: ramp ends", o->angle);
      break;
    }
  }
  return 0;
}

static int fem_run(void *scene, SaRun *run) {
  FemScene *sc = scene;
  double t_start = sa_time_now();
  FemMesh *m = NULL;
  SA_CHECK(fem_actuator_mesh(&sc->act, &m));
  Out o = {.sc = sc, .run = run, .m = m};
  FemMaterial *mats = calloc((size_t)(m->nregions > 0 ? m->nregions : 1), sizeof *mats);
  int rc = mats ? 0 : SA_ERROR(SA_ERR_MEMORY, "materials");
  const char *surfs[] = {sc->load.pressure_surface, sc->load.fixed_surface, sc->out.tip_surface};
  if (!rc) rc = fem_mesh_require(m, 0, NULL, 3, surfs);
  if (!rc) rc = fem_actuator_materials(&sc->act, m, mats);
  FemSolverParams prm = fem_actuator_solver_params(&sc->act, run->threads);
  if (!rc) rc = fem_solver_create(m, mats, &prm, &o.s);
  if (!rc) rc = fem_solver_fix_surface(o.s, sc->load.fixed_surface, FEM_XYZ);
  if (!rc) rc = fem_solver_add_pressure_surface(o.s, sc->load.pressure_surface);
  if (!rc && sc->load.gravity) rc = fem_solver_set_gravity(o.s, (const double[3]){0, 0, -9.81});
  if (!rc) rc = fem_solver_setup(o.s);
  /* output buffers */
  o.cell_types = malloc(sizeof(int) * m->nelem);
  o.cell_off = malloc(sizeof(int) * (m->nelem + 1));
  o.sigma = malloc(sizeof(double) * 9 * m->nelem);
  o.vm = malloc(sizeof(double) * m->nelem);
  o.lam = malloc(sizeof(double) * 3 * m->nelem);
  o.reg = malloc(sizeof(double) * m->nelem);
  if (!rc && !(o.cell_types && o.cell_off && o.sigma && o.vm && o.lam && o.reg))
    rc = SA_ERROR(SA_ERR_MEMORY, "output buffers");
  if (!rc) {
    for (int e = 0; e < m->nelem; e++) {
      o.cell_types[e] = m->nen == 10 ? SA_VTK_QUADRATIC_TETRA : SA_VTK_TETRA;
      o.cell_off[e] = e * m->nen;
      o.reg[e] = m->region ? m->region[e] : 0;
    }
    o.cell_off[m->nelem] = m->nelem * m->nen;
    o.z_lo = INFINITY, o.z_hi = -INFINITY;
    for (int i = 0; i < m->nnodes; i++) {
      o.z_lo = fmin(o.z_lo, m->xyz[3 * i + 2]);
      o.z_hi = fmax(o.z_hi, m->xyz[3 * i + 2]);
    }
    o.V0 = fem_solver_cavity_volume(o.s);
    tip_centroid(m, sc->out.tip_surface, m->xyz, o.tip0);
  }
  char path[SA_STR_MAX];
  const char *names[] = {"step", "pressure", "pressure_kpa", "bending_angle", "cavity_volume",
                         "volume_change", "volume_change_rel", "tip_dx", "tip_dz",
                         "newton_iterations"};
  const char *units[] = {"-", "Pa", "kPa", "deg", "m^3", "m^3", "-", "m", "m", "-"};
  if (!rc) rc = sa_run_path(run, "bending.csv", path);
  if (!rc) rc = sa_csv_open(path, 10, names, units, &o.csv);
  if (!rc) rc = sa_run_path(run, "fem.vtk.series", path);
  if (!rc) rc = sa_vtk_series_open(path, &o.series);
  if (!rc) {
    o.step = 0;
    rc = output_step(&o, 0); /* the reference state, step 0 */
  }
  if (!rc) rc = run_ramp(&o);
  int rc_ramp = rc;
  /* commit what was computed even if the ramp failed */
  if (o.csv) {
    int r2 = sa_csv_commit(&o.csv);
    if (!rc) rc = r2;
  }
  sa_vtk_series_close(&o.series);
  if (!rc && run->params.plots) rc = make_plots(run);

  /* summary */
  if (o.s) {
    FemSolverStats st;
    fem_solver_stats(o.s, &st);
    SaFile *f = NULL;
    if (sa_run_path(run, "summary.ini", path) == 0 && sa_file_open(path, &f) == 0) {
      FILE *fp = sa_file_stream(f);
      fprintf(fp, "; softact fem pressure bending summary\n");
      fprintf(fp, "nodes = %d\nelements = %d\nelement = %s\nfree_dofs = %d\nnnz_K = %ld\n"
              "nnz_L = %.0f\n", st.nnodes, st.nelem, m->nen == 10 ? "tet10" : "tet4", st.nfree,
              st.nnz_k, st.nnz_l);
      fprintf(fp, "final_pressure = %.9g ; Pa\nfinal_bending_angle = %.6f ; deg\n"
              "final_volume_ratio = %.6f\n", fem_solver_pressure(o.s), o.angle,
              fem_solver_cavity_volume(o.s) / o.V0);
      fprintf(fp, "assemblies = %d\nassemble_s = %.3f\nfactorisations = %d\ncholesky = %d\n"
              "lu = %d\nreused_factors = %d\nfactorise_s = %.3f\nsolves = %d\nsolve_s = %.3f\n"
              "symbolic_s = %.3f\nwall_s = %.3f\nstatus = %s\n", st.n_assemble, st.t_assemble,
              st.n_factor, st.n_chol, st.n_lu, st.n_reuse, st.t_factor, st.n_solve, st.t_solve,
              st.t_symbolic, sa_time_now() - t_start, rc_ramp ? "ramp stopped early" : "completed");
      if (sa_file_commit(&f)) sa_error_clear();
    } else {
      sa_error_clear();
    }
    sa_log(SA_LOG_INFO, "fem", "Newton: %d assemblies %.2f s, %d factorisations (%d Cholesky, "
           "%d LU) %.2f s, %d directions from reused factors, %d solves %.2f s", st.n_assemble,
           st.t_assemble, st.n_factor, st.n_chol, st.n_lu, st.t_factor, st.n_reuse, st.n_solve,
           st.t_solve);
  }
  if (o.csv) sa_csv_abort(&o.csv);
  fem_solver_destroy(&o.s);
  free(mats);
  free(o.cell_types);
  free(o.cell_off);
  free(o.sigma);
  free(o.vm);
  free(o.lam);
  free(o.reg);
  fem_mesh_destroy(&m);
  return rc ? sa_error_push(rc, __func__, __FILE__, __LINE__) : 0;
}

const SaModule fem_module = {
    .name = "fem",
    .trigger = "mesh",
    .help = "nonlinear FEM of the soft actuator (pressure bending)",
    .tables = fem_tables,
    .ntables = 5,
    .check = fem_check,
    .write_resolved = fem_write_resolved,
    .run = fem_run,
    .destroy = fem_destroy,
};
