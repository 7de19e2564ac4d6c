/* fem_footing.c - rigid strip footing on a weightless Mohr-Coulomb layer (scene [footing],
 * cases/mc_footing.ini; fem_fill.h).
 *
 * Model (plane strain, half the problem by symmetry): a slab x in [0, W], z in [-D, 0], one
 * cell thick in y (thickness t = the smallest cell size) with u_y = 0 at every node; symmetry
 * u_x = 0 at x = 0, a roller u_x = 0 at x = W, the base z = -D fixed. The footing of width B
 * covers x in [0, B/2] of the top: its nodes get a prescribed settlement u_z (and u_x = 0 when
 * rough), ramped in `steps` output steps to `settlement` x B; each step is a solve with the
 * solver's cut-backs (a failed substep is cut and retried, never accepted). Weightless (no
 * gravity), no initial stress. W and D default to multiples of the extent of Prandtl's
 * mechanism. Two structured blocks of Kuhn-split hexahedra (tet10 by default), graded toward
 * the footing edge (x = B/2, z = 0): `cells` cells across the half footing with a power map
 * of exponent `grading`, cells sqrt(L / (B/2)) beside it and over the depth (L their extent)
 * with the power that makes the cells at the edge match; straight-sided elements.
 * Footing pressure p = -(sum of the support forces in z on the footing nodes) / (t B/2); the
 * limit pressure is the largest p of the ramp, reported with how much p still rose over the
 * last 10 % of the settlement (the plateau check).
 *
 * Reference (Prandtl 1920, weightless, associated flow; Terzaghi's N_c):
 *   N_q = e^(pi tan phi) tan^2(45 deg + phi/2),  N_c = (N_q - 1) cot phi  (2 + pi at phi = 0),
 *   bearing_capacity_factor = p_limit / c.
 * Displacement-based FE limit loads approach N_c from above as the mesh is refined (volumetric
 * locking of a dilatant/incompressible flow on coarse meshes); docs/mohr_coulomb.md has the
 * measured convergence.
 *
 * Outputs: footing.csv (settlement, pressure, p / c), pressure_settlement.png,
 * footing_NNNN.vtk + footing.vtk.series (displacement, Cauchy stress, equivalent plastic strain,
 * return region), summary.ini. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem_actuator.h"
#include "fem_fill.h"
#include "sa_csv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_plot.h"
#include "sa_vtk.h"

typedef struct {
  double width, domain_width, domain_depth, settlement, grading;
  int cells, order, steps, rough, vtk_every;
} FootParams;

#define P(f) offsetof(FootParams, f)
static const SaParam foot_params[] = {
    {"width", SA_PARAM_REAL, P(width), "m", "1", 0, 1e3, SA_MIN_OPEN, NULL,
     "footing width B (the model is the half x >= 0)"},
    {"domain_width", SA_PARAM_REAL, P(domain_width), "-", "0", 0, 100, 0, NULL,
     "half-width of the layer in footing widths B (0 = 0.5 + 1.5 L, L the surface extent of "
     "Prandtl's mechanism beyond the footing edge)"},
    {"domain_depth", SA_PARAM_REAL, P(domain_depth), "-", "0", 0, 100, 0, NULL,
     "depth of the layer in footing widths B (0 = 0.5 + 0.6 L)"},
    {"settlement", SA_PARAM_REAL, P(settlement), "-", "0.02", 0, 0.5, SA_MIN_OPEN, NULL,
     "final footing settlement in footing widths B"},
    {"steps", SA_PARAM_INT, P(steps), "-", "40", 2, 10000, 0, NULL,
     "output steps of the settlement ramp (the solver substeps itself when needed)"},
    {"cells", SA_PARAM_INT, P(cells), "-", "6", 1, 200, 0, NULL,
     "mesh refinement: cells across the half footing (cells sqrt(L / (B/2)) over a length L "
     "beside it and over the depth, graded so that the cells at the footing edge match)"},
    {"grading", SA_PARAM_REAL, P(grading), "-", "1.5", 1, 4, 0, NULL,
     "power of the mesh grading under the footing toward its edge (1 = uniform); the smallest "
     "cell is (B/2) cells^-grading"},
    {"order", SA_PARAM_INT, P(order), "-", "2", 1, 2, 0, NULL,
     "element order: 2 = tet10 (use this), 1 = tet4 (locks under plastic flow)"},
    {"rough", SA_PARAM_BOOL, P(rough), "-", "0", 0, 0, 0, NULL,
     "rough footing (u_x = 0 under it) instead of smooth"},
    {"vtk_every", SA_PARAM_INT, P(vtk_every), "-", "10", 0, 100000, 0, NULL,
     "write a VTK file every this many steps (0 = none; the last step is always written)"},
};
#undef P
static const SaParamTable foot_table = {"footing", "fem",
                                        "rigid strip footing on a weightless Mohr-Coulomb layer",
                                        foot_params, SA_NPARAMS(foot_params)};
static const SaParamTable *const foot_tables[] = {&foot_table, &fem_fill_table,
                                                  &fem_actuator_solver_table};

typedef struct {
  FootParams ft;
  FemFillParams fill;
  FemActuatorCase act; /* only .solver */
} FootScene;

/* Prandtl's N_c (weightless, Terzaghi's form) */
static double prandtl_nc(double phi_deg) {
  if (phi_deg == 0) return 2 + M_PI;
  double p = phi_deg * M_PI / 180, t = tan(M_PI / 4 + p / 2);
  double nq = exp(M_PI * tan(p)) * t * t;
  return (nq - 1) / tan(p);
}

/* Domain (in B) and cell counts of the mesh: Prandtl's mechanism, r0 = (B/2) / cos(45 + phi/2),
 * r1 = r0 e^(pi/2 tan phi), the passive wedge reaches L = 2 r1 cos(45 - phi/2) beyond the
 * footing edge (1 B at phi = 0, 4.3 B at 30 deg); beside the footing and over the depth
 * n sqrt(L / (B/2)) cells, graded with the power that makes the first cell at the edge equal
 * the smallest one. Counts as doubles: the check compares them before they become ints. */
static void foot_grid(const FootScene *sc, double *dw, double *dd, double *nb, double *nz) {
  const FootParams *F = &sc->ft;
  double ph = sc->fill.friction_angle * M_PI / 180;
  double Lm = 2 * 0.5 / cos(M_PI / 4 + ph / 2) * exp(M_PI / 2 * tan(ph)) * cos(M_PI / 4 - ph / 2);
  *dw = F->domain_width > 0 ? F->domain_width : 0.5 + 1.5 * Lm;
  *dd = F->domain_depth > 0 ? F->domain_depth : 0.5 + 0.6 * Lm;
  *nb = fmax(2.0, ceil(F->cells * sqrt((*dw - 0.5) / 0.5)));
  *nz = fmax(2.0, ceil(F->cells * sqrt(*dd / 0.5)));
}

/* Tetrahedra the footing mesh may have (6 per cell): cells and the domain keys multiply, and
 * the element arrays and the sparse factors grow with (faster than) their count. */
#define FOOT_MAX_TETS 2e6

static int foot_check(const SaCase *c, void **out) {
  *out = NULL;
  FootScene *s;
  SA_CALLOC(s, 1);
  int rc = sa_params_load(&foot_table, c, &s->ft);
  if (!rc) rc = fem_fill_load(c, &s->fill);
  if (!rc) rc = sa_params_load(&fem_actuator_solver_table, c, &s->act.solver);
  if (!rc && s->ft.domain_width > 0 && s->ft.domain_width <= 0.5)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [footing] domain_width = %g: expected 0 (automatic) or a "
                  "value in (0.5, 100] (the layer must be wider than the half footing)",
                  sa_case_path(c), s->ft.domain_width);
  if (!rc && s->ft.domain_depth > 0 && s->ft.domain_depth < 0.5)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [footing] domain_depth = %g: expected 0 (automatic) or a "
                  "value in [0.5, 100]", sa_case_path(c), s->ft.domain_depth);
  if (!rc) {
    double dw, dd, nb, nz;
    foot_grid(s, &dw, &dd, &nb, &nz);
    double ntet = 6.0 * (s->ft.cells + nb) * nz;
    if (ntet > FOOT_MAX_TETS)
      rc = SA_ERROR(SA_ERR_INPUT, "%s: [footing] cells = %d with domain_width = %g, domain_depth "
                    "= %g (B) makes (%d + %.0f) x %.0f cells = %.3g tetrahedra; at most %.0e are "
                    "allowed (lower cells or the domain)", sa_case_path(c), s->ft.cells, dw, dd,
                    s->ft.cells, nb, nz, ntet, FOOT_MAX_TETS);
  }
  if (!rc && !(s->fill.cohesion > 0))
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [fill] cohesion = %g: the footing scene reports p / c, "
                  "expected cohesion > 0", sa_case_path(c), s->fill.cohesion);
  if (rc) {
    free(s);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = s;
  return 0;
}

static void foot_write_resolved(const void *scene, FILE *f) {
  const FootScene *s = scene;
  sa_params_write(&foot_table, &s->ft, f);
  fprintf(f, "\n");
  sa_params_write(&fem_fill_table, &s->fill, f);
  fprintf(f, "\n");
  sa_params_write(&fem_actuator_solver_table, &s->act.solver, f);
  fprintf(f, "\n");
}

static void foot_destroy(void **scene) {
  if (!scene) return;
  free(*scene);
  *scene = NULL;
}

/* Block maps. xi0 -> x, xi1 -> y (one cell), xi2 -> z. Power grading toward the footing edge:
 * under the footing x = (B/2)(1 - (1 - xi)^g); beside it x = B/2 + (W - B/2) xi^gb;
 * z = -D (1 - xi)^gz, with gb, gz such that the first cell beside / below the edge equals the
 * last one under the footing, (B/2)(1/cells)^g. */
typedef struct {
  double b2, W, D, t, g, gb, gz;
  int side; /* 0: under the footing, 1: beside it */
} FootMap;

static void map_foot(const double xi[3], const void *ctx, double X[3]) {
  const FootMap *m = ctx;
  X[0] = m->side == 0 ? m->b2 * (1 - pow(1 - xi[0], m->g))
                      : m->b2 + (m->W - m->b2) * pow(xi[0], m->gb);
  X[1] = m->t * xi[1];
  X[2] = -m->D * pow(1 - xi[2], m->gz);
}

typedef struct {
  const FootScene *sc;
  const SaRun *run;
  FemSolver *s;
  FemMesh *m;
  const FemSurface *foot;
  int step, cuts, iters, *cell_types, *cell_off;
  double *react, *sigma, *vm, *epsp, *region;
  double area, B, p_max, p_last, nc, *p_hist;
  SaCsv *csv;
  SaVtkSeries *series;
} Ft;

static int write_vtk(Ft *t) {
  char name[64], path[SA_STR_MAX];
  snprintf(name, sizeof name, "footing_%04d.vtk", t->step);
  SA_CHECK(sa_run_path(t->run, name, path));
  SA_CHECK(fem_solver_element_stress(t->s, t->sigma, t->vm, NULL));
  fem_fill_history_mean(t->s, 6, t->epsp);
  fem_fill_history_mean(t->s, 7, t->region);
  SaVtk *v;
  SA_CHECK(sa_vtk_grid_open(path, t->run->vtk, "softact footing", t->m->nnodes,
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
  /* time = settlement / B in percent */
  SA_CHECK(sa_vtk_series_add(t->series, name,
                             100 * t->sc->ft.settlement * t->step / t->sc->ft.steps));
  return 0;
}

static int output_step(Ft *t, int last) {
  SA_CHECK(fem_solver_reactions(t->s, t->react));
  double Fz = 0;
  for (int k = 0; k < t->foot->nnodes; k++) Fz += t->react[3 * t->foot->nodes[k] + 2];
  double p = -Fz / t->area, c = t->sc->fill.cohesion;
  double d = t->sc->ft.settlement * t->B * t->step / t->sc->ft.steps;
  FemSolveReport rep;
  fem_solver_report(t->s, &rep);
  t->cuts += rep.cuts;
  t->iters += rep.newton_iters;
  double row[] = {t->step, d, d / t->B, p, p / c, t->nc, rep.newton_iters};
  SA_CHECK(sa_csv_row(t->csv, row));
  t->p_hist[t->step] = p;
  t->p_last = p;
  if (p > t->p_max) t->p_max = p;
  int every = t->sc->ft.vtk_every;
  if ((every > 0 && t->step % every == 0) || last) SA_CHECK(write_vtk(t));
  sa_log(SA_LOG_INFO, "fem", "footing step %3d: settlement %.4g B, p / c = %.5g (Prandtl %.5g), "
         "%d Newton iterations", t->step, d / t->B, p / c, t->nc, rep.newton_iters);
  return 0;
}

/* gnuplot runs in the results folder (sa_plot.c), beside the CSV: named without a folder */
static int make_plot(const SaRun *run, double nc) {
  char png[SA_STR_MAX], body[4 * SA_STR_MAX];
  SA_CHECK(sa_run_path(run, "pressure_settlement.png", png));
  snprintf(body, sizeof body,
           "set datafile separator ','\nset key bottom right\nset grid\n"
           "set title 'Strip footing on a weightless Mohr-Coulomb layer'\n"
           "set xlabel 'settlement / B [-]'\nset ylabel 'p / c [-]'\n"
           "plot '%s' using 3:5 skip 1 with linespoints pt 7 ps 0.6 title 'FEM', "
           "%.9g with lines dt 2 lw 2 title 'Prandtl N_c'\n", "footing.csv", nc);
  if (sa_plot_script(png, body)) sa_error_clear(); /* optional; the data is in the CSV */
  return 0;
}

static int foot_run(void *scene, SaRun *run) {
  FootScene *sc = scene;
  const FootParams *F = &sc->ft;
  double t_start = sa_time_now();
  Ft t = {.sc = sc, .run = run};
  t.B = F->width;
  t.nc = prandtl_nc(sc->fill.friction_angle);
  t.p_max = -INFINITY;
  double dw, dd, nbd, nzd;
  foot_grid(sc, &dw, &dd, &nbd, &nzd);
  int n = F->cells, nb = (int)nbd, nz = (int)nzd;
  double b2 = 0.5 * F->width, W = dw * F->width, D = dd * F->width, g = F->grading;
  /* the smallest cell, at the footing edge (also the slab thickness) */
  double hx = b2 * pow(1.0 / n, g);
  double gb = fmax(1.0, log((W - b2) / hx) / log(nb)), gz = fmax(1.0, log(D / hx) / log(nz));
  FootMap ma = {b2, W, D, hx, g, gb, gz, 0}, mb = ma;
  mb.side = 1;
  FemMeshBlock blk[2] = {
      {{n, 1, nz}, map_foot, &ma, {"sym", NULL, "front", "back", "base", "footing"}},
      {{nb, 1, nz}, map_foot, &mb, {NULL, "far", "front", "back", "base", "free"}}};
  SA_CHECK(fem_mesh_blocks(2, blk, F->order, 1e-9 * F->width, &t.m));
  /* straight-sided tet10: the domain is polygonal, and mid-nodes placed by the graded map would
   * curve the elements (inverted ones for strong grading) and need the 8-point rule */
  if (t.m->nen == 10) {
    static const int ed[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
    for (int e = 0; e < t.m->nelem; e++) {
      const int *c = t.m->conn + (size_t)e * 10;
      for (int q = 0; q < 6; q++)
        for (int i = 0; i < 3; i++)
          t.m->xyz[3 * c[4 + q] + i] =
              0.5 * (t.m->xyz[3 * c[ed[q][0]] + i] + t.m->xyz[3 * c[ed[q][1]] + i]);
    }
  }
  t.area = hx * b2;
  FemMaterial mat;
  int rc = fem_fill_material(&sc->fill, &mat);
  FemSolverParams prm = fem_actuator_solver_params(&sc->act, run->threads);
  /* backtrack as soon as the residual grows: a plastic zone that spreads makes the full Newton
   * step overshoot (measured: without it most first attempts of a substep stall and are cut) */
  prm.ls_growth = 1.0;
  /* a substep converging in up to 8 iterations lets the next one grow (the default 5 keeps the
   * increments of a spreading plastic zone at their first cut for the whole ramp) */
  prm.easy_iter = 8;
  if (!rc) rc = fem_solver_create(t.m, &mat, &prm, &t.s);
  /* plane strain: u_y = 0 at every node (the mid-nodes inside the slab too) */
  for (int a = 0; a < t.m->nnodes && !rc; a++) rc = fem_solver_fix_nodes(t.s, 1, &a, FEM_Y);
  if (!rc) rc = fem_solver_fix_surface(t.s, "sym", FEM_X);
  if (!rc) rc = fem_solver_fix_surface(t.s, "far", FEM_X);
  if (!rc) rc = fem_solver_fix_surface(t.s, "base", FEM_XYZ);
  if (!rc) rc = fem_solver_fix_surface(t.s, "footing", F->rough ? FEM_X | FEM_Z : FEM_Z);
  if (!rc) rc = fem_solver_setup(t.s);
  t.foot = fem_mesh_find_surface(t.m, "footing");
  int ne = t.m->nelem;
  t.react = malloc(sizeof(double) * 3 * t.m->nnodes);
  t.sigma = malloc(sizeof(double) * 9 * ne);
  t.vm = malloc(sizeof(double) * ne);
  t.epsp = malloc(sizeof(double) * ne);
  t.region = malloc(sizeof(double) * ne);
  t.cell_types = malloc(sizeof(int) * ne);
  t.cell_off = malloc(sizeof(int) * (ne + 1));
  t.p_hist = calloc((size_t)F->steps + 1, sizeof(double));
  if (!rc && !(t.react && t.sigma && t.vm && t.epsp && t.region && t.cell_types && t.cell_off &&
               t.p_hist))
    rc = SA_ERROR(SA_ERR_MEMORY, "output buffers");
  if (!rc) {
    for (int e = 0; e < ne; e++) {
      t.cell_types[e] = t.m->nen == 10 ? SA_VTK_QUADRATIC_TETRA : SA_VTK_TETRA;
      t.cell_off[e] = e * t.m->nen;
    }
    t.cell_off[ne] = ne * t.m->nen;
  }
  char path[SA_STR_MAX];
  const char *names[] = {"step", "settlement", "settlement_over_b", "pressure",
                         "pressure_over_c", "prandtl_n_c", "newton_iterations"};
  const char *units[] = {"-", "m", "-", "Pa", "-", "-", "-"};
  if (!rc) rc = sa_run_path(run, "footing.csv", path);
  if (!rc) rc = sa_csv_open(path, 7, names, units, &t.csv);
  if (!rc) rc = sa_run_path(run, "footing.vtk.series", path);
  if (!rc) rc = sa_vtk_series_open(path, &t.series);
  if (!rc) {
    sa_log(SA_LOG_INFO, "fem", "footing: %d x %d + %d x %d cells (x, z), %d %s, %d nodes, "
           "footing edge cell %.3g B", n, nz, nb, nz, ne, t.m->nen == 10 ? "tet10" : "tet4",
           t.m->nnodes, hx / F->width);
    t.step = 0;
    t.p_max = 0;
    for (t.step = 1; t.step <= F->steps && !rc; t.step++) {
      if (sa_interrupted()) {
        rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted at step %d", t.step);
        break;
      }
      double d = F->settlement * F->width * t.step / F->steps;
      rc = fem_solver_set_prescribed(t.s, t.foot->nnodes, t.foot->nodes, 2, -d);
      if (!rc) rc = fem_solver_solve(t.s);
      if (rc) {
        sa_log(rc == SA_ERR_INTERRUPTED ? SA_LOG_WARN : SA_LOG_ERROR, "fem", "settlement ramp "
               "stopped at step %d; results up to step %d are written", t.step, t.step - 1);
        break;
      }
      rc = output_step(&t, t.step == F->steps);
    }
    t.step--;
  }
  int rc_run = rc;
  if (t.csv) {
    int r2 = sa_csv_commit(&t.csv);
    if (!rc) rc = r2;
  }
  sa_vtk_series_close(&t.series);
  if (!rc && run->params.plots) rc = make_plot(run, t.nc);

  if (t.s && t.step > 0) {
    FemSolverStats st;
    fem_solver_stats(t.s, &st);
    double c = sc->fill.cohesion, Nc = t.p_max / c;
    int k90 = (int)floor(0.9 * t.step);
    double rise = t.p_hist[k90] > 0 ? t.p_last / t.p_hist[k90] - 1 : INFINITY;
    /* the plastic branch: least-squares line through the last 20 % of the steps; its slope and
     * its intercept at zero settlement (a diagnostic, docs/mohr_coulomb.md) */
    int k80 = (int)floor(0.8 * t.step);
    if (k80 < 1) k80 = 1;
    double sx = 0, sy = 0, sxx = 0, sxy = 0, nk = 0;
    for (int k = k80; k <= t.step; k++) {
      double x = F->settlement * k / F->steps, y = t.p_hist[k] / c;
      sx += x, sy += y, sxx += x * x, sxy += x * y, nk++;
    }
    double den = nk * sxx - sx * sx, slope = den > 0 ? (nk * sxy - sx * sy) / den : NAN;
    double icpt = (sy - slope * sx) / nk;
    SaFile *f = NULL;
    if (sa_run_path(run, "summary.ini", path) == 0 && sa_file_open(path, &f) == 0) {
      FILE *fp = sa_file_stream(f);
      fprintf(fp, "; softact strip footing on a weightless Mohr-Coulomb layer (plane strain)\n");
      fprintf(fp, "friction_angle = %.9g ; deg\ncohesion = %.9g ; Pa\ndilation_angle = %.9g ; "
              "deg\nrough = %d\n", sc->fill.friction_angle, c, sc->fill.dilation_angle, F->rough);
      fprintf(fp, "limit_pressure = %.9g ; Pa, largest footing pressure of the ramp\n"
              "bearing_capacity_factor = %.9g ; limit_pressure / cohesion\n"
              "prandtl_N_c = %.9g ; (N_q - 1) cot phi, N_q = e^(pi tan phi) tan^2(45 + phi/2)\n"
              "bearing_capacity_rel_error = %.4e\n"
              "last_tenth_rise = %.4e ; p(end) / p(90 %% of the settlement) - 1 (plateau check)\n"
              "plastic_branch_slope = %.6g ; d(p/c) / d(settlement/B) over the last 20 %% of the "
              "steps\nplastic_branch_intercept = %.9g ; that line at zero settlement (diagnostic: "
              "meaningful only when the knee of the curve lies before the last 20 %%)\n",
              t.p_max, Nc, t.nc, Nc / t.nc - 1, rise, slope, icpt);
      fprintf(fp, "domain_width = %.6g ; B\ndomain_depth = %.6g ; B\n", dw, dd);
      fprintf(fp, "cells = %d\ncells_beside = %d\ncells_depth = %d\nedge_cell = %.6g ; B\n"
              "nodes = %d\nelements = %d\nelement = %s\nsteps = %d\nsubsteps_cut = %d\nnewton_iterations = %d\n"
              "factorisations = %d\ncholesky = %d\nlu = %d\nwall_s = %.3f\nstatus = %s\n",
              n, nb, nz, hx / F->width, st.nnodes, st.nelem, t.m->nen == 10 ? "tet10" : "tet4",
              t.step, t.cuts, t.iters, st.n_factor, st.n_chol, st.n_lu, sa_time_now() - t_start,
              rc_run ? "stopped early" : "completed");
      if (sa_file_commit(&f)) sa_error_clear();
    } else {
      sa_error_clear();
    }
    sa_log(SA_LOG_INFO, "fem", "bearing capacity factor %.5g, Prandtl %.5g (%+.2f %%), rise over "
           "the last tenth %.2e", Nc, t.nc, 100 * (Nc / t.nc - 1), rise);
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
  free(t.p_hist);
  fem_mesh_destroy(&t.m);
  return rc ? sa_error_push(rc, __func__, __FILE__, __LINE__) : 0;
}

const SaModule fem_footing_module = {
    .name = "footing",
    .trigger = "footing",
    .help = "rigid strip footing on a weightless Mohr-Coulomb layer (verification)",
    .tables = foot_tables,
    .ntables = 3,
    .check = foot_check,
    .write_resolved = foot_write_resolved,
    .run = foot_run,
    .destroy = foot_destroy,
};
