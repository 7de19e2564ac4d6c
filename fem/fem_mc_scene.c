/* fem_mc_scene.c - the granular bending actuator with a Mohr-Coulomb continuum fill (issue 13,
 * the continuum prediction; cases/granular_bending_mc.ini, docs/mohr_coulomb.md "The actuator
 * scene"). The FEM-DEM scene's geometry and outputs with the grains replaced by one body.
 *
 * Model (/work/shared/ACTUATOR.md):
 *   - silicone actuator: the [mesh]/[material] of every actuator scene (meshes/actuator.geo),
 *     clamped on `fixed_surface`;
 *   - fill: its own body (meshes/fill.geo: the bore r = 6 mm from the cavity floor z = -80 mm to
 *     the bed surface fill_height), law mohr_coulomb from [fill], sharing no node with the
 *     silicone. Its cavity-side surface nodes are moved at set-up onto the silicone's faceted
 *     cavity surface (their closest point on the flat sub-triangles), so the two bodies start
 *     touching with zero gap: the fill's nodes on the true cylinder would otherwise penetrate the
 *     faceted wall by up to the chord's sagitta (~80 um for 2 mm sub-triangles, a contact
 *     pressure of MPa at any sensible penalty);
 *   - contact (fem_contact.h, node-to-surface penalty with Coulomb friction):
 *       fill_cavity (lateral z <= 0 + bottom) on the mesh master `wall_surface`, mu = friction_wall;
 *       fill_barrel (lateral z >= 0) on a rigid cylinder r = 6 mm, 0 <= z <= barrel_length,
 *         mu = friction_piston;
 *       fill_top on the piston: a rigid plane (normal -z) moved down with the solver's load factor
 *         (fem_contact_move_plane), mu = friction_piston.
 *     The piston is a plane and not a prescribed displacement of the top face: the bed must settle
 *     under gravity first with a free surface (a top face fixed from the start would carry the
 *     column), and the plane carries the piston friction of ACTUATOR.md; the plane's motion is
 *     ramped and cut by the solver like a load.
 *     Penalty: eps_N = penalty * E_fill / fill_h for every pair (docs/contact.md: alpha E / h);
 *   - symmetry: the problem is symmetric about the x-z plane, so the fill's nodes on y = 0 (the
 *     seam of the cylinder) are held in y; this removes the fill's rigid spin about the axis,
 *     which frictionless walls (the geostatic stage) leave free.
 * Procedure:
 *   1. geostatic stage: gravity on every body with frictionless walls (friction during the
 *      first loading stalls Newton, docs/contact.md); the settled fill's lateral stress ratio
 *      K = mean (sigma_xx + sigma_yy)/2 / mean sigma_zz away from the floor and the free surface
 *      is logged and written to summary.ini against nu/(1-nu) and 1 - sin phi;
 *   2. the wall and barrel friction are switched on (a solve at unchanged loads);
 *   3. the piston plane is placed on the highest node of the settled bed (displacement 0) and
 *      pushed by `stroke` in n_steps output steps; each step is a solver ramp with its own
 *      cut-backs (a failed substep is restored and cut, never accepted). If the solver gives up
 *      inside a step, the state it reached (the last accepted substep) is kept, the plane is
 *      re-placed there, and the next steps are split in two, up to max_cuts times; then the
 *      stroke ends and the results so far are written.
 * Outputs (as the FEM-DEM scene): bending.csv (piston_displacement [m], bending_angle [deg],
 * piston_force [N], displaced_volume [m^3], volume_change_rel, then the cavity and fill volume
 * changes, the contact forces on the fill, the force and volume balance errors, plastic strain
 * and solver counts), bending_angle.png, piston_force.png, volume.png, fem.vtk.series (silicone
 * and fill: displacement, Cauchy stress, von Mises, equivalent plastic strain, yielded flag,
 * region; time = piston displacement in mm), summary.ini.
 * Balances (every row; tests/apps/test_mc_bending.py checks them):
 *   force on the fill: F_piston + F_barrel + F_cavity + W_fill = 0 (z; Newton tolerance);
 *   volume: the fill fills the bore, so dV_fill = dV_cavity - A d + dV_overlap, with dV_overlap
 *   the change of the penalty overlap volume sum A_k <-g_k> of the three contacts. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem.h"
#include "fem_actuator.h"
#include "fem_contact.h"
#include "fem_element.h"
#include "fem_fill.h"
#include "sa_csv.h"
#include "sa_error.h"
#include "sa_log.h"
#include "sa_output.h"
#include "sa_plot.h"
#include "sa_vtk.h"

#define R_BORE 6e-3
#define G_ACC 9.81

typedef struct {
  char fill_geo[SA_STR_MAX], wall_surface[SA_STR_MAX], fixed_surface[SA_STR_MAX];
  char tip_surface[SA_STR_MAX], initial_stress[SA_STR_MAX], slave_weights[SA_STR_MAX];
  char fill_element[SA_STR_MAX];
  double fill_h, fill_height, barrel_length, stroke, penalty, penalty_tangent, augment_tol;
  double k0_ratio, piston_speed;
  int n_steps, max_cuts, vtk_every, gravity, smooth_normals, augment;
} McParams;

#define P(f) offsetof(McParams, f)
static const SaParam mc_params[] = {
    {"fill_geo", SA_PARAM_FILE, P(fill_geo), "-", "meshes/fill.geo", 0, 0, 0, NULL,
     "Gmsh source of the fill body (groups fill, fill_cavity, fill_barrel, fill_top)"},
    {"fill_h", SA_PARAM_REAL, P(fill_h), "m", "3e-3", 0, 0.05, SA_MIN_OPEN, NULL,
     "element size of the fill (its element order is [mesh] order; above ~4 mm a flat element "
     "with four corners on the surface can invert when the surface is put on the faceted wall)"},
    {"fill_height", SA_PARAM_REAL, P(fill_height), "m", "0.03", 0, 1, SA_MIN_OPEN, NULL,
     "bed surface above the top of the silicone (z = 0); the fill starts at the cavity floor"},
    {"barrel_length", SA_PARAM_REAL, P(barrel_length), "m", "0.04", 0, 1, SA_MIN_OPEN, NULL,
     "rigid feed barrel (radius 6 mm) from z = 0 up to this"},
    {"stroke", SA_PARAM_REAL, P(stroke), "m", "0.025", 0, 1, SA_MIN_OPEN, NULL,
     "piston displacement from touching the settled bed"},
    {"piston_speed", SA_PARAM_REAL, P(piston_speed), "m/s", "0.02", 0, 10, SA_MIN_OPEN, NULL,
     "piston speed: the stroke's time (a step of length d stands for d / piston_speed), which "
     "only a rate-dependent fill sees ([fill] relaxation_time > 0)"},
    {"n_steps", SA_PARAM_INT, P(n_steps), "-", "25", 1, 100000, 0, NULL,
     "output steps of the stroke (the solver substeps and cuts inside each)"},
    {"max_cuts", SA_PARAM_INT, P(max_cuts), "-", "4", 0, 30, 0, NULL,
     "times a step the solver gave up on is split in two before the stroke ends"},
    {"penalty", SA_PARAM_REAL, P(penalty), "-", "0.1", 0, 1e6, SA_MIN_OPEN, NULL,
     "contact penalty alpha: eps_N = alpha [fill] young / fill_h for every contact pair (0.1: "
     "the stroke converges; 1: stalls before 0.5 mm on the 3 mm mesh; docs/mohr_coulomb.md)"},
    {"penalty_tangent", SA_PARAM_REAL, P(penalty_tangent), "-", "1", 0, 1e3, SA_MIN_OPEN, NULL,
     "tangential penalty eps_T / eps_N"},
    {"augment", SA_PARAM_INT, P(augment), "-", "0", 0, 1000, 0, NULL,
     "augmented Lagrangian: most Uzawa updates of the normal contact pressures per stroke step "
     "(each one more solve at the same piston position), so the answer does not depend on the "
     "penalty; 0 = pure penalty (the contact layers then take part of the displaced volume)"},
    {"augment_tol", SA_PARAM_REAL, P(augment_tol), "-", "0.005", 0, 1, SA_MIN_OPEN, NULL,
     "augmented Lagrangian: a step is done when the penalty overlap volume of all contacts is "
     "below this fraction of the displaced volume (bore area x piston displacement, at least "
     "one step's: the settled bed is augmented before the stroke)"},
    {"smooth_normals", SA_PARAM_BOOL, P(smooth_normals), "-", "1", 0, 0, 0, NULL,
     "cavity contact: interpolated vertex normals of the faceted wall (0: facet normals, whose "
     "jumps at the facet edges stall Newton in this scene)"},
    {"slave_weights", SA_PARAM_CHOICE, P(slave_weights), "-", "lumped", 0, 0, 0,
     "lumped|consistent",
     "the fill's contact areas per node on tri6 faces (tet10 fill): lumped = corners 1/12, "
     "mid-nodes 1/4 of a face; consistent = corners 0, mid-nodes 1/3, which a uniform pressure "
     "needs (tet10 patch test, docs/contact.md), but leaves the corners free to penetrate"},
    {"fill_element", SA_PARAM_CHOICE, P(fill_element), "-", "composite", 0, 0, 0,
     "composite|quadratic",
     "the fill's tet10 ([mesh] order = 2): composite = piecewise linear over 8 sub-tets, whose "
     "faces the lumped slave_weights load exactly (passes the tet10 contact patch test); "
     "quadratic = the silicone's element, which fails that test with the lumped weights "
     "(docs/mohr_coulomb.md)"},
    {"gravity", SA_PARAM_BOOL, P(gravity), "-", "1", 0, 0, 0, NULL,
     "geostatic stage: gravity (-z, 9.81 m/s^2) on every body before the stroke"},
    {"initial_stress", SA_PARAM_CHOICE, P(initial_stress), "-", "none", 0, 0, 0, "none|k0",
     "the fill's settled stress: none = what the geostatic stage gives the stress-free fill "
     "(its lateral ratio set by the elasticity and the walls), k0 = a K0 procedure after it: "
     "the fill's stress replaced where it stands by vertical rho g depth and lateral k0_ratio "
     "times it, then balanced at the same loads (needs gravity and a tet4 fill; how much of "
     "it the balance keeps depends on the contact penalty, docs/mohr_coulomb.md)"},
    {"k0_ratio", SA_PARAM_REAL, P(k0_ratio), "-", "0", 0, 10, 0, NULL,
     "lateral stress ratio of initial_stress = k0 (0 = Jaky's 1 - sin(friction_angle); must lie "
     "in the Rankine range, active (1 - sin)/(1 + sin) to passive (1 + sin)/(1 - sin))"},
    {"vtk_every", SA_PARAM_INT, P(vtk_every), "-", "5", 0, 100000, 0, NULL,
     "write a VTK file every this many steps (0 = none; the settled state and the last step "
     "are always written)"},
    {"wall_surface", SA_PARAM_STRING, P(wall_surface), "-", "cavity_wall", 0, 0, 0, NULL,
     "silicone surface the fill touches (cavity wall and floor)"},
    {"fixed_surface", SA_PARAM_STRING, P(fixed_surface), "-", "fixed_end", 0, 0, 0, NULL,
     "silicone surface clamped in x, y and z"},
    {"tip_surface", SA_PARAM_STRING, P(tip_surface), "-", "tip", 0, 0, 0, NULL,
     "surface whose mean normal defines the bending angle"},
};
#undef P

static const SaParamTable mc_table = {
    "mc_bending", "fem", "granular actuator with a Mohr-Coulomb continuum fill (selects it)",
    mc_params, SA_NPARAMS(mc_params)};
static const SaParamTable *const mc_tables[] = {&mc_table, &fem_fill_table,
                                                &fem_actuator_mesh_table,
                                                &fem_actuator_material_table,
                                                &fem_actuator_solver_table};

typedef struct {
  McParams mc;
  FemFillParams fill;
  FemActuatorCase act;
} McScene;

static int mc_check(const SaCase *c, void **out) {
  *out = NULL;
  McScene *s;
  SA_CALLOC(s, 1);
  int rc = sa_params_load(&mc_table, c, &s->mc);
  if (!rc) rc = fem_fill_load(c, &s->fill);
  if (!rc) rc = fem_actuator_load(c, &s->act);
  if (!rc && s->mc.fill_height >= s->mc.barrel_length)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [mc_bending] fill_height = %g m must lie below the barrel's "
                  "top, barrel_length = %g m", sa_case_path(c), s->mc.fill_height,
                  s->mc.barrel_length);
  if (!rc && !strcmp(s->mc.initial_stress, "k0") && !s->mc.gravity)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [mc_bending] initial_stress = k0 needs gravity = true (a "
                  "geostatic stress without its weight is not in equilibrium)", sa_case_path(c));
  if (!rc && !strcmp(s->mc.initial_stress, "k0") && s->act.mesh.order != 1)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [mc_bending] initial_stress = k0 needs [mesh] order = 1 "
                  "(tet4 fill: the stress is replaced at each element's F, constant in a tet4)",
                  sa_case_path(c));
  if (!rc && !strcmp(s->mc.initial_stress, "k0")) {
    double k0 = s->mc.k0_ratio > 0 ? s->mc.k0_ratio : fem_fill_k0_jaky(s->fill.friction_angle);
    double ka, kp;
    fem_fill_rankine(s->fill.friction_angle, &ka, &kp);
    /* the cohesion widens the range near the surface only: the cohesionless range holds at depth */
    if (k0 < ka || k0 > kp)
      rc = SA_ERROR(SA_ERR_INPUT, "%s: [mc_bending] k0_ratio = %g lies outside the Rankine range "
                    "%.4g .. %.4g of friction_angle = %g deg (the stress would be outside the "
                    "yield surface)", sa_case_path(c), k0, ka, kp, s->fill.friction_angle);
  }
  if (!rc && s->mc.stroke >= s->mc.fill_height + 0.08)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [mc_bending] stroke = %g m exceeds the bed height",
                  sa_case_path(c), s->mc.stroke);
  if (rc) {
    free(s);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = s;
  return 0;
}

static void mc_write_resolved(const void *scene, FILE *f) {
  const McScene *s = scene;
  sa_params_write(&mc_table, &s->mc, f);
  fprintf(f, "\n");
  sa_params_write(&fem_fill_table, &s->fill, f);
  fprintf(f, "\n");
  fem_actuator_write_resolved(&s->act, f);
}

static void mc_destroy(void **scene) {
  if (!scene) return;
  free(*scene);
  *scene = NULL;
}

/* ------------------------------------------------------------------ geometry helpers */

/* Closest point q [out] on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection,
 * 5.1.5); returns the squared distance. */
static double closest_on_tri(const double *p, const double *a, const double *b, const double *c,
                             double q[3]) {
  double ab[3], ac[3], ap[3];
  for (int i = 0; i < 3; i++) ab[i] = b[i] - a[i], ac[i] = c[i] - a[i], ap[i] = p[i] - a[i];
#define DOT(u, v) ((u)[0] * (v)[0] + (u)[1] * (v)[1] + (u)[2] * (v)[2])
  double d1 = DOT(ab, ap), d2 = DOT(ac, ap), v, w;
  if (d1 <= 0 && d2 <= 0) {
    v = w = 0;
  } else {
    double bp[3], cp[3];
    for (int i = 0; i < 3; i++) bp[i] = p[i] - b[i], cp[i] = p[i] - c[i];
    double d3 = DOT(ab, bp), d4 = DOT(ac, bp), d5 = DOT(ab, cp), d6 = DOT(ac, cp);
    double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) v = 1, w = 0;
    else if (vc <= 0 && d1 >= 0 && d3 <= 0) v = d1 / (d1 - d3), w = 0;
    else if (d6 >= 0 && d5 <= d6) v = 0, w = 1;
    else if (vb <= 0 && d2 >= 0 && d6 <= 0) v = 0, w = d2 / (d2 - d6);
    else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      v = 1 - w;
    } else {
      double den = 1 / (va + vb + vc);
      v = vb * den, w = vc * den;
    }
  }
  double d = 0;
  for (int i = 0; i < 3; i++) {
    q[i] = a[i] + v * ab[i] + w * ac[i];
    d += (p[i] - q[i]) * (p[i] - q[i]);
  }
#undef DOT
  return d;
}

/* Flat triangles of a surface (tri6 -> its 4 corner/mid-node triangles), node indices. */
static int flat_triangles(const FemSurface *S, int **tri) {
  static const int sub[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
  int nsub = S->nfn == 6 ? 4 : 1, n = S->nfaces * nsub;
  *tri = malloc(sizeof(int) * 3 * (size_t)(n ? n : 1));
  SA_REQUIRE(*tri, SA_ERR_MEMORY, "triangles of %s", S->name);
  for (int f = 0; f < S->nfaces; f++)
    for (int k = 0; k < nsub; k++)
      for (int i = 0; i < 3; i++)
        (*tri)[3 * (f * nsub + k) + i] = S->faces[S->nfn * f + (nsub == 4 ? sub[k][i] : i)];
  return n;
}

/* Closest point q [out] to p on the flat triangles tri (nt, node indices into X); distance. */
static double closest_on_surface(const double *p, const double *X, const int *tri, int nt,
                                 double q[3]) {
  double best = INFINITY;
  for (int t = 0; t < nt; t++) {
    const double *a = X + 3 * tri[3 * t], *b = X + 3 * tri[3 * t + 1], *c = X + 3 * tri[3 * t + 2];
    double qt[3], d = closest_on_tri(p, a, b, c, qt);
    if (d < best) best = d, memcpy(q, qt, sizeof qt);
  }
  return sqrt(best);
}

/* Put the fill's surface `slave` (of fill [in/out]) on the faceted surface `master` of act [in]:
 * its corner nodes move to their closest point on the master's flat (sub-)triangles; a tet10
 * face's mid-node moves to the closest point to the midpoint of its (moved) corners, so a fill
 * edge bends only as the master does; the fill's other mid-nodes go to their edge midpoints (a
 * corner moved under an unmoved mid-node would curve the edge and can invert the element).
 * Nodes farther than tol from the master stay. max_move [out], nmoved [out]. */
static int snap_to_master(FemMesh *fill, const char *slave, const FemMesh *act,
                          const char *master, double tol, double *max_move, int *nmoved) {
  static const int edge[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  const FemSurface *S = fem_mesh_find_surface(fill, slave), *M = fem_mesh_find_surface(act, master);
  SA_REQUIRE(S && M, SA_ERR_INPUT, "surfaces %s / %s missing", slave, master);
  int *tri = NULL, nt = flat_triangles(M, &tri);
  SA_CHECK(nt < 0 ? nt : 0);
  char *on = calloc((size_t)fill->nnodes, 1);
  if (!on) {
    free(tri);
    return SA_ERROR(SA_ERR_MEMORY, "node flags");
  }
  for (int k = 0; k < S->nnodes; k++) on[S->nodes[k]] = 1;
  *max_move = 0;
  *nmoved = 0;
  double q[3];
  for (int f = 0; f < S->nfaces; f++)
    for (int a = 0; a < 3; a++) {
      int A = S->faces[S->nfn * f + a];
      if (on[A] != 1) continue;
      double *p = fill->xyz + 3 * A, d = closest_on_surface(p, act->xyz, tri, nt, q);
      on[A] = 2;
      if (d > tol) continue;
      *max_move = fmax(*max_move, d);
      memcpy(p, q, sizeof q);
      ++*nmoved;
    }
  if (S->nfn == 6) {
    static const int fe[3][2] = {{0, 1}, {1, 2}, {2, 0}};
    for (int f = 0; f < S->nfaces; f++)
      for (int j = 0; j < 3; j++) {
        const int *F = S->faces + 6 * f;
        int A = F[3 + j];
        if (on[A] != 1) continue;
        double mid[3];
        for (int i = 0; i < 3; i++)
          mid[i] = 0.5 * (fill->xyz[3 * F[fe[j][0]] + i] + fill->xyz[3 * F[fe[j][1]] + i]);
        double *p = fill->xyz + 3 * A, d = closest_on_surface(mid, act->xyz, tri, nt, q);
        on[A] = 2;
        if (d > tol) continue;
        double dd = 0;
        for (int i = 0; i < 3; i++) dd += (p[i] - q[i]) * (p[i] - q[i]);
        *max_move = fmax(*max_move, sqrt(dd));
        memcpy(p, q, sizeof q);
        ++*nmoved;
      }
  }
  if (fill->nen == 10)
    for (int e = 0; e < fill->nelem; e++) {
      const int *c = fill->conn + 10 * (size_t)e;
      for (int j = 0; j < 6; j++) {
        if (on[c[4 + j]]) continue;
        for (int i = 0; i < 3; i++)
          fill->xyz[3 * c[4 + j] + i] =
              0.5 * (fill->xyz[3 * c[edge[j][0]] + i] + fill->xyz[3 * c[edge[j][1]] + i]);
      }
    }
  free(on);
  free(tri);
  return 0;
}

/* Volume enclosed by the faces of the listed surfaces of m at positions x (outward normals). */
static double enclosed_volume(const FemMesh *m, int ns, const char *const *names, const double *x) {
  double V = 0, xf[18];
  for (int k = 0; k < ns; k++) {
    const FemSurface *S = fem_mesh_find_surface(m, names[k]);
    if (!S) continue;
    for (int f = 0; f < S->nfaces; f++) {
      for (int a = 0; a < S->nfn; a++)
        for (int i = 0; i < 3; i++) xf[3 * a + i] = x[3 * S->faces[S->nfn * f + a] + i];
      V -= fem_face_volume(S->nfn, xf, NULL, NULL);
    }
  }
  return V;
}

/* Penalty overlap volume sum A_k <-g_k> of a contact (committed state). */
static double overlap_volume(const FemContact *c) {
  const double *area, *gap;
  int n = fem_contact_slaves(c, NULL, &area, &gap, NULL, NULL, NULL);
  double v = 0;
  for (int k = 0; k < n; k++)
    if (gap[k] < 0) v -= area[k] * gap[k];
  return v;
}

/* ------------------------------------------------------------------ the run */

enum { C_WALL, C_BARREL, C_PISTON, NC };

#define N_COLS 19
typedef struct {
  const McScene *sc;
  const SaRun *run;
  FemMesh *m;
  FemSolver *s;
  FemContact *c[NC];
  SaCsv *csv;
  SaVtkSeries *series;
  int fill_region, nvtk, *cell_types, *cell_off;
  double *sigma, *vm, *epsp, *yield, *reg;
  double V_fill0, V_cav0, V_ov0, z_p0, weight_fill, angle0, angle, d, force, epsp_max;
  double K_ratio, K_sh, K_sv, balance_f, balance_v;
  int newton, cuts, nyield, augments, augment_unconverged;
  int augment_damped; /* updates retried with a fraction of the Uzawa step */
  FemSnapshot *snap; /* the state before an augmented solve */
  FemSnapshot *snap_step; /* the state at the step's start (mark_step) */
  int step_marked;
  double t_start;
} Mc;

static const char *fill_surfs[] = {"fill_cavity", "fill_barrel", "fill_top"};

static int write_vtk(Mc *o, int step) {
  const FemMesh *m = o->m;
  char name[64], path[SA_STR_MAX];
  snprintf(name, sizeof name, "fem_%04d.vtk", step);
  SA_CHECK(sa_run_path(o->run, name, path));
  SA_CHECK(fem_solver_element_stress(o->s, o->sigma, o->vm, NULL));
  fem_fill_history_mean(o->s, 6, o->epsp);
  fem_fill_history_mean(o->s, 7, o->yield);
  for (int e = 0; e < m->nelem; e++) o->yield[e] = o->yield[e] > 0 ? 1.0 : 0.0;
  SaVtk *v;
  char title[128];
  snprintf(title, sizeof title, "softact mc_bending piston %.6g mm", 1e3 * o->d);
  SA_CHECK(sa_vtk_grid_open(path, o->run->vtk, title, m->nnodes, fem_solver_positions(o->s),
                            m->nelem, o->cell_types, o->cell_off, m->conn, &v));
  int rc = sa_vtk_point_data(v, "displacement", 3, fem_solver_displacements(o->s));
  if (!rc) rc = sa_vtk_cell_data(v, "cauchy_stress", 9, o->sigma);
  if (!rc) rc = sa_vtk_cell_data(v, "von_mises", 1, o->vm);
  if (!rc) rc = sa_vtk_cell_data(v, "eq_plastic_strain", 1, o->epsp);
  if (!rc) rc = sa_vtk_cell_data(v, "yielded", 1, o->yield);
  if (!rc) rc = sa_vtk_cell_data(v, "region", 1, o->reg);
  if (rc) {
    sa_vtk_abort(&v);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  SA_CHECK(sa_vtk_commit(&v));
  /* time = piston displacement in mm, as the FEM-DEM scene */
  SA_CHECK(sa_vtk_series_add(o->series, name, 1e3 * o->d));
  o->nvtk++;
  return 0;
}

/* Lateral stress ratio of the settled fill: volume means over the fill elements between 10 mm
 * above the floor and 10 mm below the bed surface. */
static int lateral_ratio(Mc *o) {
  const FemMesh *m = o->m;
  SA_CHECK(fem_solver_element_stress(o->s, o->sigma, NULL, NULL));
  double sh = 0, sv = 0, vol = 0;
  for (int e = 0; e < m->nelem; e++) {
    if (m->region[e] != o->fill_region) continue;
    const int *c = m->conn + (size_t)m->nen * e;
    double zc = 0, a[3], b[3], d[3];
    for (int k = 0; k < 4; k++) zc += 0.25 * m->xyz[3 * c[k] + 2];
    if (zc < -0.07 || zc > o->sc->mc.fill_height - 0.01) continue;
    for (int i = 0; i < 3; i++) {
      a[i] = m->xyz[3 * c[1] + i] - m->xyz[3 * c[0] + i];
      b[i] = m->xyz[3 * c[2] + i] - m->xyz[3 * c[0] + i];
      d[i] = m->xyz[3 * c[3] + i] - m->xyz[3 * c[0] + i];
    }
    double v = fabs(a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                    a[2] * (b[0] * d[1] - b[1] * d[0])) / 6;
    const double *sg = o->sigma + 9 * e;
    sh -= v * 0.5 * (sg[0] + sg[4]);
    sv -= v * sg[8];
    vol += v;
  }
  o->K_sh = vol > 0 ? sh / vol : 0;
  o->K_sv = vol > 0 ? sv / vol : 0;
  o->K_ratio = sv != 0 ? sh / sv : 0;
  return 0;
}

static int output_row(Mc *o) {
  const FemMesh *m = o->m;
  const double *x = fem_solver_positions(o->s);
  double ang;
  SA_CHECK(fem_bending_angle(m, o->sc->mc.tip_surface, x, &ang));
  o->angle = ang;
  FemContactStats st[NC];
  for (int k = 0; k < NC; k++) fem_contact_stats(o->c[k], &st[k]);
  o->force = -st[C_PISTON].force[2];
  double fz = st[C_PISTON].force[2] + st[C_BARREL].force[2] + st[C_WALL].force[2] -
              (o->sc->mc.gravity ? o->weight_fill : 0);
  double scale = fabs(o->force) + o->weight_fill;
  for (int k = 0; k < NC; k++) scale += st[k].normal_force;
  o->balance_f = scale > 0 ? fz / scale : 0;
  double A = M_PI * R_BORE * R_BORE, Vd = A * o->d;
  double V = fem_solver_cavity_volume(o->s), Vf = enclosed_volume(m, 3, fill_surfs, x);
  double Vov = 0;
  for (int k = 0; k < NC; k++) Vov += overlap_volume(o->c[k]);
  double dVf = Vf - o->V_fill0, dVc = V - o->V_cav0, dVov = Vov - o->V_ov0;
  o->balance_v = (dVf - (dVc - Vd + dVov)) / fmax(Vd, 1e-12 * A);
  fem_fill_history_mean(o->s, 6, o->epsp);
  fem_fill_history_mean(o->s, 7, o->yield);
  o->epsp_max = 0;
  o->nyield = 0;
  for (int e = 0; e < m->nelem; e++) {
    o->epsp_max = fmax(o->epsp_max, o->epsp[e]);
    o->nyield += o->yield[e] > 0;
  }
  double row[N_COLS] = {o->d, ang, o->force, Vd, V / o->V_cav0 - 1, dVc, dVf, dVov,
                        st[C_BARREL].force[2], st[C_WALL].force[2], st[C_WALL].normal_force,
                        o->balance_f, o->balance_v, st[C_WALL].max_penetration,
                        o->epsp_max, o->nyield, o->newton, o->cuts, sa_time_now() - o->t_start};
  SA_CHECK(sa_csv_row(o->csv, row));
  sa_log(SA_LOG_INFO, "mc", "piston %6.3f mm: angle %7.3f deg, force %8.3f N (upward on the fill: barrel "
         "%.3f, cavity %.3f N), cavity %+.4f %%, displaced %.1f mm^3, fill dV %+.2f mm^3; balance force %.1e "
         "volume %.1e; eps_p max %.3g, %d yielded elements; %d Newton, %d cuts", 1e3 * o->d, ang,
         o->force, st[C_BARREL].force[2], st[C_WALL].force[2], 100 * (V / o->V_cav0 - 1),
         Vd * 1e9, dVf * 1e9, o->balance_f, o->balance_v, o->epsp_max, o->nyield, o->newton,
         o->cuts);
  return 0;
}

/* gnuplot runs in the results folder (sa_plot.c), beside the CSV: named without a folder */
static void make_plots(const SaRun *run) {
  char png[SA_STR_MAX], body[2048];
  if (sa_run_path(run, "bending_angle.png", png)) {
    sa_error_clear();
    return;
  }
  snprintf(body, sizeof body,
           "set datafile separator ','\nset grid\nset key top left\n"
           "set title 'Granular actuator: bending angle (Mohr-Coulomb fill)'\n"
           "set xlabel 'piston displacement [mm]'\nset ylabel 'bending angle [deg]'\n"
           "plot '%s' skip 2 using ($1*1e3):2 with linespoints pt 7 ps 0.6 lw 2 title "
           "'FEM, Mohr-Coulomb continuum'\n", "bending.csv");
  if (sa_plot_script(png, body)) sa_error_clear();
  if (sa_run_path(run, "piston_force.png", png)) {
    sa_error_clear();
    return;
  }
  snprintf(body, sizeof body,
           "set datafile separator ','\nset grid\nset key top left\n"
           "set title 'Granular actuator: piston force (Mohr-Coulomb fill)'\n"
           "set xlabel 'piston displacement [mm]'\nset ylabel 'force [N]'\n"
           "plot '%s' skip 2 using ($1*1e3):3 with linespoints pt 7 ps 0.6 lw 2 title 'piston "
           "force', '' skip 2 using ($1*1e3):9 with lines title 'barrel friction (up)', "
           "'' skip 2 using ($1*1e3):10 with lines title 'cavity wall + floor (up)'\n", "bending.csv");
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
           "'' skip 2 using ($1*1e3):($6*1e9) with lines lw 2 title 'cavity volume change', "
           "'' skip 2 using ($1*1e3):(-$7*1e9) with lines lw 2 title 'fill volume loss'\n", "bending.csv");
  if (sa_plot_script(png, body)) sa_error_clear();
}

static int build(Mc *o) {
  const McScene *sc = o->sc;
  const McParams *P = &sc->mc;
  FemMesh *fill = NULL;
  SA_CHECK(fem_actuator_mesh(&sc->act, &o->m));
  const char *asurf[] = {P->wall_surface, P->fixed_surface, P->tip_surface};
  SA_CHECK(fem_mesh_require(o->m, 0, NULL, 3, asurf));
  FemGeoParam gp[] = {{"R_bore", R_BORE}, {"z_floor", -80e-3}, {"z_top", P->fill_height}};
  double t0 = sa_time_now();
  SA_CHECK(fem_mesh_generate(P->fill_geo, 3, gp, P->fill_h, sc->act.mesh.order, &fill));
  sa_timing_add("fem mesh", sa_time_now() - t0);
  const char *freg[] = {"fill"};
  int rc = fem_mesh_require(fill, 1, freg, 3, fill_surfs);
  double mv = 0;
  int nmv = 0;
  if (!rc) rc = snap_to_master(fill, "fill_cavity", o->m, P->wall_surface, 0.25 * P->fill_h, &mv, &nmv);
  /* a start in contact: a bed node at a gap of +1e-19 m would be out of contact, and the fill,
   * held only by frictionless contacts, would float in the first iterate. The fill is scaled
   * radially by 1 + 1e-6 and lowered by 10 nm: every surface node starts ~6-10 nm deep (a contact
   * pressure of ~0.1 % of the settled stress), the fill itself stays stress-free */
  for (int A = 0; !rc && A < fill->nnodes; A++) {
    fill->xyz[3 * A] *= 1 + 1e-6;
    fill->xyz[3 * A + 1] *= 1 + 1e-6;
    fill->xyz[3 * A + 2] -= 1e-8;
  }
  if (!rc)
    sa_log(SA_LOG_INFO, "mc", "fill: %d nodes, %d elements; %d cavity-side nodes moved onto the "
           "faceted cavity wall (largest move %.1f um)", fill->nnodes, fill->nelem, nmv, 1e6 * mv);
  FemMaterial *mats = NULL;
  int nact = o->m->nregions;
  if (!rc) {
    mats = calloc((size_t)nact + fill->nregions, sizeof *mats);
    if (!mats) rc = SA_ERROR(SA_ERR_MEMORY, "materials");
  }
  if (!rc) rc = fem_actuator_materials(&sc->act, o->m, mats);
  if (!rc) rc = fem_fill_material(&sc->fill, &mats[nact]);
  if (!rc && sc->act.mesh.order == 2 && !strcmp(P->fill_element, "composite")) {
    mats[nact].tet10_composite = 1;
    if (!strcmp(P->slave_weights, "consistent"))
      sa_log(SA_LOG_WARN, "mc", "fill_element = composite with slave_weights = consistent: a "
             "composite face's consistent loads are the lumped weights (corners 1/12, mid-nodes "
             "1/4); the consistent (quadratic) ones leave its corners without contact force");
  }
  if (!rc) rc = fem_mesh_append(o->m, fill);
  fem_mesh_destroy(&fill);
  o->fill_region = nact;
  FemSolverParams prm = fem_actuator_solver_params(&sc->act, o->run->threads);
  /* the first ramp (gravity) from 1/64: from 1 it was cut 6 times (inverted elements, stalls)
   * before 1/64 converged, ~60 wasted factorisations; later ramps start from the last
   * accepted increment */
  prm.dl_init = 1.0 / 64;
  if (!rc) rc = fem_solver_create(o->m, mats, &prm, &o->s);
  free(mats);
  SA_CHECK(rc);
  FemMesh *m = o->m;
  SA_CHECK(fem_solver_fix_surface(o->s, P->fixed_surface, FEM_XYZ));
  /* symmetry about y = 0: the fill's seam nodes held in y (no spin about the axis) */
  int nsym = 0;
  for (int e = 0; e < m->nelem; e++) {
    if (m->region[e] != o->fill_region) continue;
    for (int a = 0; a < m->nen; a++) {
      int A = m->conn[(size_t)m->nen * e + a];
      if (fabs(m->xyz[3 * A + 1]) < 1e-9 * R_BORE) {
        SA_CHECK(fem_solver_fix_nodes(o->s, 1, &A, FEM_Y));
        nsym++;
      }
    }
  }
  SA_REQUIRE(nsym > 0, SA_ERR_INPUT, "%s: no fill node on y = 0 to hold the spin", P->fill_geo);
  /* the cavity volume (pressure surface at p = 0) */
  SA_CHECK(fem_solver_add_pressure_surface(o->s, P->wall_surface));
  FemContactParams cp = fem_contact_params_default();
  cp.penalty = P->penalty * sc->fill.young / P->fill_h;
  cp.penalty_tangent = P->penalty_tangent * cp.penalty;
  cp.search_radius = 2 * P->fill_h;
  cp.smooth_normals = P->smooth_normals;
  cp.slave_weights = strcmp(P->slave_weights, "consistent") ? FEM_CONTACT_WEIGHTS_LUMPED
                                                            : FEM_CONTACT_WEIGHTS_CONSISTENT;
  cp.friction = 0; /* geostatic stage: frictionless */
  SA_CHECK(fem_contact_create(m, "fill_cavity", &cp, &o->c[C_WALL]));
  SA_CHECK(fem_contact_set_master(o->c[C_WALL], P->wall_surface));
  SA_CHECK(fem_contact_create(m, "fill_barrel", &cp, &o->c[C_BARREL]));
  SA_CHECK(fem_contact_set_cylinder(o->c[C_BARREL], (const double[3]){0, 0, 0},
                                    (const double[3]){0, 0, 1}, R_BORE, 0, P->barrel_length));
  cp.friction = sc->fill.friction_piston;
  SA_CHECK(fem_contact_create(m, "fill_top", &cp, &o->c[C_PISTON]));
  /* above the bed during the geostatic stage */
  SA_CHECK(fem_contact_set_plane(o->c[C_PISTON], (const double[3]){0, 0, P->barrel_length},
                                 (const double[3]){0, 0, -1}));
  for (int k = 0; k < NC; k++) SA_CHECK(fem_contact_attach(o->c[k], o->s));
  if (P->gravity) o->weight_fill = sc->fill.density * G_ACC * fem_mesh_volume(m, o->fill_region);
  SA_CHECK(fem_solver_setup(o->s));
  o->cell_types = malloc(sizeof(int) * m->nelem);
  o->cell_off = malloc(sizeof(int) * (m->nelem + 1));
  o->sigma = malloc(sizeof(double) * 9 * m->nelem);
  o->vm = malloc(sizeof(double) * m->nelem);
  o->epsp = malloc(sizeof(double) * m->nelem);
  o->yield = malloc(sizeof(double) * m->nelem);
  o->reg = malloc(sizeof(double) * m->nelem);
  SA_REQUIRE(o->cell_types && o->cell_off && o->sigma && o->vm && o->epsp && o->yield && o->reg,
             SA_ERR_MEMORY, "output buffers");
  for (int e = 0; e < m->nelem; e++) {
    o->cell_types[e] = m->nen == 10 ? SA_VTK_QUADRATIC_TETRA : SA_VTK_TETRA;
    o->cell_off[e] = e * m->nen;
    o->reg[e] = m->region[e];
  }
  o->cell_off[m->nelem] = m->nelem * m->nen;
  return 0;
}

static void accumulate(Mc *o) {
  FemSolveReport rep;
  fem_solver_report(o->s, &rep);
  o->newton += rep.newton_iters;
  o->cuts += rep.cuts;
}

/* The start of a load step: the contacts' stick anchors, committed plane point and
 * multipliers (fem_contact_mark) and the solver's state (positions, material history). With
 * friction each augmented solve of the step is the whole step again from there (restore_step),
 * so the step stays one backward-Euler increment whatever the number of Uzawa updates: the
 * plastic flow and slip that the first, penalty-soft solve committed would otherwise stay in
 * the answer and make it depend on the penalty (docs/contact.md). */
static int mark_step(Mc *o) {
  for (int k = 0; k < NC; k++) fem_contact_mark(o->c[k]);
  SA_CHECK(fem_solver_snapshot(o->s, &o->snap_step));
  o->step_marked = 1;
  return 0;
}

static int restore_step(Mc *o) {
  /* Frictionless the updates continue from the last solve (only the stick anchors, unused,
   * go back): restarted, the CI mesh's Newton fell into a 2-cycle after the second update and
   * the step failed, while the incremental path is penalty-independent to 1.3-3.5 % there
   * (test mc_augmented). With friction the incremental path left the answer 12-47 % apart
   * between penalties. */
  const McScene *sc = o->sc;
  if (!o->step_marked || (sc->fill.friction_wall <= 0 && sc->fill.friction_piston <= 0)) {
    for (int k = 0; k < NC; k++) fem_contact_restore_mark(o->c[k]);
    return 0;
  }
  SA_CHECK(fem_solver_rollback(o->s, o->snap_step));
  for (int k = 0; k < NC; k++) fem_contact_rewind(o->c[k]);
  return 0;
}

/* Augmented Lagrangian at the piston position reached: Uzawa updates of every contact's
 * multipliers, each followed by a solve at the same loads (the plane's committed point is its
 * target after a completed ramp, so it stays), until the overlap volume is below augment_tol of
 * the displaced volume. The last update is kept for the next step (a warm start). */
#define AUGMENT_DAMP_MIN 0.25 /* the smallest fraction of an update tried after failures */

static int augment_step(Mc *o) {
  const McParams *P = &o->sc->mc;
  if (P->augment <= 0) return 0;
  /* at least one step's displaced volume: the settled bed (d = 0) is augmented too */
  double Vd = M_PI * R_BORE * R_BORE * fmax(o->d, P->stroke / P->n_steps), vol = 0, pen = 0;
  double slack = 0;
  for (int it = 0;; it++) {
    vol = pen = slack = 0;
    for (int k = 0; k < NC; k++) {
      double p, v;
      FemContactStats st;
      fem_contact_stats(o->c[k], &st); /* the committed state, before the update */
      slack += st.tangent_slack;
      SA_CHECK(fem_contact_augment(o->c[k], &p, &v));
      vol += v;
      pen = fmax(pen, p);
    }
    sa_log(SA_LOG_DEBUG, "mc", "augmentation %d at %.4g mm: overlap %.3g mm^3 (%.3g of the "
           "displaced volume), largest penetration %.3g um, tangential slack %.3g mm^3 (%.3g)",
           it, 1e3 * o->d, vol * 1e9, vol / Vd, pen * 1e6, slack * 1e9, slack / Vd);
    /* done when neither the normal nor (with friction) the tangential penalty carries a part of
     * the displaced volume above the tolerance */
    if (vol <= P->augment_tol * Vd && slack <= P->augment_tol * Vd) return 0;
    if (it == P->augment) break;
    /* a failed update must leave the last converged state, multipliers and anchors */
    SA_CHECK(fem_solver_snapshot(o->s, &o->snap));
    for (int k = 0; k < NC; k++) SA_CHECK(fem_contact_save(o->c[k]));
    /* A solve that fails is retried from the same state with half the update, then a quarter
     * (measured on the production mesh, 2026-12-06: whole updates at 0.5 and 1.5 mm failed
     * after tens of cut substeps, their Newton iterations stalling on stick/slip changes) */
    for (double omega = 1.0;; omega *= 0.5) {
      SA_CHECK(restore_step(o));
      int rc = fem_solver_solve(o->s);
      accumulate(o);
      o->augments++;
      if (rc < 0) return sa_error_push(rc, __func__, __FILE__, __LINE__);
      if (rc == 0) break;
      /* recoverable: back to the last converged solve (which drops the pending update) */
      sa_error_clear();
      SA_CHECK(fem_solver_rollback(o->s, o->snap));
      for (int k = 0; k < NC; k++) SA_CHECK(fem_contact_restore(o->c[k]));
      if (omega <= AUGMENT_DAMP_MIN) { /* the next step goes on from here */
        o->augment_unconverged++;
        sa_log(SA_LOG_WARN, "mc", "solve after augmentation %d at %.4g mm failed, also with "
               "%.3g of the update; back to the last converged state (overlap %.3g of the "
               "displaced volume)", it + 1, 1e3 * o->d, omega, vol / Vd);
        return 0;
      }
      sa_log(SA_LOG_INFO, "mc", "solve after augmentation %d at %.4g mm failed; again with %.3g "
             "of the update", it + 1, 1e3 * o->d, 0.5 * omega);
      o->augment_damped++;
      for (int k = 0; k < NC; k++) {
        SA_CHECK(fem_contact_augment(o->c[k], NULL, NULL));
        SA_CHECK(fem_contact_augment_damp(o->c[k], 0.5 * omega));
      }
    }
  }
  o->augment_unconverged++;
  sa_log(SA_LOG_WARN, "mc", "augmented Lagrangian at %.4g mm: overlap still %.3g, tangential "
         "slack %.3g of the displaced volume after %d updates (augment_tol %.3g)", 1e3 * o->d,
         vol / Vd, slack / Vd, P->augment, P->augment_tol);
  return 0;
}

/* Stages 1 and 2: gravity with frictionless walls, then friction on. */
static int geostatic(Mc *o) {
  const McScene *sc = o->sc;
  if (sc->mc.gravity) {
    SA_CHECK(fem_solver_set_gravity(o->s, (const double[3]){0, 0, -G_ACC}));
    double t0 = sa_time_now();
    int rc = fem_solver_solve(o->s);
    accumulate(o);
    if (rc) {
      sa_log(SA_LOG_ERROR, "mc", "geostatic stage failed");
      return sa_error_push(rc, __func__, __FILE__, __LINE__);
    }
    /* the K0 procedure: the settled fill's stress replaced by the geostatic K0 state where it
     * stands, then balanced at the same loads. Imposing it on the stress-free fill instead
     * needs the full weight in one increment, which inverts fill and silicone elements at the
     * cavity's top edge (also without the initial stress; measured on the CI mesh) */
    if (!strcmp(sc->mc.initial_stress, "k0")) {
      int nset = 0;
      SA_CHECK(fem_fill_k0_stress(o->s, o->fill_region, &sc->fill, sc->mc.fill_height,
                                  sc->mc.k0_ratio, G_ACC, &nset));
      SA_CHECK(lateral_ratio(o));
      sa_log(SA_LOG_INFO, "mc", "K0 procedure: the stress of %d fill elements replaced (lateral "
             "ratio %.4f as imposed); balancing it", nset, o->K_ratio);
      rc = fem_solver_solve(o->s);
      accumulate(o);
      if (rc) {
        sa_log(SA_LOG_ERROR, "mc", "balancing the K0 stress failed");
        return sa_error_push(rc, __func__, __FILE__, __LINE__);
      }
    }
    /* frictionless, the settled state is unique: augmented here it does not depend on the
     * penalty (with friction on, the nodes stick where the penalty left them) */
    SA_CHECK(augment_step(o));
    SA_CHECK(lateral_ratio(o));
    double nu = sc->fill.poisson, phi = sc->fill.friction_angle * M_PI / 180;
    sa_log(SA_LOG_INFO, "mc", "geostatic stage: %.2f s, %d Newton iterations; fill lateral "
           "stress ratio K = %.4f (mean sigma_h %.1f Pa, sigma_v %.1f Pa; nu/(1-nu) = %.4f, "
           "1 - sin phi = %.4f)", sa_time_now() - t0, o->newton, o->K_ratio, o->K_sh, o->K_sv,
           nu / (1 - nu), 1 - sin(phi));
  }
  SA_CHECK(fem_contact_set_friction(o->c[C_WALL], sc->fill.friction_wall));
  SA_CHECK(fem_contact_set_friction(o->c[C_BARREL], sc->fill.friction_piston));
  SA_CHECK(mark_step(o));
  /* without the geostatic stage nothing is loaded: the reference state needs no solve (the
   * solve would only chase the nm start-in-contact overlap at round-off force levels) */
  if (!sc->mc.gravity) return 0;
  int rc = fem_solver_solve(o->s);
  accumulate(o);
  if (rc) {
    sa_log(SA_LOG_ERROR, "mc", "switching the wall friction on failed");
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  return augment_step(o);
}

/* Stage 3: the stroke. Returns 0 when the stroke is complete, > 0 (recoverable code) when it
 * ended early with the state reached written. */
static int stroke(Mc *o, double *d_reached) {
  const McParams *P = &o->sc->mc;
  const FemMesh *m = o->m;
  const FemSurface *top = fem_mesh_find_surface(m, "fill_top");
  const double *x = fem_solver_positions(o->s);
  o->z_p0 = -INFINITY;
  for (int k = 0; k < top->nnodes; k++) o->z_p0 = fmax(o->z_p0, x[3 * top->nodes[k] + 2]);
  SA_CHECK(fem_contact_set_plane(o->c[C_PISTON], (const double[3]){0, 0, o->z_p0},
                                 (const double[3]){0, 0, -1}));
  double dd = P->stroke / P->n_steps;
  int cuts = 0, step = 0, rc_end = 0;
  *d_reached = 0;
  while (o->d < P->stroke * (1 - 1e-12)) {
    if (sa_interrupted()) return SA_ERROR(SA_ERR_INTERRUPTED, "interrupted at %.4g mm", 1e3 * o->d);
    double dt = fmin(dd, P->stroke - o->d);
    SA_CHECK(fem_contact_move_plane(o->c[C_PISTON], (const double[3]){0, 0, o->z_p0 - o->d - dt}));
    /* the step's time, for a rate-dependent fill ([fill] relaxation_time) */
    SA_CHECK(fem_solver_set_static_interval(o->s, dt / P->piston_speed));
    SA_CHECK(mark_step(o));
    int rc = fem_solver_solve(o->s);
    FemSolveReport rep;
    fem_solver_report(o->s, &rep);
    accumulate(o);
    if (rc < 0) return sa_error_push(rc, __func__, __FILE__, __LINE__);
    if (rc > 0) {
      double got = rep.lambda * dt;
      sa_log(SA_LOG_WARN, "mc", "step to %.4g mm failed after %.4g of it (%s)",
             1e3 * (o->d + dt), rep.lambda, rep.reason);
      sa_error_clear();
      o->d += got;
      /* the plane's committed point is still the step's start: put it where the fill is */
      SA_CHECK(fem_contact_set_plane(o->c[C_PISTON], (const double[3]){0, 0, o->z_p0 - o->d},
                                     (const double[3]){0, 0, -1}));
      if (got > 0) SA_CHECK(output_row(o));
      if (++cuts > P->max_cuts) {
        rc_end = rc;
        break;
      }
      dd *= 0.5;
      continue;
    }
    o->d += dt;
    step++;
    SA_CHECK(augment_step(o));
    SA_CHECK(output_row(o));
    int last = o->d >= P->stroke * (1 - 1e-12);
    if ((P->vtk_every > 0 && step % P->vtk_every == 0) || last) SA_CHECK(write_vtk(o, step));
  }
  *d_reached = o->d;
  if (rc_end) SA_CHECK(write_vtk(o, step + 1));
  return rc_end;
}

static int mc_run(void *scene, SaRun *run) {
  McScene *sc = scene;
  Mc o = {.sc = sc, .run = run, .t_start = sa_time_now()};
  int rc = build(&o);
  char path[SA_STR_MAX];
  static const char *names[N_COLS] = {
      "piston_displacement", "bending_angle", "piston_force", "displaced_volume",
      "volume_change_rel", "cavity_volume_change", "fill_volume_change", "overlap_volume_change",
      "barrel_force_z", "wall_force_z", "wall_normal_force", "force_balance_error",
      "volume_balance_error", "max_penetration", "max_plastic_strain", "yielded_elements",
      "newton_iterations", "cuts", "time"};
  static const char *units[N_COLS] = {"m", "deg", "N", "m^3", "-", "m^3", "m^3", "m^3", "N", "N",
                                      "N", "-", "-", "m", "-", "-", "-", "-", "s"};
  if (!rc) rc = sa_run_path(run, "bending.csv", path);
  if (!rc) rc = sa_csv_open(path, N_COLS, names, units, &o.csv);
  if (!rc) rc = sa_run_path(run, "fem.vtk.series", path);
  if (!rc) rc = sa_vtk_series_open(path, &o.series);
  double t_geo = sa_time_now();
  if (!rc) rc = geostatic(&o);
  t_geo = sa_time_now() - t_geo;
  int newton_geo = o.newton;
  if (!rc) {
    fem_bending_angle(o.m, sc->mc.tip_surface, fem_solver_positions(o.s), &o.angle0);
    o.V_cav0 = fem_solver_cavity_volume(o.s);
    o.V_fill0 = enclosed_volume(o.m, 3, fill_surfs, fem_solver_positions(o.s));
    for (int k = 0; k < NC; k++) o.V_ov0 += overlap_volume(o.c[k]);
  }
  double d_reached = 0, t_stroke = sa_time_now();
  if (!rc) rc = output_row(&o); /* the settled state: displacement 0 */
  if (!rc) rc = write_vtk(&o, 0);
  int rc_stroke = 0;
  if (!rc) {
    rc_stroke = stroke(&o, &d_reached);
    if (rc_stroke < 0) rc = rc_stroke;
  }
  t_stroke = sa_time_now() - t_stroke;
  /* commit what was computed even if a stage failed or the run was interrupted */
  if (o.csv) {
    int r2 = sa_csv_commit(&o.csv);
    if (!rc) rc = r2;
  }
  sa_vtk_series_close(&o.series);
  if (!rc && run->params.plots) make_plots(run);
  if (o.s) {
    FemSolverStats st;
    fem_solver_stats(o.s, &st);
    SaFile *f = NULL;
    if (sa_run_path(run, "summary.ini", path) == 0 && sa_file_open(path, &f) == 0) {
      FILE *fp = sa_file_stream(f);
      double nu = sc->fill.poisson, phi = sc->fill.friction_angle * M_PI / 180;
      fprintf(fp, "; softact granular bending, Mohr-Coulomb continuum fill\n");
      fprintf(fp, "nodes = %d\nelements = %d\nelement = %s\nfree_dofs = %d\nnnz_K = %ld\n",
              st.nnodes, st.nelem, o.m->nen == 10 ? "tet10" : "tet4", st.nfree, st.nnz_k);
      fprintf(fp, "penalty = %.6g ; Pa/m (eps_N)\n",
              sc->mc.penalty * sc->fill.young / sc->mc.fill_h);
      fprintf(fp, "fill_weight = %.6g ; N\n", o.weight_fill);
      fprintf(fp, "lateral_stress_ratio = %.6f ; settled fill, mean sigma_h / mean sigma_v\n"
              "k0_elastic = %.6f ; nu/(1-nu)\nk0_jaky = %.6f ; 1 - sin(phi)\n"
              "initial_stress = %s\nk0_imposed = %.6f ; lateral ratio of the initial stress (0: none)\n",
              o.K_ratio, nu / (1 - nu), 1 - sin(phi), sc->mc.initial_stress,
              strcmp(sc->mc.initial_stress, "k0") ? 0
              : sc->mc.k0_ratio > 0 ? sc->mc.k0_ratio : fem_fill_k0_jaky(sc->fill.friction_angle));
      fprintf(fp, "settled_bending_angle = %.6f ; deg (gravity alone)\n", o.angle0);
      fprintf(fp, "stroke_reached = %.9g ; m\nfinal_bending_angle = %.6f ; deg\n"
              "final_piston_force = %.6g ; N\nfinal_force_balance_error = %.3g\n"
              "final_volume_balance_error = %.3g\nmax_plastic_strain = %.6g\n", d_reached,
              o.angle, o.force, o.balance_f, o.balance_v, o.epsp_max);
      fprintf(fp, "newton_iterations = %d\nnewton_iterations_geostatic = %d\ncuts = %d\n"
              "geostatic_s = %.3f\nstroke_s = %.3f\n", o.newton, newton_geo, o.cuts, t_geo,
              t_stroke);
      fprintf(fp, "augment_max = %d ; Uzawa updates allowed per step (0 = pure penalty)\n"
              "augment_solves = %d\naugment_damped = %d ; updates retried with half or a quarter "
              "of the step\naugment_unconverged_steps = %d\n", sc->mc.augment, o.augments,
              o.augment_damped, o.augment_unconverged);
      fprintf(fp, "krylov_directions = %d ; Newton directions from Krylov on earlier factors\n"
              "krylov_failed = %d\nkrylov_iterations = %d\n", st.n_krylov, st.n_krylov_fail,
              st.n_krylov_it);
      fprintf(fp, "assemblies = %d\nassemble_s = %.3f\nfactorisations = %d\ncholesky = %d\n"
              "lu = %d\nfactorise_s = %.3f\nsolves = %d\nsolve_s = %.3f\npattern_rebuilds = %d\n"
              "wall_s = %.3f\nstatus = %s\n", st.n_assemble, st.t_assemble, st.n_factor,
              st.n_chol, st.n_lu, st.t_factor, st.n_solve, st.t_solve, st.n_pattern_rebuilds,
              sa_time_now() - o.t_start,
              rc == SA_ERR_INTERRUPTED ? "interrupted"
              : rc                     ? "failed"
              : rc_stroke              ? "stroke stopped early"
                                       : "completed");
      if (sa_file_commit(&f)) sa_error_clear();
    } else {
      sa_error_clear();
    }
    sa_log(SA_LOG_INFO, "mc", "stroke %.4g of %.4g mm in %.1f s; %d Newton iterations, %d cuts; "
           "%d assemblies %.1f s, %d factorisations (%d LU) %.1f s", 1e3 * d_reached,
           1e3 * sc->mc.stroke, t_stroke, o.newton, o.cuts, st.n_assemble, st.t_assemble,
           st.n_factor, st.n_lu, st.t_factor);
  }
  if (o.csv) sa_csv_abort(&o.csv);
  fem_snapshot_destroy(&o.snap);
  fem_snapshot_destroy(&o.snap_step);
  fem_solver_destroy(&o.s);
  for (int k = 0; k < NC; k++) fem_contact_destroy(&o.c[k]);
  free(o.cell_types);
  free(o.cell_off);
  free(o.sigma);
  free(o.vm);
  free(o.epsp);
  free(o.yield);
  free(o.reg);
  fem_mesh_destroy(&o.m);
  if (rc) return sa_error_push(rc, __func__, __FILE__, __LINE__);
  /* an early end of the stroke is a numerical failure (exit 2) with the results kept */
  if (rc_stroke) return SA_ERROR(rc_stroke, "stroke ended at %.4g mm of %.4g mm (results up to "
                                 "there are written)", 1e3 * d_reached, 1e3 * sc->mc.stroke);
  return 0;
}

const SaModule fem_mc_bending_module = {
    .name = "mc_bending",
    .trigger = "mc_bending",
    .extends = "mesh",
    .help = "granular bending actuator with a Mohr-Coulomb continuum fill (FEM contact)",
    .tables = mc_tables,
    .ntables = 5,
    .check = mc_check,
    .write_resolved = mc_write_resolved,
    .run = mc_run,
    .destroy = mc_destroy,
};
