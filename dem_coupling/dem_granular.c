/* dem_granular.c - the FEM-DEM granular bending run (the plugin's entry point).
 *
 * Phases (docs/dem.md):
 *  1. FEM model of the actuator (fem_actuator.h), clamped, gravity; the cavity wall is a
 *     coupling surface (fem_coupling.h) and also the "pressure" surface at zero pressure, only
 *     so that the solver reports the cavity volume.
 *  2. LIGGGHTS: grains, the cavity wall mesh (held rigid while pouring), the rigid barrel above
 *     the cavity and the piston disc. Grains are poured in rounds, settled, and those above
 *     fill_height removed.
 *  3. The piston is lowered until its force reaches contact_force: displacement zero.
 *  4. Coupling steps: the piston advances by `interval`; during the step the DEM sees the wall
 *     move linearly from its previous to its current FEM position (velocity = change / step
 *     time); the wall forces averaged over the step, under-relaxed with factor `relaxation`,
 *     are the FEM's nodal loads; the FEM solves (reusing factors); the new wall position is
 *     used during the next step. A few steps with the piston at rest first load the wall with
 *     the settled bed.
 * Every step checks lost grains, NaN, the force balance and (every check_every steps) grains
 * outside the bore; the largest overlap and the implied packing are reported and bounded. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem.h"
#include "dem_checks.h"
#include "dem_piston.h"
#include "dem_iqn.h"
#include "dem_parallel.h"
#include "dem_scene.h"
#include "fem_contrib.h"
#include "fem_coupling.h"
#include "fem_material.h"
#include "sa_csv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_plot.h"
#include "sa_vtk.h"

#define R_BORE 6e-3 /* cavity and barrel radius of meshes/actuator.geo */
#define G_ACC 9.81
#define N_PRELOAD 5 /* coupling steps with the piston at rest before the stroke */
#define Z_FLOOR (-80e-3) /* cavity floor of meshes/actuator.geo */
/* insertion packing of the pour column (random sequential insertion saturated there at 0.298
 * for 2 mm and 0.266 for 3 mm beads) */
#define POUR_PACKING 0.25

enum { M_WALL = 0, M_BARREL = 1, M_PISTON = 2, N_MESH = 3 };

typedef struct {
  const DemScene *sc;
  const SaRun *run;
  /* FEM */
  FemMesh *m;
  FemMaterial *mats;
  FemSolver *s;
  FemCouplingSurface *cs;
  int nv, nt;                 /* wall vertices, triangles */
  double *xw_prev, *xw_cur;   /* wall vertex positions: start and end of the motion */
  double *xw, *vw;            /* interpolated positions and velocities handed to LIGGGHTS */
  double *f_tri, *f_sum, *f_node, *f_app; /* wall forces: per triangle, summed, nodal, applied */
  double *k_if, *n_if, *a_if; /* Robin interface: stiffness, normal, anchor per wall vertex */
  double V0;
  /* iterated coupling step ([coupling] iterations > 1): quasi-Newton, the step's start */
  DemIqn *iqn;
  FemSnapshot *snap;
  double *x_start, *x_try, *x_next, *f_app0, *x_hang, *x_prev0;
  double t_rollback, it_res, it_res_max;
  int it_last, it_sum, it_max, it_steps, it_unconverged;
  int it_cuts;                /* coupling steps halved because their iteration did not converge */
  double it_fp_max;           /* largest fixed-point residual |x~ - x| / scale accepted */
  int it_overlap;             /* passes not accepted for their overlap */
  int it_limited;             /* trial walls shortened by [coupling] max_trial_change */
  /* DEM */
  DemBridge *b;
  int mesh_id[N_MESH], mesh_nt[N_MESH], mesh_nv[N_MESH];
  double *mesh_x[N_MESH], *mesh_f[N_MESH]; /* barrel/piston vertices; per-triangle forces */
  double *piston_v;                        /* piston vertex velocities */
  double dt, d, m_grain, z_top, z_piston, piston_r;
  double z_barrel; /* the rigid barrel's bottom: 0, or below it with [dem] rigid_band */
  int n_grains;
  double *px, *pv, *pf, *pr; /* grain read-back */
  DemBore *bore;
  /* coupling step averages */
  double F_mesh[N_MESH][3];
  double angle, piston_force, overlap, balance, phi, phi0, V_bed0, wall_fz, barrel_fz;
  double indent;            /* largest bead indentation into the silicone wall (fraction of d;
                             * [grains] wall_contact = silicone) */
  double E_sil, nu_sil;     /* the silicone's small-strain Young's modulus and Poisson ratio */
  double inertial, inertial_max; /* inertial number of the bed (now, largest in the stroke) */
  double v_piston, T_step;       /* piston speed at the end of the step, step duration */
  double p_start[3];             /* the bed's momentum at the start of the step */
  int newton, dynamic, rigid;
  /* outputs */
  SaCsv *csv;
  SaVtkSeries *vtk_fem, *vtk_grains;
  int *cell_types, *cell_off;
  double *sigma, *vm, *reg;
  int vtk_index;
  double t_dem, t_exchange, t_fem, t_out, t_checks;
  /* the exchange's parts in this process (not checkpointed: since the run or its resume began):
   * the wall placed with the piston at rest (every DEM step) and moving (every wall_every),
   * the piston placed, the wall and piston forces read, and mapped to FEM loads */
  double t_x_wall_rest, t_x_wall_moving, t_x_piston, t_x_forces, t_x_map; /* map: forces to
                                                                           * FEM loads */
  /* the stroke's progress (kept in a checkpoint): next step (preload steps first), time,
   * piston contact height, the CSV rows and VTK times written so far */
  int next_step;
  double time, z_contact;
  double *rows, *vtk_t;
  int nrows, cap_rows, cap_vtk;
} Run;

#define N_COLS 15

/* ------------------------------------------------------------------ FEM side */

/* Robin interface (docs/dem.md): the bed's reaction to wall motion beyond the position the DEM
 * saw, linearised as a normal spring per wall vertex, f = k n n.(x - a); k = 0 where no grain
 * pushes. Stiff beds make the plain staggered exchange unstable (the FEM moves the wall by the
 * force of a bed it does not know is there); the spring lets the FEM know. */
static int interface_eval(void *ctx, FemAsmView *v) {
  Run *g = ctx;
  const double *x = fem_asm_positions(v);
  const int *nd = fem_coupling_surface_nodes(g->cs);
  int tangent = fem_asm_wants_tangent(v);
  double kt_frac = g->sc->coupling.interface_tangential;
  for (int i = 0; i < g->nv; i++) {
    double k = g->k_if[i], kt = kt_frac * k;
    if (k <= 0) continue;
    const double *n = g->n_if + 3 * i, *a = g->a_if + 3 * i, *xi = x + 3 * nd[i];
    /* K = kt I + (k - kt) n n^T: k along the normal, kt across it */
    double d[3] = {xi[0] - a[0], xi[1] - a[1], xi[2] - a[2]};
    double s = (k - kt) * (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
    double f[3] = {kt * d[0] + s * n[0], kt * d[1] + s * n[1], kt * d[2] + s * n[2]};
    fem_asm_add_force(v, nd[i], f);
    if (tangent) {
      double K[9];
      for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) K[3 * r + c] = (k - kt) * n[r] * n[c] + (r == c ? kt : 0);
      fem_asm_add_block(v, nd[i], nd[i], K);
    }
  }
  return 0;
}

/* Interface stiffness from the step's wall forces: a triangle pushed with normal force F has
 * the Hertz contact stiffness dF/ddelta = (6 E*^2 R F)^(1/3) (grain on a flat wall, E* of the
 * pair); each vertex takes a third of its triangles' stiffness along its mean normal, times
 * [coupling] interface_stiffness; anchored at the current wall position. */
static void interface_update(Run *g) {
  const DemGrainCase *gr = &g->sc->grains;
  double E = gr->young / gr->softening, nu = gr->poisson;
  double estar = E / (2 * (1 - nu * nu)), R = 0.5 * g->d;
  double c = 6 * estar * estar * R, fac = g->sc->coupling.interface_stiffness;
  const int *tri = fem_coupling_surface_triangles(g->cs);
  memset(g->k_if, 0, sizeof(double) * (size_t)g->nv);
  memset(g->n_if, 0, sizeof(double) * 3 * (size_t)g->nv);
  for (int t = 0; t < g->nt; t++) {
    double n[3], A = fem_coupling_surface_tri_area(g->cs, g->xw_cur, t, n);
    double fn = fabs(g->f_sum[3 * t] * n[0] + g->f_sum[3 * t + 1] * n[1] + g->f_sum[3 * t + 2] * n[2]);
    double k = fac * cbrt(c * fn) / 3;
    for (int j = 0; j < 3; j++) {
      int vtx = tri[3 * t + j];
      g->k_if[vtx] += k;
      for (int d = 0; d < 3; d++) g->n_if[3 * vtx + d] += A * n[d];
    }
  }
  for (int i = 0; i < g->nv; i++) {
    double *n = g->n_if + 3 * i, l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) n[0] /= l, n[1] /= l, n[2] /= l;
    else g->k_if[i] = 0;
  }
  memcpy(g->a_if, g->xw_cur, sizeof(double) * 3 * (size_t)g->nv);
}

/* [grains] wall_contact = silicone: the silicone's small-strain Young's modulus and Poisson
 * ratio from its law's initial shear modulus mu0 and bulk modulus K (E = 9 K mu0 / (3 K + mu0),
 * nu = (3 K - 2 mu0) / (2 (3 K + mu0)); the reference silicone: 0.66 MPa, 0.499), for the
 * wall's side of a bead's Hertz contact in LIGGGHTS. */
static int silicone_contact_moduli(Run *g) {
  int r = -1;
  for (int k = 0; k < g->m->nregions; k++)
    if (!strcmp(g->m->region_names[k], "silicone")) r = k;
  SA_REQUIRE(r >= 0, SA_ERR_INPUT, "[grains] wall_contact = silicone: the mesh has no region "
             "named 'silicone' to take the wall's modulus from");
  double mu = fem_material_mu0(&g->mats[r]), K = g->mats[r].kappa;
  SA_REQUIRE(mu > 0 && K > 0, SA_ERR_INPUT, "[grains] wall_contact = silicone: the silicone "
             "law has no initial shear and bulk moduli (mu0 = %g, K = %g Pa)", mu, K);
  g->E_sil = 9 * K * mu / (3 * K + mu);
  g->nu_sil = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  sa_log(SA_LOG_INFO, "dem", "bead-silicone contacts: the wall's side is the silicone (E = %.4g "
         "MPa, nu = %.4f)", g->E_sil * 1e-6, g->nu_sil);
  return 0;
}

static int setup_fem(Run *g) {
  const DemScene *sc = g->sc;
  const DemCouplingCase *cc = &sc->coupling;
  SA_CHECK(fem_actuator_mesh(&sc->act, &g->m));
  const char *surfs[] = {cc->wall_surface, cc->fixed_surface, cc->tip_surface};
  SA_CHECK(fem_mesh_require(g->m, 0, NULL, 3, surfs));
  g->mats = calloc((size_t)(g->m->nregions > 0 ? g->m->nregions : 1), sizeof *g->mats);
  SA_REQUIRE(g->mats, SA_ERR_MEMORY, "materials");
  SA_CHECK(fem_actuator_materials(&sc->act, g->m, g->mats));
  if (!strcmp(sc->grains.wall_contact, "silicone")) SA_CHECK(silicone_contact_moduli(g));
  FemSolverParams prm = fem_actuator_solver_params(&sc->act, g->run->threads);
  prm.mass_damping = cc->damping;
  SA_CHECK(fem_solver_create(g->m, g->mats, &prm, &g->s));
  SA_CHECK(fem_solver_fix_surface(g->s, cc->fixed_surface, FEM_XYZ));
  SA_CHECK(fem_solver_add_pressure_surface(g->s, cc->wall_surface)); /* volume only, p = 0 */
  if (cc->gravity) SA_CHECK(fem_solver_set_gravity(g->s, (const double[3]){0, 0, -G_ACC}));
  SA_CHECK(fem_solver_setup(g->s));
  /* the actuator hangs under its own weight before the grains are poured into it */
  if (cc->gravity) {
    double t0 = sa_time_now();
    SA_CHECK(fem_solver_solve(g->s));
    g->t_fem += sa_time_now() - t0;
  }
  const char *wall[] = {cc->wall_surface};
  /* [dem] rigid_band: the wall's faces that reach into the band go to the rigid barrel, which
   * then extends down to their lowest node (the two overlap along the band's zig-zag edge, so
   * the bore has no gap) */
  double band = g->sc->dem.rigid_band;
  g->z_barrel = 0;
  if (band > 0) {
    const FemSurface *S = fem_mesh_find_surface(g->m, cc->wall_surface);
    for (int f = 0; S && f < S->nfaces; f++) {
      const int *fn = S->faces + (size_t)S->nfn * f;
      double zmin = INFINITY, zmax = -INFINITY;
      for (int j = 0; j < S->nfn; j++)
        zmin = fmin(zmin, g->m->xyz[3 * fn[j] + 2]), zmax = fmax(zmax, g->m->xyz[3 * fn[j] + 2]);
      if (zmax >= -band) g->z_barrel = fmin(g->z_barrel, zmin);
    }
  }
  SA_CHECK(fem_coupling_surface_create_below(g->m, 1, wall, band > 0 ? -band : INFINITY, &g->cs));
  if (band > 0)
    sa_log(SA_LOG_INFO, "dem", "rigid_band: the wall above z = %.2f mm is the rigid bore's; the "
           "barrel reaches down to z = %.2f mm", -1e3 * band, 1e3 * g->z_barrel);
  g->nv = fem_coupling_surface_nverts(g->cs);
  g->nt = fem_coupling_surface_ntri(g->cs);
  size_t v3 = 3 * (size_t)g->nv, t3 = 3 * (size_t)g->nt;
  g->xw_prev = malloc(sizeof(double) * v3), g->xw_cur = malloc(sizeof(double) * v3);
  g->xw = malloc(sizeof(double) * v3), g->vw = calloc(v3, sizeof(double));
  g->f_tri = malloc(sizeof(double) * t3), g->f_sum = calloc(t3, sizeof(double));
  g->f_node = calloc(v3, sizeof(double)), g->f_app = calloc(v3, sizeof(double));
  g->k_if = calloc((size_t)g->nv, sizeof(double)), g->n_if = calloc(v3, sizeof(double));
  g->a_if = calloc(v3, sizeof(double));
  SA_REQUIRE(g->xw_prev && g->xw_cur && g->xw && g->vw && g->f_tri && g->f_sum && g->f_node &&
             g->f_app && g->k_if && g->n_if && g->a_if, SA_ERR_MEMORY, "coupling buffers");
  if (g->sc->coupling.iterations > 1) {
    g->x_start = malloc(sizeof(double) * v3), g->x_try = malloc(sizeof(double) * v3);
    g->x_next = malloc(sizeof(double) * v3), g->f_app0 = malloc(sizeof(double) * v3);
    g->x_hang = malloc(sizeof(double) * v3), g->x_prev0 = malloc(sizeof(double) * v3);
    SA_REQUIRE(g->x_start && g->x_try && g->x_next && g->f_app0 && g->x_hang && g->x_prev0,
               SA_ERR_MEMORY, "iteration buffers");
    /* 3 columns per iteration at most matter; 40 hold several steps' worth */
    SA_CHECK(dem_iqn_create(3 * g->nv, 40, g->sc->coupling.qn_reuse, &g->iqn));
    dem_iqn_set_initial_relaxation(g->iqn, g->sc->coupling.initial_relaxation);
  }
  if (g->sc->coupling.interface_stiffness > 0) {
    FemContributor c = {.name = "dem interface", .eval = interface_eval, .ctx = g};
    SA_CHECK(fem_solver_add_contributor(g->s, &c));
  }
  fem_coupling_surface_gather(g->cs, fem_solver_positions(g->s), g->xw_cur);
  /* the hanging wall before any grain: the iterated step's scale (a resumed run computes the
   * same hanging state before it reads its checkpoint) */
  if (g->x_hang) memcpy(g->x_hang, g->xw_cur, sizeof(double) * v3);
  memcpy(g->xw_prev, g->xw_cur, sizeof(double) * v3);
  memcpy(g->xw, g->xw_cur, sizeof(double) * v3);
  g->V0 = fem_solver_cavity_volume(g->s);
  SA_CHECK(dem_bore_create(g->nv, fem_coupling_surface_triangles(g->cs), g->nt, R_BORE, &g->bore));
  sa_log(SA_LOG_INFO, "dem", "FEM: %d nodes, %d elements; wall: %d vertices, %d triangles; "
         "cavity volume %.1f mm^3", g->m->nnodes, g->m->nelem, g->nv, g->nt, g->V0 * 1e9);
  return 0;
}

/* ------------------------------------------------------------------ rigid meshes */

/* Barrel: a tube of radius R_BORE from z_bot (0, or lower with [dem] rigid_band) to z_top;
 * segments about 0.75 d around and 2 d
 * high. The wall contact's cost grows with the triangles near a grain (LIGGGHTS resolves each
 * candidate triangle every step: 55 % of the DEM time in perf with 2 mm rows of 48 segments);
 * the facets' sagitta stays below 2.5 % of d. */
static int make_barrel(double z_bot, double z_top, double d, int *nv, double **xyz, int *nt,
                       int **tri) {
  int nth = (int)ceil(2 * M_PI * R_BORE / (0.75 * d));
  if (nth < 24) nth = 24;
  int nz = (int)ceil((z_top - z_bot) / (2 * d));
  if (nz < 1) nz = 1;
  *nv = nth * (nz + 1), *nt = 2 * nth * nz;
  *xyz = malloc(sizeof(double) * 3 * (size_t)*nv);
  *tri = malloc(sizeof(int) * 3 * (size_t)*nt);
  SA_REQUIRE(*xyz && *tri, SA_ERR_MEMORY, "barrel mesh");
  for (int k = 0; k <= nz; k++)
    for (int j = 0; j < nth; j++) {
      double th = 2 * M_PI * j / nth, *p = *xyz + 3 * (k * nth + j);
      p[0] = R_BORE * cos(th), p[1] = R_BORE * sin(th), p[2] = z_bot + (z_top - z_bot) * k / nz;
    }
  int t = 0;
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < nth; j++) {
      int a = k * nth + j, b = k * nth + (j + 1) % nth, c = a + nth, d = b + nth;
      int *q = *tri + 3 * t;
      q[0] = a, q[1] = c, q[2] = b, q[3] = b, q[4] = c, q[5] = d;
      t += 2;
    }
  return 0;
}

/* Piston: a disc of radius r at height z: centre + nth rim vertices, a fan of triangles. */
static void piston_vertices(int nth, double r, double z, double *xyz) {
  xyz[0] = xyz[1] = 0, xyz[2] = z;
  for (int j = 0; j < nth; j++) {
    double th = 2 * M_PI * j / nth;
    xyz[3 * (j + 1)] = r * cos(th), xyz[3 * (j + 1) + 1] = r * sin(th), xyz[3 * (j + 1) + 2] = z;
  }
}

/* ------------------------------------------------------------------ DEM side */

/* Top of a pour column that holds the whole pour (dem_scene_pour_count: the same on a resume,
 * whose barrel must be the checkpoint's) at POUR_PACKING above the cavity floor. */
static double pour_column_top(const DemGrainCase *gr) {
  double d = gr->diameter, r_in = R_BORE - 0.55 * d, v_grain = M_PI * pow(d, 3) / 6;
  return Z_FLOOR + 0.6 * d + dem_scene_pour_count(gr) * v_grain / (POUR_PACKING * M_PI * r_in * r_in) +
         1.2 * d;
}

/* resume [in]: checkpoint path to continue from (NULL: a new bed is poured); xw_wall,
 * z_piston: the wall nodes and piston height LIGGGHTS held at the checkpoint. */
static int setup_dem(Run *g, const char *resume, const double *xw_wall, double z_piston,
                     int repeat) {
  const DemScene *sc = g->sc;
  const DemGrainCase *gr = &sc->grains;
  g->d = gr->diameter;
  g->m_grain = gr->density * M_PI * pow(g->d, 3) / 6;
  /* pour at the softer of the two stiffnesses (the pour only prepares a random packing; its
   * duration is set by free fall, so a larger step makes it cheaper), press at the working one */
  double E = gr->young / fmax(gr->softening, resume ? 1 : sc->dem.pour_softening);
  double t_r = dem_scene_rayleigh_dt(g->d, gr->density, E, gr->poisson);
  g->dt = sc->dem.dt_fraction * t_r;
  DemParams p = {
      .diameter = g->d, .density = gr->density, .young = E, .poisson = gr->poisson,
      .restitution = gr->restitution, .friction = gr->friction,
      .friction_wall = gr->friction_wall, .friction_piston = gr->friction_piston,
      .rolling_friction = gr->rolling_friction, .wall_young = E, .wall_poisson = gr->poisson,
      .silicone_young = g->E_sil, .silicone_poisson = g->nu_sil,
      .dt = g->dt, .dt_safety = 0.35, .gravity = {0, 0, sc->coupling.gravity ? -G_ACC : 0},
      .skin = (resume ? sc->dem.skin : sc->dem.pour_skin) * g->d, .seed = sc->dem.seed,
      .resume_new_dt = sc->coupling.resume_new_dt};
  /* the pour column: the bed volume at a loose 0.3 packing above the barrel top */
  if (!resume) g->n_grains = (int)dem_scene_pour_count(gr); /* <= DEM_MAX_GRAINS (dem_check) */
  /* the pour column: a grain column of height h takes sqrt(2 h / g) to fall, so one tall round
   * pours faster than several short ones (two rounds of 160 mm: ~0.54 s of fall for the 2 mm
   * bed; one of ~290 mm: ~0.2 s, inserted moving at pour_speed). The column holds the whole
   * bed at POUR_PACKING (random sequential insertion reached 0.298 of the 0.3 asked); at least
   * 160 mm above the barrel top so that the barrel always has room for the piston */
  g->z_top = fmax(sc->piston.barrel_length + 0.16, pour_column_top(gr));
  /* room for the actuator bending toward -x and up (tip ~84 mm from the clamp) */
  double lo[3] = {-0.12, -0.04, -0.14}, hi[3] = {0.04, 0.04, g->z_top + 4 * g->d};
  memcpy(p.box_lo, lo, sizeof lo);
  memcpy(p.box_hi, hi, sizeof hi);
  char log[SA_STR_MAX];
  SA_CHECK(sa_run_path(g->run, "liggghts.log", log));
  /* a repeated coupling step writes on in the run's log (a new log would truncate it) */
  SA_CHECK(dem_bridge_create(repeat ? NULL : log, &g->b));
  /* several MPI ranks: the box cut by the plane y = 0, the plane of the bend, so that both
   * halves of the axisymmetric bore hold as many grains while it pours, settles and bends
   * (LIGGGHTS' own choice would cut the long z side above the bed, leaving one rank idle) */
  if (dem_par_size() > 1) SA_CHECK(dem_bridge_set_processors(g->b, 1, dem_par_size(), 1));
  if (repeat && dem_bridge_log_append(g->b, log)) sa_error_clear();
  if (resume) {
    SA_CHECK(dem_bridge_setup_from_checkpoint(g->b, &p, resume, g->n_grains));
    if (!repeat) sa_log(SA_LOG_INFO, "dem", "resumed %d grains from %s%s", g->n_grains, resume,
                        sc->coupling.resume_new_dt ? " (resume_new_dt: with this case's DEM time "
                                                      "step, a variant of the bed)" : "");
  } else {
    SA_CHECK(dem_bridge_setup(g->b, &p));
    if (sc->dem.pour_friction != 1) SA_CHECK(dem_bridge_scale_friction(g->b, sc->dem.pour_friction));
    sa_log(SA_LOG_INFO, "dem", "pouring %d grains of d = %.3g mm at E = %.3g MPa (physical / %g), "
           "dt = %.3g us (%.2f x Rayleigh %.3g us)", g->n_grains, g->d * 1e3, E / 1e6,
           gr->young / E, g->dt * 1e6, sc->dem.dt_fraction, t_r * 1e6);
  }
  /* wall (the FEM coupling surface at its hanging position, or where the checkpoint had it) */
  SA_CHECK(dem_bridge_add_mesh(g->b, "wall", g->nv, resume ? xw_wall : g->xw_cur, g->nt,
                               fem_coupling_surface_triangles(g->cs), DEM_WALL_SILICONE,
                               &g->mesh_id[M_WALL]));
  g->mesh_nt[M_WALL] = g->nt, g->mesh_nv[M_WALL] = g->nv;
  /* barrel, tall enough for the pour (grains are above barrel_length only while pouring) */
  int bnv, bnt, *btri;
  double *bx;
  SA_CHECK(make_barrel(g->z_barrel, g->z_top, g->d, &bnv, &bx, &bnt, &btri));
  int rc = dem_bridge_add_mesh(g->b, "barrel", bnv, bx, bnt, btri, DEM_WALL_STEEL,
                               &g->mesh_id[M_BARREL]);
  free(btri);
  g->mesh_x[M_BARREL] = bx, g->mesh_nt[M_BARREL] = bnt, g->mesh_nv[M_BARREL] = bnv;
  SA_CHECK(rc);
  /* piston above the pour column */
  int nth = 36;
  g->piston_r = R_BORE - 0.15 * g->d;
  g->z_piston = resume ? z_piston : g->z_top + 2 * g->d;
  g->mesh_nv[M_PISTON] = nth + 1, g->mesh_nt[M_PISTON] = nth;
  g->mesh_x[M_PISTON] = malloc(sizeof(double) * 3 * (nth + 1));
  g->piston_v = malloc(sizeof(double) * 3 * (nth + 1));
  int *ptri = malloc(sizeof(int) * 3 * nth);
  SA_REQUIRE(g->mesh_x[M_PISTON] && g->piston_v && ptri, SA_ERR_MEMORY, "piston mesh");
  piston_vertices(nth, g->piston_r, g->z_piston, g->mesh_x[M_PISTON]);
  for (int j = 0; j < nth; j++) ptri[3 * j] = 0, ptri[3 * j + 1] = 1 + j, ptri[3 * j + 2] = 1 + (j + 1) % nth;
  rc = dem_bridge_add_mesh(g->b, "piston", nth + 1, g->mesh_x[M_PISTON], nth, ptri,
                           DEM_WALL_STEEL, &g->mesh_id[M_PISTON]);
  free(ptri);
  SA_CHECK(rc);
  for (int k = 0; k < N_MESH; k++) {
    g->mesh_f[k] = malloc(sizeof(double) * 3 * (size_t)g->mesh_nt[k]);
    SA_REQUIRE(g->mesh_f[k], SA_ERR_MEMORY, "mesh forces");
  }
  return 0;
}

static int alloc_particles(Run *g, int n) {
  free(g->px), free(g->pv), free(g->pf), free(g->pr);
  g->px = malloc(sizeof(double) * 3 * (size_t)n), g->pv = malloc(sizeof(double) * 3 * (size_t)n);
  g->pf = malloc(sizeof(double) * 3 * (size_t)n), g->pr = malloc(sizeof(double) * (size_t)n);
  SA_REQUIRE(g->px && g->pv && g->pf && g->pr, SA_ERR_MEMORY, "grain buffers");
  return 0;
}

/* Grain statistics: rms speed, highest grain top. */
static int grain_stats(Run *g, double *v_rms, double *z_max) {
  int n = dem_bridge_count(g->b);
  SA_CHECK(alloc_particles(g, n > 0 ? n : 1));
  SA_CHECK(dem_bridge_particles(g->b, g->px, g->pv, NULL, g->pr));
  double s = 0, zm = -INFINITY;
  for (int i = 0; i < n; i++) {
    const double *v = g->pv + 3 * i;
    s += v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    zm = fmax(zm, g->px[3 * i + 2] + g->pr[i]);
    SA_REQUIRE(isfinite(s) && isfinite(zm), SA_ERR_NAN, "grain %d has a non-finite state", i);
  }
  *v_rms = n > 0 ? sqrt(s / n) : 0;
  *z_max = zm;
  return 0;
}

/* Run the DEM for time t [s] with nothing moving (pour and settling), in chunks: a signal stops
 * it after the current chunk with SA_ERR_INTERRUPTED (a settling loop that only saw a short
 * advance would otherwise count time it never simulated and report an unsettled bed). */
static int dem_advance(Run *g, double t) {
  long steps = (long)ceil(t / g->dt);
  double t0 = sa_time_now();
  while (steps > 0) {
    /* 250 steps of ~2 ms (docs/dem.md): a signal is answered within about half a second;
     * after the first run the chunks skip LIGGGHTS' set-up (run N pre no) */
    int n = steps > 250 ? 250 : (int)steps;
    SA_CHECK(dem_bridge_run(g->b, n));
    steps -= n;
    if (sa_interrupted()) break;
  }
  g->t_dem += sa_time_now() - t0;
  SA_REQUIRE(!sa_interrupted(), SA_ERR_INTERRUPTED, "interrupted while pouring and settling the "
             "bed (nothing to resume: a checkpoint is written only once the bed is preloaded)");
  return 0;
}

/* Run the DEM in chunks of `chunk` [s] until the rms grain speed is below settle_speed; *z_max
 * is the top grain's height then. `what` names the stage in the error. */
static int settle(Run *g, double chunk, const char *what, double *z_max) {
  const DemNumericsCase *dm = &g->sc->dem;
  double v_rms;
  for (double t = 0;; t += chunk) {
    SA_CHECK(grain_stats(g, &v_rms, z_max));
    if (v_rms < dm->settle_speed) return 0;
    SA_REQUIRE(t < dm->settle_time_max, SA_ERR_DOMAIN, "the bed did not settle%s in %g s (rms "
               "speed %.3g m/s > settle_speed %.3g m/s): raise settle_time_max or restitution "
               "damping", what, dm->settle_time_max, v_rms, dm->settle_speed);
    SA_CHECK(dem_advance(g, chunk));
  }
}

/* Pour in rounds into the column above the bed, settle, cut the bed at fill_height. */
static int pour(Run *g) {
  const DemScene *sc = g->sc;
  double r_in = R_BORE - 0.55 * g->d, bed_top = Z_FLOOR, v_rms, z_max;
  int left = g->n_grains, rounds = 0;
  while (left > 0) {
    SA_REQUIRE(!sa_interrupted(), SA_ERR_INTERRUPTED, "interrupted while pouring");
    double z_lo = fmax(bed_top + g->d, Z_FLOOR + 0.6 * g->d), z_hi = g->z_top - 0.6 * g->d;
    SA_REQUIRE(z_hi - z_lo > 2 * g->d, SA_ERR_DOMAIN, "the pour column is full after %d rounds "
               "with %d grains left: the bore cannot take %d grains of %g mm (lower "
               "[grains] packing_guess)", rounds, left, g->n_grains, g->d * 1e3);
    /* random sequential insertion saturates near 0.38 in bulk, less in a narrow column */
    double cap = 0.3 * M_PI * r_in * r_in * (z_hi - z_lo) / (M_PI * pow(g->d, 3) / 6);
    int n = left < (int)cap ? left : (int)cap, got = 0;
    SA_CHECK(dem_bridge_insert_cylinder(g->b, 0, 0, r_in, z_lo, z_hi, n, &got));
    SA_REQUIRE(got > 0, SA_ERR_DOMAIN, "no grain could be inserted in round %d", rounds + 1);
    /* the new grains (IDs after the n_grains - left inserted before) start moving down */
    double v0 = sc->dem.pour_speed;
    if (v0 > 0) {
      char cmd[160];
      int id0 = g->n_grains - left;
      snprintf(cmd, sizeof cmd, "group dem_new id <> %d %d", id0 + 1, id0 + got);
      SA_CHECK(dem_bridge_command(g->b, cmd));
      snprintf(cmd, sizeof cmd, "velocity dem_new set 0 0 %.9g units box", -v0);
      SA_CHECK(dem_bridge_command(g->b, cmd));
      SA_CHECK(dem_bridge_command(g->b, "group dem_new delete"));
    }
    left -= got;
    rounds++;
    /* let them fall: the time for the column top to reach the bed (the last round's top lands
     * near fill_height) at g from v0, plus settling; the settling loop below waits for the rest */
    double land = left == 0 ? fmax(bed_top, sc->grains.fill_height - 2 * g->d) : bed_top;
    double fall = (sqrt(v0 * v0 + 2 * G_ACC * (z_hi - land)) - v0) / G_ACC;
    SA_CHECK(dem_advance(g, fall + 0.05));
    SA_CHECK(grain_stats(g, &v_rms, &z_max));
    bed_top = z_max - 2 * g->d; /* grains still bouncing on top: stay conservative */
    sa_log(SA_LOG_INFO, "dem", "pour round %d: %d grains inserted, %d left, bed top %.1f mm",
           rounds, got, left, bed_top * 1e3);
  }
  /* the working friction once the grains have landed: a frictionless bed creeps at a few
   * mm/s for long (the whole pour took 23 min against 19 min with this order, on a loaded
   * machine), and the packing is set by the landing (0.577 against 0.575, docs/dem.md) */
  if (sc->dem.pour_friction != 1) {
    SA_CHECK(dem_bridge_scale_friction(g->b, 1));
    sa_log(SA_LOG_INFO, "dem", "working friction (the grains landed at %g x)",
           sc->dem.pour_friction);
  }
  SA_CHECK(settle(g, 0.02, "", &z_max));
  /* cut the bed at fill_height (grain centres above it are removed) and settle again */
  char cmd[256];
  double zc = sc->grains.fill_height - 0.5 * g->d;
  snprintf(cmd, sizeof cmd, "region dem_above block EDGE EDGE EDGE EDGE %.9g EDGE units box", zc);
  SA_CHECK(dem_bridge_command(g->b, cmd));
  SA_CHECK(dem_bridge_command(g->b, "delete_atoms region dem_above"));
  SA_CHECK(dem_advance(g, 0.05));
  SA_CHECK(settle(g, 0.02, " after the cut at fill_height", &z_max));
  /* the working stiffness, then settle again (the bed expands slightly) */
  const DemGrainCase *gr = &sc->grains;
  double E = gr->young / gr->softening;
  double dt = sc->dem.dt_fraction * dem_scene_rayleigh_dt(g->d, gr->density, E, gr->poisson);
  if (dt != g->dt) {
    SA_CHECK(dem_bridge_set_young(g->b, E, dt));
    g->dt = dt;
    sa_log(SA_LOG_INFO, "dem", "working stiffness: E = %.3g MPa (physical / %g), dt = %.3g us",
           E / 1e6, gr->softening, dt * 1e6);
    SA_CHECK(dem_advance(g, 0.01));
    SA_CHECK(settle(g, 0.01, " at the working stiffness", &z_max));
  }
  /* the stroke's skin (the checkpoints record it, so a resume starts with it) */
  if (sc->dem.pour_skin != sc->dem.skin) SA_CHECK(dem_bridge_set_skin(g->b, sc->dem.skin * g->d));
  g->n_grains = dem_bridge_count(g->b);
  SA_REQUIRE(z_max < sc->grains.fill_height + 0.5 * g->d || z_max > 0, SA_ERR_INTERNAL, "bed");
  SA_REQUIRE(z_max > 0, SA_ERR_DOMAIN, "the settled bed (top %.1f mm) does not reach the top of "
             "the cavity: too few grains (raise packing_guess)", z_max * 1e3);
  /* bed volume: cavity + barrel up to the bed top */
  g->V_bed0 = g->V0 + M_PI * R_BORE * R_BORE * z_max;
  g->phi0 = g->n_grains * M_PI * pow(g->d, 3) / 6 / g->V_bed0;
  sa_log(SA_LOG_INFO, "dem", "settled bed: %d grains, top at %.2f mm, packing fraction %.3f",
         g->n_grains, z_max * 1e3, g->phi0);
  return 0;
}

/* Move the piston to height z with velocity vz and hand it to LIGGGHTS. */
static int set_piston(Run *g, double z, double vz) {
  int nv = g->mesh_nv[M_PISTON];
  piston_vertices(nv - 1, g->piston_r, z, g->mesh_x[M_PISTON]);
  for (int i = 0; i < nv; i++) g->piston_v[3 * i] = g->piston_v[3 * i + 1] = 0, g->piston_v[3 * i + 2] = vz;
  g->z_piston = z;
  /* the piston is a flat disc: moved as one, its normals are not recomputed */
  return dem_bridge_place_flat_mesh(g->b, g->mesh_id[M_PISTON], z, vz);
}

static double sum_z(const double *f, int nt) {
  double s = 0;
  for (int t = 0; t < nt; t++) s += f[3 * t + 2];
  return s;
}

/* Lower the piston until it presses on the bed with contact_force. */
static int lower_piston(Run *g, double *z_contact) {
  const DemPistonCase *pc = &g->sc->piston;
  /* start one diameter above the bed */
  double v_rms, z_max;
  SA_CHECK(grain_stats(g, &v_rms, &z_max));
  double z = z_max + g->d, v = pc->approach_speed;
  int chunk = g->sc->coupling.sample_every;
  SA_CHECK(set_piston(g, z, 0));
  for (long it = 0;; it++) {
    SA_REQUIRE(!sa_interrupted(), SA_ERR_INTERRUPTED, "interrupted while lowering the piston");
    SA_REQUIRE(z > z_max - 3 * g->d, SA_ERR_DOMAIN, "the piston went through the bed top "
               "without reaching contact_force = %g N (lower it)", pc->contact_force);
    z -= v * chunk * g->dt;
    SA_CHECK(set_piston(g, z, -v));
    double t0 = sa_time_now();
    SA_CHECK(dem_bridge_run(g->b, chunk));
    g->t_dem += sa_time_now() - t0;
    SA_CHECK(dem_bridge_mesh_forces(g->b, g->mesh_id[M_PISTON], g->mesh_f[M_PISTON]));
    if (sum_z(g->mesh_f[M_PISTON], g->mesh_nt[M_PISTON]) >= pc->contact_force) break;
  }
  SA_CHECK(set_piston(g, z, 0));
  *z_contact = z;
  sa_log(SA_LOG_INFO, "dem", "piston touches the bed at z = %.2f mm", z * 1e3);
  return 0;
}

/* ------------------------------------------------------------------ one coupling step */

/* DEM over time T with the piston moving down from z0, its speed going uniformly from v0 to
 * v1, and the wall moving from xw_prev to xw_cur; forces averaged over the samples. */
static int dem_step(Run *g, double z0, double v0, double v1, double T) {
  const DemCouplingCase *cc = &g->sc->coupling;
  long nsteps = (long)ceil(T / g->dt);
  /* with the piston at rest the bed carries only its weight: with the near-rigid wall contact
   * its grain-wall overlaps are ~0.2 um, the size of a 10-step jump of the settling wall, so
   * there the wall moves every step (docs/dem.md, "Session 2026-12-06"); the silicone's
   * contact has ~10 um overlaps at that load, so it may use wall_every_rest > 1 (stop 38) */
  int chunk = cc->sample_every, nsamp = 0;
  int wall_every = v0 > 0 || v1 > 0 ? cc->wall_every : cc->wall_every_rest;
  /* several MPI ranks: the forces are summed on each rank over the step and gathered at its
   * end (one reduction instead of one per DEM step); one rank: read every step as before */
  int par = dem_par_size() > 1;
  long next_wall = 0; /* DEM step at which the wall is placed next */
  int piston_placed = 0;
  for (int k = 0; k < N_MESH; k++) g->F_mesh[k][0] = g->F_mesh[k][1] = g->F_mesh[k][2] = 0;
  memset(g->f_sum, 0, sizeof(double) * 3 * (size_t)g->nt);
  for (int k = 0; k < 3 * g->nv; k++) g->vw[k] = (g->xw_cur[k] - g->xw_prev[k]) / T;
  /* the wall's straight path over the step goes to every rank once; each placement below then
   * sends one number */
  if (!g->rigid) {
    double t0 = sa_time_now();
    SA_CHECK(dem_bridge_set_mesh_path(g->b, g->mesh_id[M_WALL], g->xw_prev, g->xw_cur, g->vw));
    *(v0 > 0 || v1 > 0 ? &g->t_x_wall_moving : &g->t_x_wall_rest) += sa_time_now() - t0;
    g->t_exchange += sa_time_now() - t0;
  }
  for (long done = 0; done < nsteps;) {
    /* a coupling step is thousands of DEM steps (~17 s in the default scene) */
    SA_REQUIRE(!sa_interrupted(), SA_ERR_INTERRUPTED, "interrupted inside a coupling step");
    int n = nsteps - done < chunk ? (int)(nsteps - done) : chunk;
    double te = (done + n) * g->dt, a = fmin(te / T, 1.0);
    double t0 = sa_time_now(), t0x = t0;
    /* positions at the end of the chunk (wall_every = 1) or at the middle of the next window
     * of wall_every steps; velocities constant over the step */
    if (done >= next_wall) {
      double aw = wall_every == 1 ? a : fmin((done + 0.5 * (wall_every + 1)) * g->dt / T, 1.0);
      for (int k = 0; k < 3 * g->nv; k++)
        g->xw[k] = g->xw_prev[k] + aw * (g->xw_cur[k] - g->xw_prev[k]);
      if (!g->rigid) /* LIGGGHTS alone: the wall stays where it is */
        SA_CHECK(dem_bridge_place_on_path(g->b, g->mesh_id[M_WALL], aw));
      next_wall = done + wall_every;
      double t1 = sa_time_now();
      *(v0 > 0 || v1 > 0 ? &g->t_x_wall_moving : &g->t_x_wall_rest) += t1 - t0;
      t0 = t1;
    }
    if (sa_log_get_level() >= SA_LOG_DEBUG && done == 0) {
      double *chk = malloc(sizeof(double) * 3 * (size_t)g->nv), e = 0;
      if (chk && !dem_bridge_mesh_nodes(g->b, g->mesh_id[M_WALL], chk))
        for (int k = 0; k < 3 * g->nv; k++) e = fmax(e, fabs(chk[k] - g->xw[k]));
      free(chk);
      sa_log(SA_LOG_DEBUG, "dem", "wall node read-back: largest difference %.3g m", e);
    }
    double ds, vp;
    dem_piston_at(0, v0, v1, T, te, &ds, &vp);
    /* a piston at rest (the preload) is placed once per step, not every DEM step: nothing else
     * moves it within the step, and placing it where it is changes nothing in LIGGGHTS */
    if (!piston_placed || z0 - ds != g->z_piston || -vp != g->piston_v[2])
      SA_CHECK(set_piston(g, z0 - ds, -vp));
    piston_placed = 1;
    double t1 = sa_time_now();
    g->t_x_piston += t1 - t0;
    g->t_exchange += t1 - t0x;
    t0 = sa_time_now();
    SA_CHECK(dem_bridge_run(g->b, n));
    g->t_dem += sa_time_now() - t0;
    t0 = sa_time_now();
    if (par) /* each rank adds up its own triangles; summed over the ranks once, below */
      SA_CHECK(dem_bridge_mesh_forces_add(g->b));
    else {
      SA_CHECK(dem_bridge_mesh_forces(g->b, g->mesh_id[M_WALL], g->f_tri));
      for (int k = 0; k < 3 * g->nt; k++) g->f_sum[k] += g->f_tri[k];
      for (int m = 0; m < N_MESH; m++) {
        if (m != M_WALL)
          SA_CHECK(dem_bridge_mesh_forces(g->b, g->mesh_id[m], g->mesh_f[m]));
        const double *f = m == M_WALL ? g->f_tri : g->mesh_f[m];
        for (int q = 0; q < g->mesh_nt[m]; q++)
          for (int d = 0; d < 3; d++) g->F_mesh[m][d] += f[3 * q + d];
      }
    }
    nsamp++;
    double t2 = sa_time_now();
    g->t_x_forces += t2 - t0;
    g->t_exchange += t2 - t0;
    done += n;
  }
  if (par) { /* the sums over the step, from every rank */
    double t0 = sa_time_now();
    for (int m = 0; m < N_MESH; m++) {
      double *f = m == M_WALL ? g->f_sum : g->mesh_f[m];
      SA_CHECK(dem_bridge_mesh_forces_take(g->b, g->mesh_id[m], f));
      for (int q = 0; q < g->mesh_nt[m]; q++)
        for (int d = 0; d < 3; d++) g->F_mesh[m][d] += f[3 * q + d];
    }
    g->t_x_forces += sa_time_now() - t0;
    g->t_exchange += sa_time_now() - t0;
  }
  if (wall_every > 1 && !g->rigid) { /* the step ends with the wall where the FEM put it */
    double t0 = sa_time_now();
    memcpy(g->xw, g->xw_cur, sizeof(double) * 3 * (size_t)g->nv);
    SA_CHECK(dem_bridge_set_mesh_nodes(g->b, g->mesh_id[M_WALL], g->xw, g->vw));
    g->t_x_wall_moving += sa_time_now() - t0;
    g->t_exchange += sa_time_now() - t0;
  }
  for (int k = 0; k < 3 * g->nt; k++) {
    g->f_sum[k] /= nsamp;
    SA_REQUIRE(isfinite(g->f_sum[k]), SA_ERR_NAN, "non-finite wall force from the DEM");
  }
  for (int m = 0; m < N_MESH; m++)
    for (int d = 0; d < 3; d++) g->F_mesh[m][d] /= nsamp;
  double fabs_sum = 0, pull = 0, push = 0;
  for (int k = 0; k < 3 * g->nt; k++) fabs_sum += fabs(g->f_sum[k]);
  for (int t = 0; t < g->nt; t++) {
    double n[3];
    fem_coupling_surface_tri_area(g->cs, g->xw, t, n);
    double fn = g->f_sum[3 * t] * n[0] + g->f_sum[3 * t + 1] * n[1] + g->f_sum[3 * t + 2] * n[2];
    if (fn > 0) pull += fn; else push -= fn;
  }
  sa_log(SA_LOG_DEBUG, "dem", "wall normal forces: pushing %.4g N, pulling %.4g N", push, pull);
  if (sa_log_get_level() >= SA_LOG_DEBUG) {
    double fx[9] = {0}, ux[9] = {0};
    int cnt[9] = {0};
    const int *tri = fem_coupling_surface_triangles(g->cs);
    for (int t = 0; t < g->nt; t++) {
      double zc = 0, dx = 0;
      for (int j = 0; j < 3; j++) {
        int v = tri[3 * t + j];
        zc += g->xw[3 * v + 2] / 3;
        dx += (g->xw_cur[3 * v] - g->m->xyz[3 * fem_coupling_surface_nodes(g->cs)[v]]) / 3;
      }
      int b = (int)floor(-zc / 10e-3);
      b = b < 0 ? 0 : b > 8 ? 8 : b;
      fx[b] += g->f_sum[3 * t], ux[b] += dx, cnt[b]++;
    }
    char line[512];
    int k = 0;
    for (int b = 0; b < 9; b++)
      k += snprintf(line + k, sizeof line - k, " [%d] %.3f/%.3f", b, fx[b],
                    cnt[b] ? 1e3 * ux[b] / cnt[b] : 0.0);
    sa_log(SA_LOG_DEBUG, "dem", "x-force [N] / mean x-displacement [mm] per 10 mm slab:%s", line);
  }
  sa_log(SA_LOG_DEBUG, "dem", "step forces: wall (%.4g, %.4g, %.4g) N, sum|f| %.4g N; barrel "
         "(%.4g, %.4g, %.4g) N; piston (%.4g, %.4g, %.4g) N", g->F_mesh[0][0], g->F_mesh[0][1],
         g->F_mesh[0][2], fabs_sum, g->F_mesh[1][0], g->F_mesh[1][1], g->F_mesh[1][2],
         g->F_mesh[2][0], g->F_mesh[2][1], g->F_mesh[2][2]);
  return 0;
}

/* Averaged wall forces -> relaxed FEM loads -> FEM step of length T (implicit dynamic or static
 * equilibrium) -> new wall position. */
static int fem_step(Run *g, double T) {
  double t0 = sa_time_now();
  fem_coupling_surface_scatter(g->cs, g->f_sum, g->f_node);
  double w = g->sc->coupling.relaxation;
  for (int k = 0; k < 3 * g->nv; k++) g->f_app[k] += w * (g->f_node[k] - g->f_app[k]);
  SA_CHECK(fem_solver_set_nodal_forces(g->s, g->nv, fem_coupling_surface_nodes(g->cs), g->f_app));
  if (g->sc->coupling.interface_stiffness > 0) interface_update(g);
  memcpy(g->xw_prev, g->xw_cur, sizeof(double) * 3 * (size_t)g->nv);
  g->t_x_map += sa_time_now() - t0;
  g->t_exchange += sa_time_now() - t0;
  if (g->rigid) { /* LIGGGHTS alone: the wall keeps its shape, nothing is solved */
    g->newton = 0;
    return 0;
  }
  t0 = sa_time_now();
  int rc = g->dynamic ? fem_solver_step_dynamic(g->s, T) : fem_solver_solve(g->s);
  g->t_fem += sa_time_now() - t0;
  FemSolveReport rep;
  fem_solver_report(g->s, &rep);
  g->newton = rep.newton_iters;
  if (rc) {
    /* an interrupted solve is no failure: the run keeps its last step (exit 3) */
    if (rc != SA_ERR_INTERRUPTED)
      sa_log(SA_LOG_ERROR, "dem", "FEM solve failed: %s",
             rep.reason[0] ? rep.reason : sa_error_message());
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  fem_coupling_surface_gather(g->cs, fem_solver_positions(g->s), g->xw_cur);
  if (sa_log_get_level() >= SA_LOG_DEBUG) {
    int kf = 0, ku = 0;
    double fm = 0, um = 0;
    for (int i = 0; i < g->nv; i++) {
      double f = hypot(hypot(g->f_app[3 * i], g->f_app[3 * i + 1]), g->f_app[3 * i + 2]);
      double u = 0;
      for (int d = 0; d < 3; d++)
        u += pow(g->xw_cur[3 * i + d] - g->m->xyz[3 * fem_coupling_surface_nodes(g->cs)[i] + d], 2);
      u = sqrt(u);
      if (f > fm) fm = f, kf = i;
      if (u > um) um = u, ku = i;
    }
    const double *X = g->m->xyz;
    const int *nd = fem_coupling_surface_nodes(g->cs);
    double mu[3] = {0, 0, 0}, mv[3] = {0, 0, 0};
    for (int i = 0; i < g->nv; i++)
      for (int d = 0; d < 3; d++) {
        mu[d] += (g->xw_cur[3 * i + d] - X[3 * nd[i] + d]) / g->nv;
        mv[d] += (g->xw_cur[3 * i + d] - g->xw_prev[3 * i + d]) / g->nv;
      }
    sa_log(SA_LOG_DEBUG, "dem", "mean wall displacement (%.4g, %.4g, %.4g) mm, change over the step "
           "(%.4g, %.4g, %.4g) mm", mu[0] * 1e3, mu[1] * 1e3, mu[2] * 1e3, mv[0] * 1e3, mv[1] * 1e3,
           mv[2] * 1e3);
    sa_log(SA_LOG_DEBUG, "dem", "largest nodal load %.4g N at (%.2f, %.2f, %.2f) mm; largest wall "
           "displacement %.4g mm at (%.2f, %.2f, %.2f) mm", fm, X[3 * nd[kf]] * 1e3,
           X[3 * nd[kf] + 1] * 1e3, X[3 * nd[kf] + 2] * 1e3, um * 1e3, X[3 * nd[ku]] * 1e3,
           X[3 * nd[ku] + 1] * 1e3, X[3 * nd[ku] + 2] * 1e3);
  }
  return 0;
}

/* ------------------------------------------------------------------ iterated coupling step */

/* The DEM as it was at a checkpoint: a new bridge from it, the wall at xw_wall and the piston at
 * z_start, where the checkpoint has them (docs/dem.md "Iterated coupling": about a second). */
static int dem_reload_at(Run *g, const char *path, const double *xw_wall, double z_start) {
  double t0 = sa_time_now();
  dem_bridge_destroy(&g->b);
  for (int k = 0; k < N_MESH; k++) {
    free(g->mesh_x[k]), free(g->mesh_f[k]);
    g->mesh_x[k] = g->mesh_f[k] = NULL;
  }
  free(g->piston_v);
  g->piston_v = NULL;
  int rc = setup_dem(g, path, xw_wall, z_start, 1);
  g->t_rollback += sa_time_now() - t0;
  return rc;
}

/* The DEM as it was at the step's start, from the step's checkpoint. */
static int dem_reload(Run *g, const char *path, double z_start) {
  return dem_reload_at(g, path, g->x_start, z_start);
}

/* |a - b|_2 */
static double dist2(const double *a, const double *b, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += (a[i] - b[i]) * (a[i] - b[i]);
  return sqrt(s);
}

/* An iterated step is accepted only when, besides the quasi-Newton update, the fixed-point
 * residual |x~ - x| is below RESIDUAL_GUARD x iteration_tol of the grains' wall displacement
 * (measured with the scene's softening 100, 3 mm beads: accepted steps had residuals up to
 * 0.23 in the preload, where the wall first takes the bed's weight, and 0.06 in the stroke;
 * with softening 10 steps were accepted at 0.5-1 and the wall ran away). */
#define RESIDUAL_GUARD 10.0

/* One coupling step iterated to the interface equilibrium: the DEM moves the wall from where
 * it is (x_start) to a trial end position x, the FEM answers with x~ = H(x) under the step's
 * wall forces, and IQN-ILS (dem_iqn.h) proposes the next x, until its update |x_next - x| <=
 * iteration_tol |x~ - x_hang| (x_hang: the wall hanging before the grains came). Each repeat starts again from the step's start: the FEM from a snapshot, the
 * DEM from a checkpoint written at the start. The first trial extrapolates the last step's
 * wall motion. With the Robin springs the FEM knows the bed's local stiffness (a
 * preconditioner); at the converged x their force vanishes (anchor = x), so the answer does
 * not depend on interface_stiffness. */
static int coupling_step_iterated(Run *g, double z0, double v0, double v1, double T,
                                  double T_last, int can_cut, int *cut) {
  const DemCouplingCase *cc = &g->sc->coupling;
  int n3 = 3 * g->nv;
  size_t bytes = sizeof(double) * (size_t)n3;
  char dir[SA_STR_MAX], ck[SA_STR_MAX];
  SA_CHECK(sa_run_path(g->run, "checkpoint", dir));
  SA_CHECK(sa_mkdir_p(dir));
  SA_CHECK(sa_path_join(dir, "step.ckpt", ck));
  double t0 = sa_time_now(), z_start = g->z_piston;
  SA_CHECK(dem_bridge_write_checkpoint(g->b, ck));
  SA_CHECK(fem_solver_snapshot(g->s, &g->snap));
  g->t_rollback += sa_time_now() - t0;
  memcpy(g->x_start, g->xw, bytes);
  memcpy(g->x_prev0, g->xw_prev, bytes);
  memcpy(g->f_app0, g->f_app, bytes);
  *cut = 0;
  /* first trial: the last step's wall motion, scaled to this step's length and by
   * [coupling] extrapolation (0: the wall where it is) */
  double a = T_last > 0 ? cc->extrapolation * T / T_last : 0;
  for (int k = 0; k < n3; k++) g->x_try[k] = g->xw_cur[k] + a * (g->xw_cur[k] - g->xw_prev[k]);
  double L = cc->max_trial_change * g->d; /* the trust region of every trial wall (0: none) */
  if (dem_iqn_limit_step(g->xw_cur, g->x_try, n3, L) < 1) g->it_limited++;
  dem_iqn_new_step(g->iqn);
  int it = 0;
  double res = INFINITY, r_last = INFINITY;
  int refused_last = 0; /* the last pass had an overlap or indentation above its limit */
  for (;; it++) {
    if (it > 0) {
      SA_CHECK(dem_reload(g, ck, z_start));
      SA_CHECK(fem_solver_rollback(g->s, g->snap));
      memcpy(g->f_app, g->f_app0, bytes);
    }
    memcpy(g->xw_prev, g->x_start, bytes);
    memcpy(g->xw_cur, g->x_try, bytes);
    SA_CHECK(dem_step(g, z0, v0, v1, T));
    SA_CHECK(fem_step(g, T)); /* xw_cur <- x~ */
    /* Stop on the size of the quasi-Newton update, not of the residual: with the Robin
     * springs the residual of a soft mode (the actuator bending with its bed) is the error
     * times K_wall / (K_wall + K_if), tiny while the error is not (docs/dem.md: stopping on
     * it left the angle depending on interface_stiffness); the secant model scales it back.
     * The scale is what the grains have done to the wall so far, |x~ - x_hang| (the step's
     * own motion vanishes with the piston at rest, where grain noise then sets the floor). */
    double scale = fmax(dist2(g->xw_cur, g->x_hang, n3), 1e-9 * sqrt((double)g->nv));
    double step_motion = dist2(g->xw_cur, g->x_start, n3);
    double r_rel = dist2(g->xw_cur, g->x_try, n3) / scale;
    /* the largest nodal mismatch between the wall the DEM saw and the FEM's answer */
    double m_max = 0;
    for (int v = 0; v < g->nv; v++) {
      double e2 = 0;
      for (int d = 0; d < 3; d++) e2 += pow(g->xw_cur[3 * v + d] - g->x_try[3 * v + d], 2);
      m_max = fmax(m_max, sqrt(e2));
    }
    SA_CHECK(dem_iqn_update(g->iqn, g->x_try, g->xw_cur, g->x_next));
    /* the update of a pass without a model is the residual, relaxed by initial_relaxation w:
     * test the residual itself, else w < 1 would loosen the test by 1/w */
    res = dem_iqn_columns(g->iqn) ? dist2(g->x_next, g->x_try, n3) / scale : r_rel;
    double ang = NAN; /* cheap (a sum over the tip face), so always: the log file is DEBUG */
    if (fem_bending_angle(g->m, g->sc->coupling.tip_surface, fem_solver_positions(g->s), &ang))
      sa_error_clear();
    sa_log(SA_LOG_DEBUG, "dem", "coupling iteration %d: update %.3g, residual %.3g of the "
           "grains' wall displacement (%.3g nm rms; this step %.3g nm rms; largest %.3g um), %d "
           "quasi-Newton columns, %d Newton, angle %.4f deg", it + 1, res, r_rel,
           1e9 * scale / sqrt((double)g->nv), 1e9 * step_motion / sqrt((double)g->nv),
           1e6 * m_max, dem_iqn_columns(g->iqn), g->newton, ang);
    r_last = r_rel;
    int last = it + 1 >= cc->iterations;
    /* A pass whose grains overlap the wall (or each other) beyond the run check's limit is
     * never the accepted one: the trial wall was pushed into the bed (on one bed the
     * quasi-Newton trial put a floor node ~100 um inside a grain at an rms residual of 0.23,
     * docs/dem.md "stop 30"). The FEM's answer x~ has felt that push: substitute it. The last
     * pass is checked too: a step that ends on a refused pass is a failed step (halved while
     * cut_max allows; then the run check stops the run), never accepted (stop 42: a stiff bed's
     * step ended on its 15th refused pass and was taken). */
    double t_ov = sa_time_now(), ov = dem_bridge_max_overlap(g->b);
    double ind = dem_bridge_max_indentation(g->b); /* the same rule for the silicone's */
    g->t_checks += sa_time_now() - t_ov;
    int deep = !(ind <= g->sc->dem.max_indentation);
    if (deep || !(ov <= g->sc->dem.max_overlap)) {
      const char *next = last ? "and the step's last pass" : "the FEM's wall is tried next";
      double at[3];
      const char *with = dem_bridge_overlap_site(g->b, at);
      /* two grains two diameters above the silicone's top (z = 0) touch only grains and the
       * rigid barrel: no wall position cures their overlap, so passes and halvings would only
       * repeat it (a softening-100 bed at 5 mm spent 15 passes on one barrel contact) */
      SA_REQUIRE(deep || !(at[2] > 2 * g->d) || strcmp(with, "two grains") != 0, SA_ERR_DOMAIN,
                 "largest contact overlap %.3g of the diameter exceeds [dem] max_overlap = %g "
                 "(%s, grain at (%.2f, %.2f, %.2f) mm, in the rigid barrel, where no position of "
                 "the silicone wall changes it): the grains are too soft for this load (lower "
                 "[grains] softening) or the piston too fast", ov, g->sc->dem.max_overlap, with,
                 at[0] * 1e3, at[1] * 1e3, at[2] * 1e3);
      if (deep) {
        double ip[3];
        dem_bridge_indentation_site(g->b, ip);
        sa_log(SA_LOG_INFO, "dem", "coupling iteration %d: a bead indents the silicone wall by "
               "%.3g of its diameter, above [dem] max_indentation = %g (bead at r %.2f mm, "
               "theta %.0f deg, z %.2f mm): not accepted, %s", it + 1,
               ind, g->sc->dem.max_indentation, 1e3 * hypot(ip[0], ip[1]),
               atan2(ip[1], ip[0]) * 180 / M_PI, 1e3 * ip[2], next);
      }
      else
        sa_log(SA_LOG_INFO, "dem", "coupling iteration %d: overlap %.3g of the diameter (%s, "
               "grain at (%.2f, %.2f, %.2f) mm) above [dem] max_overlap = %g: not accepted, %s",
               it + 1, ov, with, at[0] * 1e3, at[1] * 1e3, at[2] * 1e3, g->sc->dem.max_overlap,
               next);
      g->it_overlap++;
      if (last) {
        refused_last = 1;
        break;
      }
      dem_iqn_clear(g->iqn);
      memcpy(g->x_next, g->xw_cur, bytes);
      if (dem_iqn_limit_step(g->x_try, g->x_next, n3, L) < 1) g->it_limited++;
      memcpy(g->x_try, g->x_next, bytes);
      continue;
    }
    if (last) break;
    if (res <= cc->iteration_tol) {
      if (r_rel <= RESIDUAL_GUARD * cc->iteration_tol) break;
      /* a small update with a large residual: the secant model (with columns of earlier
       * steps) predicts a fixed point the map does not have. Forget it and substitute (x~),
       * relaxed by initial_relaxation as every update without a model (on a stiff bed the
       * unrelaxed x~ threw the wall into the bed: docs/dem.md, stop 36) */
      sa_log(SA_LOG_DEBUG, "dem", "coupling iteration %d: update %.3g below the tolerance but "
             "residual %.3g: quasi-Newton model dropped", it + 1, res, r_rel);
      dem_iqn_clear(g->iqn);
      double w = cc->initial_relaxation;
      if (w == 1) /* exactly x~ (x + 1 (x~ - x) differs in the last bits) */
        memcpy(g->x_next, g->xw_cur, bytes);
      else
        for (int k = 0; k < n3; k++) g->x_next[k] = g->x_try[k] + w * (g->xw_cur[k] - g->x_try[k]);
      res = INFINITY;
    }
    /* shortened after the convergence test, which judges the full update */
    double f = dem_iqn_limit_step(g->x_try, g->x_next, n3, L);
    if (f < 1) {
      g->it_limited++;
      sa_log(SA_LOG_DEBUG, "dem", "coupling iteration %d: next wall shortened to %.3g of the "
             "update ([coupling] max_trial_change = %g of d)", it + 1, f, cc->max_trial_change);
    }
    memcpy(g->x_try, g->x_next, bytes);
  }
  /* Not converged and the step may still be halved: back to the step's start (DEM, FEM, the
   * wall's last motion for the extrapolation) and let the caller do it as two half steps */
  if (can_cut &&
      (refused_last || r_last > RESIDUAL_GUARD * cc->iteration_tol || res > cc->iteration_tol)) {
    double t_cut = sa_time_now();
    SA_CHECK(dem_reload(g, ck, z_start));
    SA_CHECK(fem_solver_rollback(g->s, g->snap));
    g->t_rollback += sa_time_now() - t_cut;
    memcpy(g->f_app, g->f_app0, bytes);
    memcpy(g->xw, g->x_start, bytes);
    memcpy(g->xw_cur, g->x_start, bytes);
    memcpy(g->xw_prev, g->x_prev0, bytes);
    dem_iqn_clear(g->iqn); /* a model of the step that failed */
    sa_log(SA_LOG_INFO, "dem", "coupling step from piston displacement %.4f mm (%.4g ms) not "
           "converged in %d passes (quasi-Newton update %.3g, residual %.3g of the grains' wall "
           "displacement%s): halved", (g->z_contact - z0) * 1e3, T * 1e3, it + 1, res, r_last,
           refused_last ? "; its last pass refused" : "");
    g->it_cuts++;
    *cut = 1;
    return 0;
  }
  /* accepted: LIGGGHTS holds the wall at x (the trial), the FEM its answer x~ within the
   * tolerance; the next step moves the wall on from x */
  memcpy(g->xw_prev, g->x_start, bytes);
  memcpy(g->xw_cur, g->x_try, bytes);
  g->it_last = it + 1, g->it_sum += it + 1, g->it_steps++;
  if (it + 1 > g->it_max) g->it_max = it + 1;
  g->it_res = res;
  if (res > g->it_res_max) g->it_res_max = res;
  if (r_last > g->it_fp_max) g->it_fp_max = r_last;
  /* A residual above the guard after the last pass: the FEM's wall answers one pass's forces,
   * not the bed (measured with softening 30 on two 3 mm beds: steps accepted at 0.31-2.14
   * made the angle jump and the force collapse; docs/dem.md "The full stroke with stiffer
   * grains"). Such a step is a failed step: halved above while cut_max allows, then stop with
   * a diagnosis, the rows up to the last accepted step kept. A large update at a small
   * residual is only slow. (The guard's scale, the whole displacement of the wall, still let a
   * 2 mm bed's step pass at 0.21 that jumped the angle from 3.0 to 6.0 deg.) */
  if (r_last > RESIDUAL_GUARD * cc->iteration_tol) {
    g->it_unconverged++;
    return SA_ERROR(SA_ERR_NOT_CONVERGED, "coupling step from piston displacement %.3f mm did "
                    "not converge in %d passes: the wall the FEM returns differs from the wall "
                    "the grains saw by %.3g of the grains' wall displacement (at most %g): the "
                    "bed is too stiff for the iterated coupling (raise [grains] softening), or "
                    "shorten [coupling] interval or raise [coupling] iterations or cut_max",
                    (g->z_contact - z0) * 1e3, it + 1, r_last, RESIDUAL_GUARD * cc->iteration_tol);
  }
  if (res > cc->iteration_tol) {
    g->it_unconverged++;
    sa_log(SA_LOG_WARN, "dem", "coupling step not converged in %d iterations: quasi-Newton "
           "update %.3g (iteration_tol %g) at a residual of %.3g (at most %g) of the grains' "
           "wall displacement (accepted; raise [coupling] iterations)", it + 1, res,
           cc->iteration_tol, r_last, RESIDUAL_GUARD * cc->iteration_tol);
  }
  return 0;
}

/* Total momentum of the grains [kg m/s] (equal masses). */
static int bed_momentum(Run *g, double p[3]) {
  int n = dem_bridge_count(g->b);
  SA_CHECK(dem_bridge_particles(g->b, NULL, g->pv, NULL, NULL));
  p[0] = p[1] = p[2] = 0;
  for (int i = 0; i < n; i++)
    for (int d = 0; d < 3; d++) p[d] += g->m_grain * g->pv[3 * i + d];
  return 0;
}

/* A coupling step (or part of one, depth halvings deep): staggered or iterated; an iterated
 * step that does not converge is redone as two half steps while depth < cut_max. */
static int coupling_step_cut(Run *g, double z0, double v0, double v1, double T, double T_last,
                             int depth) {
  g->v_piston = v1, g->T_step = T;
  SA_CHECK(bed_momentum(g, g->p_start));
  if (g->sc->coupling.iterations <= 1 || g->rigid) {
    SA_CHECK(dem_step(g, z0, v0, v1, T));
    return fem_step(g, T);
  }
  int cut;
  SA_CHECK(coupling_step_iterated(g, z0, v0, v1, T, T_last, depth < g->sc->coupling.cut_max,
                                  &cut));
  if (!cut) return 0;
  /* two halves of the step, the piston's speed still uniform in time: the first from z0 at v0
   * to the middle speed, the second on to v1 */
  double h = 0.5 * T, ds, vm;
  dem_piston_at(0, v0, v1, T, h, &ds, &vm);
  SA_CHECK(coupling_step_cut(g, z0, v0, vm, h, T_last, depth + 1));
  SA_CHECK(coupling_step_cut(g, z0 - ds, vm, v1, h, h, depth + 1));
  /* the next step extrapolates the wall's last motion as if made over this whole step (the
   * schedule's step length), from the last half's */
  for (int k = 0; k < 3 * g->nv; k++)
    g->xw_prev[k] = g->xw_cur[k] - (T / h) * (g->xw_cur[k] - g->xw_prev[k]);
  /* the step's row then holds the last half's averaged forces (and its force balance) */
  return 0;
}

/* One coupling step, the piston's speed going from v0 to v1 over T: staggered (one DEM pass,
 * one FEM solve; the wall the FEM returns is used in the next step) or iterated, halved (at
 * most [coupling] cut_max times) while its iteration does not converge. */
static int coupling_step(Run *g, double z0, double v0, double v1, double T, double T_last) {
  return coupling_step_cut(g, z0, v0, v1, T, T_last, 0);
}

/* Checks after a coupling step; fills the report fields. */
static int step_checks(Run *g, int step, double s_disp, int full) {
  const DemScene *sc = g->sc;
  double t0 = sa_time_now();
  int n = dem_bridge_count(g->b);
  /* with the silicone's contact a bead pressed hard into the compliant wall can pass through
   * it within one step (Hertz's law lets its centre reach the wall at half a diameter): say so,
   * with the deepest indentation of the last accepted step, rather than blame the time step */
  SA_REQUIRE(n == g->n_grains || !(g->E_sil > 0), SA_ERR_DOMAIN,
             "%d of %d grains left the simulation box at piston displacement %.3f mm; the "
             "deepest bead in the silicone wall was at %.3g of its diameter the step before "
             "([dem] max_indentation = %g): a bead pushed through the compliant wall (where "
             "the wall is clamped, near the cavity's top, the FEM cannot give way and the "
             "contact alone holds the bead). Lower [dem] max_indentation to stop before it, "
             "or shorten [piston] stroke; [grains] wall_contact = grain holds beads on a "
             "near-rigid wall",
             g->n_grains - n, g->n_grains, s_disp * 1e3, g->indent,
             g->sc->dem.max_indentation);
  SA_REQUIRE(n == g->n_grains, SA_ERR_DOMAIN, "%d of %d grains left the simulation box at "
             "piston displacement %.3f mm: they escaped through a gap (check the wall mesh and "
             "the piston clearance) or were ejected (soften less / slow the piston)",
             g->n_grains - n, g->n_grains, s_disp * 1e3);
  g->overlap = dem_bridge_max_overlap(g->b);
  double ov_at[3];
  const char *ov_with = dem_bridge_overlap_site(g->b, ov_at);
  sa_log(SA_LOG_DEBUG, "dem", "largest overlap %.4g of the diameter (%s, grain at (%.2f, %.2f, "
         "%.2f) mm)", g->overlap, ov_with, ov_at[0] * 1e3, ov_at[1] * 1e3, ov_at[2] * 1e3);
  g->indent = dem_bridge_max_indentation(g->b);
  double ip[3]; /* the deepest bead's centre: r, theta (0 = +x, the side away from the band), z */
  dem_bridge_indentation_site(g->b, ip);
  double ip_r = 1e3 * hypot(ip[0], ip[1]), ip_th = atan2(ip[1], ip[0]) * 180 / M_PI;
  if (g->E_sil > 0)
    sa_log(SA_LOG_DEBUG, "dem", "largest indentation of the silicone wall %.4g of the diameter "
           "(bead at r %.2f mm, theta %.0f deg, z %.2f mm)", g->indent, ip_r, ip_th, 1e3 * ip[2]);
  SA_REQUIRE(isfinite(g->indent) && g->indent <= sc->dem.max_indentation, SA_ERR_DOMAIN,
             "a bead indents the silicone wall by %.3g of its diameter, above [dem] "
             "max_indentation = %g, at piston displacement %.3f mm (bead at r %.2f mm, theta "
             "%.0f deg, z %.2f mm): Hertz's law is out of its range and the bead near "
             "tunnelling through the wall (a shorter stroke; a dent in the clamped top: [dem] "
             "rigid_band; docs/dem.md)", g->indent,
             sc->dem.max_indentation, s_disp * 1e3, ip_r, ip_th, 1e3 * ip[2]);
  SA_REQUIRE(isfinite(g->overlap) && g->overlap <= sc->dem.max_overlap, SA_ERR_DOMAIN,
             "largest contact overlap %.3g of the diameter exceeds [dem] max_overlap = %g at "
             "piston displacement %.3f mm (%s, grain at (%.2f, %.2f, %.2f) mm): the grains are "
             "too soft for this load (lower [grains] softening) or the piston too fast",
             g->overlap, sc->dem.max_overlap, s_disp * 1e3, ov_with, ov_at[0] * 1e3,
             ov_at[1] * 1e3, ov_at[2] * 1e3);
  /* force balance of the bed: the forces it puts on the walls carry its weight and change its
   * momentum (Newton's second law over the step; a jolted or fast bed is no failure here, the
   * inertial number reports it) */
  double W = g->n_grains * g->m_grain * (sc->coupling.gravity ? G_ACC : 0), F[3] = {0, 0, 0};
  for (int m = 0; m < N_MESH; m++)
    for (int d = 0; d < 3; d++) F[d] += g->F_mesh[m][d];
  double p_end[3], dp[3];
  SA_CHECK(bed_momentum(g, p_end));
  for (int d = 0; d < 3; d++) dp[d] = p_end[d] - g->p_start[d];
  double scale = fabs(g->F_mesh[M_PISTON][2]) + W;
  g->balance = dem_momentum_residual(F, W, dp, g->T_step) / scale;
  g->piston_force = g->F_mesh[M_PISTON][2];
  g->wall_fz = g->F_mesh[M_WALL][2], g->barrel_fz = g->F_mesh[M_BARREL][2];
  if (step > 0)
    SA_REQUIRE(g->balance <= sc->dem.balance_tol, SA_ERR_DOMAIN, "force balance of the bed "
               "misses by %.1f %% of the load (piston %.4g N, walls %.4g N, barrel %.4g N, weight "
               "%.4g N, momentum change %.4g N s) at piston displacement %.3f mm: force is "
               "lost or invented (grains tunnelling, a DEM time step too large for the contact "
               "stiffness)", 100 * g->balance, g->piston_force, g->wall_fz, g->barrel_fz, W,
               dp[2], s_disp * 1e3);
  /* volume balance: bed volume = cavity + barrel below the piston; packing follows */
  double V = fem_solver_cavity_volume(g->s);
  double V_bed = g->V_bed0 + (V - g->V0) - M_PI * R_BORE * R_BORE * s_disp;
  g->phi = g->phi0 * g->V_bed0 / V_bed;
  double phi_max = 0.7405 * (1 + 3 * g->overlap);
  SA_REQUIRE(g->phi <= phi_max, SA_ERR_DOMAIN, "volume balance: the bed would be packed at %.3f "
             "(> %.3f, close packing with the measured overlap) at piston displacement %.3f mm: "
             "grains are lost through the wall or overlap too much", g->phi, phi_max,
             s_disp * 1e3);
  if (full) {
    SA_CHECK(dem_bridge_particles(g->b, g->px, NULL, NULL, NULL));
    int first, out = dem_bore_count_outside(g->bore, g->xw_cur, n, g->px, 0.5 * g->d, &first);
    SA_REQUIRE(!out, SA_ERR_DOMAIN, "%d grains are outside the bore at piston displacement "
               "%.3f mm (first at %.2f, %.2f, %.2f mm): they tunnelled through the wall (%s)",
               out, s_disp * 1e3, g->px[3 * first] * 1e3, g->px[3 * first + 1] * 1e3,
               g->px[3 * first + 2] * 1e3,
               g->E_sil > 0 ? "pushed through the compliant silicone: lower [dem] "
                              "max_indentation to stop before it, or shorten [piston] stroke"
                            : "lower [coupling] interval or [grains] softening");
  }
  g->t_checks += sa_time_now() - t0;
  return 0;
}

/* ------------------------------------------------------------------ outputs */

static int write_vtk(Run *g, double s_disp) {
  double t0 = sa_time_now();
  const FemMesh *m = g->m;
  char name[64], path[SA_STR_MAX], title[128];
  snprintf(name, sizeof name, "fem_%04d.vtk", g->vtk_index);
  SA_CHECK(sa_run_path(g->run, name, path));
  SA_CHECK(fem_solver_element_stress(g->s, g->sigma, g->vm, NULL));
  snprintf(title, sizeof title, "softact FEM-DEM silicone, piston displacement %.4f mm",
           s_disp * 1e3);
  SaVtk *v;
  SA_CHECK(sa_vtk_grid_open(path, g->run->vtk, title, m->nnodes, fem_solver_positions(g->s),
                            m->nelem, g->cell_types, g->cell_off, m->conn, &v));
  int rc = sa_vtk_point_data(v, "displacement", 3, fem_solver_displacements(g->s));
  if (!rc) rc = sa_vtk_cell_data(v, "cauchy_stress", 9, g->sigma);
  if (!rc) rc = sa_vtk_cell_data(v, "von_mises", 1, g->vm);
  if (!rc) rc = sa_vtk_cell_data(v, "region", 1, g->reg);
  if (rc) {
    sa_vtk_abort(&v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  SA_CHECK(sa_vtk_commit(&v));
  SA_CHECK(sa_vtk_series_add(g->vtk_fem, name, s_disp * 1e3));
  /* grains */
  int n = dem_bridge_count(g->b);
  SA_CHECK(dem_bridge_particles(g->b, g->px, g->pv, g->pf, g->pr));
  snprintf(name, sizeof name, "grains_%04d.vtk", g->vtk_index);
  SA_CHECK(sa_run_path(g->run, name, path));
  snprintf(title, sizeof title, "softact FEM-DEM grains, piston displacement %.4f mm",
           s_disp * 1e3);
  SA_CHECK(sa_vtk_points_open(path, g->run->vtk, title, n, g->px, &v));
  rc = sa_vtk_point_data(v, "radius", 1, g->pr);
  if (!rc) rc = sa_vtk_point_data(v, "velocity", 3, g->pv);
  if (!rc) rc = sa_vtk_point_data(v, "force", 3, g->pf);
  if (rc) {
    sa_vtk_abort(&v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  SA_CHECK(sa_vtk_commit(&v));
  SA_CHECK(sa_vtk_series_add(g->vtk_grains, name, s_disp * 1e3));
  if (g->vtk_index == g->cap_vtk) {
    int cap = g->cap_vtk ? 2 * g->cap_vtk : 64;
    double *t = realloc(g->vtk_t, sizeof(double) * (size_t)cap);
    SA_REQUIRE(t, SA_ERR_MEMORY, "VTK times");
    g->vtk_t = t, g->cap_vtk = cap;
  }
  g->vtk_t[g->vtk_index] = s_disp * 1e3;
  g->vtk_index++;
  g->t_out += sa_time_now() - t0;
  return 0;
}

static int open_outputs(Run *g) {
  const FemMesh *m = g->m;
  g->cell_types = malloc(sizeof(int) * m->nelem);
  g->cell_off = malloc(sizeof(int) * (m->nelem + 1));
  g->sigma = malloc(sizeof(double) * 9 * m->nelem);
  g->vm = malloc(sizeof(double) * m->nelem);
  g->reg = malloc(sizeof(double) * m->nelem);
  SA_REQUIRE(g->cell_types && g->cell_off && g->sigma && g->vm && g->reg, SA_ERR_MEMORY,
             "output buffers");
  for (int e = 0; e < m->nelem; e++) {
    g->cell_types[e] = m->nen == 10 ? SA_VTK_QUADRATIC_TETRA : SA_VTK_TETRA;
    g->cell_off[e] = e * m->nen;
    g->reg[e] = m->region ? m->region[e] : 0;
  }
  g->cell_off[m->nelem] = m->nelem * m->nen;
  static const char *names[] = {"piston_displacement", "bending_angle", "piston_force",
                                "displaced_volume", "volume_change_rel", "cavity_volume_change",
                                "packing_fraction", "wall_force_z", "barrel_force_z",
                                "max_overlap", "force_balance_error", "newton_iterations",
                                "time", "inertial_number", "max_indentation"};
  static const char *units[] = {"m", "deg", "N", "m^3", "-", "m^3", "-", "N", "N", "-", "-", "-",
                                "s", "-", "-"};
  char path[SA_STR_MAX];
  SA_CHECK(sa_run_path(g->run, "bending.csv", path));
  SA_CHECK(sa_csv_open(path, N_COLS, names, units, &g->csv));
  SA_CHECK(sa_run_path(g->run, "fem.vtk.series", path));
  SA_CHECK(sa_vtk_series_open(path, &g->vtk_fem));
  SA_CHECK(sa_run_path(g->run, "grains.vtk.series", path));
  SA_CHECK(sa_vtk_series_open(path, &g->vtk_grains));
  return 0;
}

/* The rows written so far are kept for a checkpoint (a resumed run writes them again). */
static int keep_row(Run *g, const double *row) {
  if (g->nrows == g->cap_rows) {
    int cap = g->cap_rows ? 2 * g->cap_rows : 256;
    double *r = realloc(g->rows, sizeof(double) * N_COLS * (size_t)cap);
    SA_REQUIRE(r, SA_ERR_MEMORY, "CSV rows");
    g->rows = r, g->cap_rows = cap;
  }
  memcpy(g->rows + (size_t)N_COLS * g->nrows++, row, sizeof(double) * N_COLS);
  return 0;
}

static int output_row(Run *g, double s_disp, double time) {
  double ang;
  SA_CHECK(fem_bending_angle(g->m, g->sc->coupling.tip_surface, fem_solver_positions(g->s), &ang));
  g->angle = ang;
  double V = fem_solver_cavity_volume(g->s), Vd = M_PI * R_BORE * R_BORE * s_disp;
  /* inertial number I = gamma_dot d / sqrt(P / rho) (GDR MiDi 2004): shear rate = piston speed
   * over the bed height below the piston, P = piston force over the bore area. Quasi-static
   * flow needs I << 1e-3; while the piston force is still ~0 (loose top layer) I is large but
   * meaningless, so the stroke's largest I is taken where the force passed 1 N. */
  double H = g->z_piston + 80e-3, P = fabs(g->piston_force) / (M_PI * R_BORE * R_BORE);
  double v = s_disp > 0 ? g->v_piston : 0;
  g->inertial = P > 0 ? v / H * g->d / sqrt(P / g->sc->grains.density) : 0;
  if (fabs(g->piston_force) >= 1.0) g->inertial_max = fmax(g->inertial_max, g->inertial);
  double row[N_COLS] = {s_disp, ang, g->piston_force, Vd, V / g->V0 - 1, V - g->V0, g->phi,
                        g->wall_fz, g->barrel_fz, g->overlap, g->balance, g->newton, time,
                        g->inertial, g->indent};
  SA_CHECK(keep_row(g, row));
  return sa_csv_row(g->csv, row);
}

/* gnuplot runs in the results folder (sa_plot.c), beside the CSV: named without a folder */
static void make_plots(const SaRun *run) {
  char png[SA_STR_MAX];
  if (sa_run_path(run, "bending_angle.png", png)) {
    sa_error_clear();
    return;
  }
  /* x in mm: gnuplot expression through a using-column scale */
  char body[2048];
  snprintf(body, sizeof body,
           "set datafile separator ','\nset grid\nset key top left\n"
           "set title 'Granular actuator: bending angle (FEM-DEM)'\n"
           "set xlabel 'piston displacement [mm]'\nset ylabel 'bending angle [deg]'\n"
           "plot '%s' skip 2 using ($1*1e3):2 with lines lw 2 title 'FEM-DEM (LIGGGHTS)'\n",
           "bending.csv");
  if (sa_plot_script(png, body)) sa_error_clear();
  if (sa_run_path(run, "piston_force.png", png)) {
    sa_error_clear();
    return;
  }
  snprintf(body, sizeof body,
           "set datafile separator ','\nset grid\nset key top left\n"
           "set title 'Granular actuator: piston force (FEM-DEM)'\n"
           "set xlabel 'piston displacement [mm]'\nset ylabel 'piston force [N]'\n"
           "plot '%s' skip 2 using ($1*1e3):3 with lines lw 2 title 'piston force', "
           "'' skip 2 using ($1*1e3):8 with lines title 'wall z-force', "
           "'' skip 2 using ($1*1e3):9 with lines title 'barrel z-force'\n", "bending.csv");
  if (sa_plot_script(png, body)) sa_error_clear();
  if (sa_run_path(run, "volume.png", png)) {
    sa_error_clear();
    return;
  }
  snprintf(body, sizeof body,
           "set datafile separator ','\nset grid\nset key top left\n"
           "set title 'Volume balance'\nset xlabel 'piston displacement [mm]'\n"
           "set ylabel 'volume [mm^3]'\n"
           "plot '%s' skip 2 using ($1*1e3):($4*1e9) with lines lw 2 title 'displaced volume', "
           "'' skip 2 using ($1*1e3):($6*1e9) with lines lw 2 title 'cavity volume change'\n",
           "bending.csv");
  if (sa_plot_script(png, body)) sa_error_clear();
}

static int write_summary(Run *g, double s_reached, const char *status, double wall) {
  char path[SA_STR_MAX];
  SaFile *f = NULL;
  SA_CHECK(sa_run_path(g->run, "summary.ini", path));
  SA_CHECK(sa_file_open(path, &f));
  FILE *fp = sa_file_stream(f);
  FemSolverStats st;
  fem_solver_stats(g->s, &st);
  double tot = g->t_dem + g->t_exchange + g->t_fem;
  /* the cavity of the last row: a run stopped inside a step leaves the FEM at its last pass */
  double vol_rel = g->nrows > 0 ? g->rows[(size_t)N_COLS * (g->nrows - 1) + 4] : 0.0;
  fprintf(fp, "; softact FEM-DEM granular bending summary\n[result]\n"
          "status = %s\npiston_displacement = %.9g ; m\nbending_angle = %.6f ; deg\n"
          "piston_force = %.6g ; N\nvolume_change_rel = %.6g\npacking_fraction_initial = %.5f\n"
          "packing_fraction_final = %.5f\nmax_overlap = %.5g ; of the diameter\n"
          "max_indentation = %.5g ; of the diameter, into the silicone wall (wall_contact = "
          "silicone)\n"
          "force_balance_error = %.4g\ngrains = %d\ninertial_number = %.4g\n"
          "inertial_number_max = %.4g ; largest once the piston force passed 1 N\n",
          status, s_reached, g->angle, g->piston_force,
          vol_rel, g->phi0, g->phi, g->overlap, g->indent, g->balance,
          g->n_grains, g->inertial, g->inertial_max);
  fprintf(fp, "\n[dem]\ntime_step = %.6g ; s\nyoung_used = %.6g ; Pa\nmpi_ranks = %d ; LIGGGHTS' "
          "domains (mpirun -np)\nsilicone_contact_young = %.6g ; Pa (0: the grains' modulus)\n",
          g->dt, g->sc->grains.young / g->sc->grains.softening,
          dem_par_size(), g->E_sil);
  fprintf(fp, "\n[timing]\nwall = %.3f ; s\n"
          "cpu = %.3f ; s (this process, user + system, all threads)\n"
          "dem = %.3f ; s\nexchange = %.3f ; s\nfem = %.3f ; s\n"
          "checks = %.3f ; s\noutput = %.3f ; s\nexchange_over_dem = %.4f\nfem_over_dem = %.4f\n"
          "dem_share = %.4f\n", wall, sa_cpu_time(), g->t_dem, g->t_exchange, g->t_fem, g->t_checks,
          g->t_out, g->t_exchange / fmax(g->t_dem, 1e-12), g->t_fem / fmax(g->t_dem, 1e-12),
          g->t_dem / fmax(tot, 1e-12));
  fprintf(fp, "\n[fem]\nnodes = %d\nelements = %d\nwall_vertices = %d\nwall_triangles = %d\n"
          "factorisations = %d\nreused_factors = %d\nassemblies = %d\n", st.nnodes, st.nelem,
          g->nv, g->nt, st.n_factor, st.n_reuse, st.n_assemble);
  if (g->iqn) /* counted since this process started (a resumed run counts its own part) */
    fprintf(fp, "\n[coupling]\niterated_steps = %d\niterations_mean = %.3f\niterations_max = %d\n"
            "residual_last = %.4g\nresidual_max = %.4g\n"
            "fixed_point_residual_max = %.4g ; |x~ - x| of an accepted step / the grains' wall "
            "displacement\nunconverged_steps = %d\n"
            "halved_steps = %d ; steps (or parts) redone as two halves, not converged\n"
            "overlap_rejected_passes = %d ; passes not accepted: an overlap above [dem] max_overlap "
            "or an indentation above max_indentation\n"
            "limited_trials = %d ; trial walls shortened by [coupling] max_trial_change\n"
            "rollback = %.3f ; s (DEM checkpoints, reloads and FEM snapshots)\n", g->it_steps,
            g->it_steps ? (double)g->it_sum / g->it_steps : 0.0, g->it_max, g->it_res,
            g->it_res_max, g->it_fp_max, g->it_unconverged, g->it_cuts, g->it_overlap,
            g->it_limited, g->t_rollback);
  return sa_file_commit(&f);
}

/* ------------------------------------------------------------------ the run */

/* ------------------------------------------------------------------ checkpoint */

/* <out>/checkpoint/dem.ckpt: the DEM bridge's (dem.h); state.ckpt: the FEM solver's state
 * (fem.h) and the run's own, in that order, written at a step boundary. A resumed run continues
 * the same floating-point path (the FEM refactorises after a checkpoint in both runs, the DEM
 * bridge does its set-up pass in both): test coupled_resume. */
typedef struct {
  char magic[8];
  int32_t nv, nrows, nvtk, next_step, n_grains, ncols;
  int64_t dem_step;
  double time, z_contact, z_piston, phi0, V_bed0, inertial_max;
  double t_dem, t_exchange, t_fem, t_out, t_checks;
} RunCheckpoint;
#define RUN_CK_MAGIC "SARUNCK1"

static int ck_paths(const Run *g, char *dir, char *dem, char *state) {
  SA_CHECK(sa_run_path(g->run, "checkpoint", dir));
  SA_CHECK(sa_path_join(dir, "dem.ckpt", dem));
  return sa_path_join(dir, "state.ckpt", state);
}

static int write_checkpoint(Run *g) {
  double t0 = sa_time_now();
  char dir[SA_STR_MAX], dem[SA_STR_MAX], st[SA_STR_MAX];
  SA_CHECK(ck_paths(g, dir, dem, st));
  SA_CHECK(sa_mkdir_p(dir));
  SA_CHECK(dem_bridge_write_checkpoint(g->b, dem));
  DemCheckpointInfo info;
  SA_CHECK(dem_bridge_checkpoint_info(dem, &info));
  RunCheckpoint h = {.nv = g->nv, .nrows = g->nrows, .nvtk = g->vtk_index,
                     .next_step = g->next_step, .n_grains = g->n_grains, .ncols = N_COLS,
                     .dem_step = info.step, .time = g->time, .z_contact = g->z_contact,
                     .z_piston = g->z_piston, .phi0 = g->phi0, .V_bed0 = g->V_bed0,
                     .inertial_max = g->inertial_max, .t_dem = g->t_dem,
                     .t_exchange = g->t_exchange, .t_fem = g->t_fem, .t_out = g->t_out,
                     .t_checks = g->t_checks};
  memcpy(h.magic, RUN_CK_MAGIC, 8);
  SaFile *f = NULL;
  SA_CHECK(sa_file_open(st, &f));
  FILE *fp = sa_file_stream(f);
  size_t v3 = 3 * (size_t)g->nv;
  int rc = fwrite(&h, sizeof h, 1, fp) == 1 ? 0 : SA_ERROR(SA_ERR_IO, "writing %s", st);
  if (!rc) rc = fem_solver_write_state(g->s, fp);
  const double *arr[] = {g->xw, g->xw_prev, g->xw_cur, g->f_app, g->rows, g->vtk_t};
  size_t len[] = {v3, v3, v3, v3, (size_t)N_COLS * g->nrows, (size_t)g->vtk_index};
  for (int k = 0; k < 6 && !rc; k++)
    if (len[k] && fwrite(arr[k], sizeof(double), len[k], fp) != len[k])
      rc = SA_ERROR(SA_ERR_IO, "writing %s", st);
  if (rc) {
    sa_file_abort(&f);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  SA_CHECK(sa_file_commit(&f));
  /* the quasi-Newton columns are not in the checkpoint: both the run that goes on and a run
   * resumed from it start the next step without them, and stay identical */
  if (g->iqn) dem_iqn_clear(g->iqn);
  /* several MPI ranks: go on from the checkpoint itself, as a resumed run starts. A LIGGGHTS
   * that has run holds each rank's wall triangles in the order their moves across the cut left
   * them, a resumed one in the file's order; the force sums then differ in the last bits, and
   * the coupled run's answer with them (measured: 2e-7 of the angle one step later) */
  if (dem_par_size() > 1) SA_CHECK(dem_reload_at(g, dem, g->xw, g->z_piston));
  sa_log(SA_LOG_INFO, "dem", "checkpoint after coupling step %d (%.1f s simulated) in %s",
         g->next_step, g->time, dir);
  g->t_out += sa_time_now() - t0;
  return 0;
}

/* The run's state and the FEM's from state.ckpt (the DEM bridge is resumed in setup_dem). */
static int read_checkpoint(Run *g, char *dem_path, double **xw_wall) {
  char dir[SA_STR_MAX], st[SA_STR_MAX];
  SA_CHECK(ck_paths(g, dir, dem_path, st));
  FILE *fp = fopen(st, "rb");
  SA_REQUIRE(fp, SA_ERR_INPUT, "[coupling] resume: no checkpoint %s (run the case without resume "
             "first, into the same --out folder)", st);
  RunCheckpoint h;
  int rc = fread(&h, sizeof h, 1, fp) == 1 && !memcmp(h.magic, RUN_CK_MAGIC, 8)
               ? 0
               : SA_ERROR(SA_ERR_INPUT, "%s is not a softact FEM-DEM checkpoint", st);
  if (!rc && (h.nv != g->nv || h.ncols != N_COLS || h.nrows < 0 || h.nvtk < 0))
    rc = SA_ERROR(SA_ERR_INPUT, "%s belongs to another model or build (%d wall vertices and %d "
                  "CSV columns; this case has %d, this build writes %d)", st, (int)h.nv,
                  (int)h.ncols, g->nv, N_COLS);
  if (!rc) rc = fem_solver_read_state(g->s, fp, st);
  size_t v3 = 3 * (size_t)g->nv;
  double *xw = NULL;
  if (!rc) {
    xw = malloc(sizeof(double) * v3);
    g->rows = malloc(sizeof(double) * N_COLS * (size_t)(h.nrows + 1));
    g->vtk_t = malloc(sizeof(double) * (size_t)(h.nvtk + 1));
    if (!xw || !g->rows || !g->vtk_t) rc = SA_ERROR(SA_ERR_MEMORY, "checkpoint buffers");
    g->cap_rows = h.nrows + 1, g->cap_vtk = h.nvtk + 1;
  }
  double *arr[] = {xw, g->xw_prev, g->xw_cur, g->f_app, g->rows, g->vtk_t};
  size_t len[] = {v3, v3, v3, v3, (size_t)N_COLS * h.nrows, (size_t)h.nvtk};
  for (int k = 0; k < 6 && !rc; k++)
    if (len[k] && fread(arr[k], sizeof(double), len[k], fp) != len[k])
      rc = SA_ERROR(SA_ERR_INPUT, "checkpoint %s is truncated", st);
  fclose(fp);
  DemCheckpointInfo info;
  if (!rc) rc = dem_bridge_checkpoint_info(dem_path, &info);
  if (!rc && (info.step != h.dem_step || info.count != h.n_grains))
    rc = SA_ERROR(SA_ERR_INPUT, "%s (step %lld, %d grains) does not belong to %s (step %lld, %d "
                  "grains): the run was stopped while writing; nothing to resume from", dem_path,
                  info.step, info.count, st, (long long)h.dem_step, (int)h.n_grains);
  if (rc) {
    free(xw);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  memcpy(g->xw, xw, sizeof(double) * v3);
  g->nrows = h.nrows, g->vtk_index = h.nvtk, g->next_step = h.next_step;
  g->n_grains = h.n_grains, g->time = h.time, g->z_contact = h.z_contact;
  g->z_piston = h.z_piston, g->phi0 = h.phi0, g->V_bed0 = h.V_bed0;
  g->inertial_max = h.inertial_max, g->t_dem = h.t_dem, g->t_exchange = h.t_exchange;
  g->t_fem = h.t_fem, g->t_out = h.t_out, g->t_checks = h.t_checks;
  *xw_wall = xw;
  sa_log(SA_LOG_INFO, "dem", "resuming after coupling step %d (%.1f s simulated, %d rows)",
         g->next_step, g->time, g->nrows);
  return 0;
}

/* A resumed run writes the rows and VTK entries of the first part again. */
static int replay_outputs(Run *g) {
  for (int r = 0; r < g->nrows; r++) SA_CHECK(sa_csv_row(g->csv, g->rows + (size_t)N_COLS * r));
  char name[64];
  for (int i = 0; i < g->vtk_index; i++) {
    snprintf(name, sizeof name, "fem_%04d.vtk", i);
    SA_CHECK(sa_vtk_series_add(g->vtk_fem, name, g->vtk_t[i]));
    snprintf(name, sizeof name, "grains_%04d.vtk", i);
    SA_CHECK(sa_vtk_series_add(g->vtk_grains, name, g->vtk_t[i]));
  }
  return 0;
}

/* Coupling steps from g->next_step on: N_PRELOAD with the piston at rest (the settled bed's
 * weight on the wall), then the stroke in steps of [coupling] interval. */
static int stroke(Run *g, double *s_reached) {
  const DemScene *sc = g->sc;
  const DemCouplingCase *cc = &sc->coupling;
  double v = sc->piston.speed, T = cc->interval / v;
  int nint = (int)ceil(sc->piston.stroke / cc->interval - 1e-9), ntot = N_PRELOAD + nint;
  SaProgress *prog = NULL;
  if (sa_progress_start("piston stroke", ntot, &prog)) sa_error_clear();
  if (prog) sa_progress_update(prog, g->next_step);
  *s_reached = g->next_step > N_PRELOAD
                   ? fmin((g->next_step - N_PRELOAD) * cc->interval, sc->piston.stroke)
                   : 0;
  int rc = 0, at_boundary = 0;
  /* the poured bed, before the preload: studies of the preload resume from it */
  if (g->next_step == 0 && cc->checkpoint_poured && !cc->resume) rc = write_checkpoint(g);
  for (int j = g->next_step; j < ntot && !rc; j++) {
    if (sa_interrupted()) {
      at_boundary = 1;
      rc = write_checkpoint(g);
      if (!rc)
        rc = SA_ERROR(SA_ERR_INTERRUPTED, "interrupted at piston displacement %.3f mm (resume "
                      "with --set coupling.resume=true)", *s_reached * 1e3);
      break;
    }
    if (j < N_PRELOAD) {
      rc = coupling_step(g, g->z_contact, 0, 0, T, j > 0 ? T : 0);
      if (!rc) rc = step_checks(g, 0, 0, j == N_PRELOAD - 1);
      if (rc) break;
      g->time += T;
      if (j == N_PRELOAD - 1) {
        rc = output_row(g, 0, g->time);
        if (!rc) rc = write_vtk(g, 0);
      }
    } else {
      int k = j - N_PRELOAD + 1;
      double s0, s1, v0, v1, Tk, T_last = T, q[4];
      const DemPistonCase *pc = &sc->piston;
      dem_piston_step(pc->stroke, cc->interval, v, pc->ramp_steps, k, &s0, &s1, &v0, &v1, &Tk);
      if (k > 1)
        dem_piston_step(pc->stroke, cc->interval, v, pc->ramp_steps, k - 1, q, q + 1, q + 2,
                        q + 3, &T_last);
      rc = coupling_step(g, g->z_contact - s0, v0, v1, Tk, T_last);
      if (!rc) rc = step_checks(g, k, s1, k % sc->dem.check_every == 0 || k == nint);
      if (rc) break;
      g->time += Tk;
      *s_reached = s1;
      rc = output_row(g, s1, g->time);
      int every = cc->vtk_every;
      if (!rc && ((every > 0 && k % every == 0) || k == nint)) rc = write_vtk(g, s1);
      sa_log(SA_LOG_DEBUG, "dem", "s = %.3f mm: angle %.3f deg, piston %.4g N, overlap %.3g, "
             "balance %.3g, phi %.4f, %d Newton", s1 * 1e3, g->angle, g->piston_force,
             g->overlap, g->balance, g->phi, g->newton);
      if (k % 10 == 0 || k == nint)
        sa_log(SA_LOG_INFO, "dem", "piston %6.2f mm: bending angle %7.3f deg, piston force "
               "%8.3f N, cavity volume %+.2f %%", s1 * 1e3, g->angle, g->piston_force,
               100 * (fem_solver_cavity_volume(g->s) / g->V0 - 1));
    }
    g->next_step = j + 1;
    if (!rc && cc->checkpoint_every > 0 && g->next_step % cc->checkpoint_every == 0 &&
        g->next_step < ntot)
      rc = write_checkpoint(g);
    if (prog) sa_progress_update(prog, j + 1);
  }
  if (rc == SA_ERR_INTERRUPTED && !at_boundary)
    /* stopped inside a coupling step (DEM chunks, Newton iterations), so that a signal is
     * answered within about a second, not at the end of a ~17 s step: the DEM is part-way
     * through the step, which cannot be checkpointed; the last checkpoint stays valid */
    sa_log(SA_LOG_WARN, "dem", "interrupted inside coupling step %d: the step is discarded; "
           "coupling.resume=true continues from the last checkpoint, if one was written",
           g->next_step);
  sa_progress_finish(&prog);
  return rc;
}

static void run_free(Run *g) {
  if (g->csv) sa_csv_abort(&g->csv);
  sa_vtk_series_close(&g->vtk_fem);
  sa_vtk_series_close(&g->vtk_grains);
  dem_bridge_destroy(&g->b);
  dem_bore_destroy(&g->bore);
  fem_coupling_surface_destroy(&g->cs);
  fem_solver_destroy(&g->s);
  fem_mesh_destroy(&g->m);
  free(g->mats);
  double *bufs[] = {g->xw_prev, g->xw_cur, g->xw, g->vw, g->f_tri, g->f_sum, g->f_node,
                    g->f_app, g->px, g->pv, g->pf, g->pr, g->sigma, g->vm, g->reg,
                    g->k_if, g->n_if, g->a_if, g->x_start, g->x_try, g->x_next, g->f_app0, g->x_hang,
                    g->x_prev0};
  for (size_t i = 0; i < sizeof bufs / sizeof *bufs; i++) free(bufs[i]);
  for (int k = 0; k < N_MESH; k++) free(g->mesh_x[k]), free(g->mesh_f[k]);
  free(g->piston_v);
  dem_iqn_destroy(&g->iqn);
  fem_snapshot_destroy(&g->snap);
  free(g->cell_types);
  free(g->cell_off);
  free(g->rows);
  free(g->vtk_t);
}

int dem_granular_run(const DemScene *sc, const SaRun *run) {
  Run g;
  memset(&g, 0, sizeof g);
  g.sc = sc, g.run = run;
  g.dynamic = !strcmp(sc->coupling.scheme, "dynamic");
  g.rigid = !strcmp(sc->coupling.scheme, "rigid");
  double t_start = sa_time_now(), s_reached = 0;
  int rc = dem_par_start();
  if (!rc && dem_par_size() > 1)
    sa_log(SA_LOG_INFO, "dem", "LIGGGHTS on %d MPI ranks (the FEM and the coupling on rank 0)",
           dem_par_size());
  if (!rc) rc = setup_fem(&g);
  if (sc->coupling.resume) {
    char dem[SA_STR_MAX];
    double *xw_wall = NULL;
    if (!rc) rc = read_checkpoint(&g, dem, &xw_wall);
    if (!rc) rc = setup_dem(&g, dem, xw_wall, g.z_piston, 0);
    free(xw_wall);
    if (!rc) rc = open_outputs(&g);
    if (!rc) rc = replay_outputs(&g);
  } else {
    if (!rc) rc = setup_dem(&g, NULL, NULL, 0, 0);
    if (!rc) rc = open_outputs(&g);
    if (!rc) rc = pour(&g);
  }
  if (!rc) rc = alloc_particles(&g, g.n_grains);
  if (!rc && !sc->coupling.resume) rc = lower_piston(&g, &g.z_contact);
  int started = !rc;
  if (!rc) rc = stroke(&g, &s_reached);
  if (started && g.inertial_max > 1e-3)
    sa_log(SA_LOG_WARN, "dem", "the bed's inertial number reached %.2g (> 1e-3): the flow is not "
           "quasi-static; slow the piston ([piston] speed) for a quasi-static result",
           g.inertial_max);
  if (g.csv && started) { /* keep what was computed, also after a failure */
    int r2 = sa_csv_commit(&g.csv);
    if (!rc) rc = r2;
  }
  if (rc && rc != SA_ERR_INTERRUPTED) sa_log(SA_LOG_ERROR, "dem", "%s", sa_error_message());
  if (started && g.s) {
    const char *status = !rc ? "completed" : rc == SA_ERR_INTERRUPTED ? "interrupted" : "stopped early";
    if (write_summary(&g, s_reached, status, sa_time_now() - t_start) && !rc)
      rc = SA_ERROR(SA_ERR_IO, "summary.ini");
    if (run->params.plots) make_plots(run);
  }
  sa_timing_add("dem", g.t_dem);
  sa_timing_add("exchange", g.t_exchange);
  sa_timing_add("  wall, piston at rest", g.t_x_wall_rest);
  sa_timing_add("  wall, piston moving", g.t_x_wall_moving);
  sa_timing_add("  piston", g.t_x_piston);
  sa_timing_add("  forces", g.t_x_forces);
  sa_timing_add("  forces to FEM loads", g.t_x_map);
  sa_timing_add("fem (coupling)", g.t_fem);
  if (g.iqn) sa_timing_add("rollback", g.t_rollback);
  sa_timing_add("run checks", g.t_checks);
  sa_timing_add("output (vtk)", g.t_out);
  if (started)
    sa_log(SA_LOG_INFO, "dem", "time: DEM %.1f s, exchange %.1f s (%.1f %% of DEM), FEM %.1f s "
           "(%.2f x DEM), checks %.1f s, VTK %.1f s", g.t_dem, g.t_exchange,
           100 * g.t_exchange / fmax(g.t_dem, 1e-12), g.t_fem, g.t_fem / fmax(g.t_dem, 1e-12),
           g.t_checks, g.t_out);
  if (g.iqn && started) {
    sa_log(SA_LOG_INFO, "dem", "coupling iterations: %.2f per step (most %d), rollback %.1f s, "
           "%d steps not converged, %d halved, %d trial walls shortened",
           g.it_steps ? (double)g.it_sum / g.it_steps : 0.0, g.it_max, g.t_rollback,
           g.it_unconverged, g.it_cuts, g.it_limited);
    char ck[SA_STR_MAX];
    if (!sa_run_path(run, "checkpoint/step.ckpt", ck)) remove(ck);
    else sa_error_clear();
  }
  run_free(&g); /* destroys the bridge on every rank */
  dem_par_release();
  dem_par_finish();
  return rc ? sa_error_push(rc, __func__, __FILE__, __LINE__) : 0;
}

int dem_granular_follow(const DemScene *sc) {
  (void)sc; /* a follower makes the lead's calls; the case only had to validate alike */
  int rc = dem_par_start();
  if (!rc) rc = dem_bridge_follow();
  dem_par_finish();
  return rc;
}
