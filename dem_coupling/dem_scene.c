/* dem_scene.c - the granular bending scene (FEM-DEM): case tables, validation, module glue.
 *
 * Selected by a [grains] section; it also reads the actuator's [mesh], [material] and [solver]
 * sections (fem_actuator.h). Everything here is plain C with no LIGGGHTS: the run itself lives
 * in the plugin libsoftact_dem.so (dem_granular.c + the LIGGGHTS bridge), loaded with dlopen
 * only when a granular scene runs, so that every other scene never loads LIGGGHTS or MPI. */
#include "dem_scene.h"

#include <dlfcn.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem_module.h"
#include "sa_error.h"
#include "sa_log.h"

#define P(f) offsetof(DemGrainCase, f)
static const SaParam grain_params[] = {
    {"diameter", SA_PARAM_REAL, P(diameter), "m", "2e-3", 0, 6e-3, SA_MIN_OPEN, NULL,
     "bead diameter (monodisperse)"},
    {"density", SA_PARAM_REAL, P(density), "kg/m^3", "2500", 0, INFINITY, SA_MIN_OPEN, NULL,
     "bead material density"},
    {"young", SA_PARAM_REAL, P(young), "Pa", "63e9", 0, INFINITY, SA_MIN_OPEN, NULL,
     "bead Young's modulus (physical; the DEM uses young / softening)"},
    {"poisson", SA_PARAM_REAL, P(poisson), "-", "0.25", 0, 0.5, SA_MAX_OPEN, NULL,
     "bead Poisson's ratio"},
    {"restitution", SA_PARAM_REAL, P(restitution), "-", "0.5", 0, 1, SA_MIN_OPEN, NULL,
     "coefficient of restitution (all contacts)"},
    {"friction", SA_PARAM_REAL, P(friction), "-", "0.4", 0, 10, 0, NULL,
     "bead-bead Coulomb friction coefficient"},
    {"friction_wall", SA_PARAM_REAL, P(friction_wall), "-", "0.6", 0, 10, 0, NULL,
     "bead-silicone friction coefficient"},
    {"friction_piston", SA_PARAM_REAL, P(friction_piston), "-", "0.3", 0, 10, 0, NULL,
     "bead-piston and bead-barrel friction coefficient"},
    {"rolling_friction", SA_PARAM_REAL, P(rolling_friction), "-", "0.02", 0, 1, 0, NULL,
     "rolling-resistance coefficient (epsd2 model)"},
    {"wall_contact", SA_PARAM_CHOICE, P(wall_contact), "-", "silicone", 0, 0, 0,
     "silicone|grain",
     "elastic side of the silicone wall in a bead's Hertz contact: silicone = the silicone's "
     "small-strain modulus and Poisson ratio from [material] (a bead indents the wall as glass "
     "does rubber; checked by [dem] max_indentation), grain = the beads' own softened modulus "
     "(a near-rigid contact, all of the wall's compliance the FEM's: the coupling's map then "
     "has a large gain and stiff beds break it down; docs/dem.md)"},
    {"softening", SA_PARAM_REAL, P(softening), "-", "1000", 1, 1e6, 0, NULL,
     "the DEM contact stiffness uses young / softening (larger time step); effect in docs/dem.md"},
    {"fill_height", SA_PARAM_REAL, P(fill_height), "m", "0.03", 0, 1, SA_MIN_OPEN, NULL,
     "bed surface above the top of the cavity (z = 0) after settling"},
    {"packing_guess", SA_PARAM_REAL, P(packing_guess), "-", "0.6", 0.3, 0.74, 0, NULL,
     "packing fraction used to size the pour (grains above fill_height are removed)"},
};
#undef P
#define P(f) offsetof(DemPistonCase, f)
static const SaParam piston_params[] = {
    {"stroke", SA_PARAM_REAL, P(stroke), "m", "0.025", 0, 1, SA_MIN_OPEN, NULL,
     "piston travel after it touches the bed"},
    {"speed", SA_PARAM_REAL, P(speed), "m/s", "0.02", 0, 10, SA_MIN_OPEN, NULL,
     "piston speed during the stroke"},
    {"approach_speed", SA_PARAM_REAL, P(approach_speed), "m/s", "0.05", 0, 10, SA_MIN_OPEN, NULL,
     "speed at which the piston is lowered onto the settled bed"},
    {"barrel_length", SA_PARAM_REAL, P(barrel_length), "m", "0.04", 0, 1, SA_MIN_OPEN, NULL,
     "rigid feed barrel above the cavity (z = 0 .. barrel_length)"},
    {"contact_force", SA_PARAM_REAL, P(contact_force), "N", "0.05", 0, INFINITY, SA_MIN_OPEN,
     NULL, "piston force that counts as touching the bed (displacement zero)"},
    {"ramp_steps", SA_PARAM_INT, P(ramp_steps), "-", "0", 0, 10000, 0, NULL,
     "the piston starts from rest and accelerates uniformly to speed over this many coupling "
     "steps (0 = at speed from the first step: a jolt of the bed for a fast piston)"},
};
#undef P
#define P(f) offsetof(DemCouplingCase, f)
static const SaParam coupling_params[] = {
    {"interval", SA_PARAM_REAL, P(interval), "m", "1e-4", 0, 0.01, SA_MIN_OPEN, NULL,
     "piston travel per coupling step (DEM forces -> FEM solve -> wall positions)"},
    {"scheme", SA_PARAM_CHOICE, P(scheme), "-", "dynamic", 0, 0, 0, "dynamic|static|rigid",
     "FEM step per coupling step: implicit dynamic (HHT, silicone inertia and damping), static "
     "equilibrium (docs/dem.md: static diverges on the soft hanging actuator), or rigid (no FEM "
     "solve: the cavity stays in its hanging shape; LIGGGHTS alone, the overhead study)"},
    {"relaxation", SA_PARAM_REAL, P(relaxation), "-", "1", 0, 1, SA_MIN_OPEN, NULL,
     "under-relaxation of the wall forces handed to the FEM (1 = plain staggered)"},
    {"interface_stiffness", SA_PARAM_REAL, P(interface_stiffness), "-", "0", 0, 100, 0, NULL,
     "Robin coupling: the FEM wall carries, per node, this factor times the Hertz contact "
     "stiffness of its wall forces, anchored at the wall position the DEM saw (the bed's "
     "linearised reaction to further wall motion; 0 = plain staggered; docs/dem.md)"},
    {"interface_tangential", SA_PARAM_REAL, P(interface_tangential), "-", "0", 0, 1, 0, NULL,
     "tangential stiffness of the Robin interface as a fraction of its normal one (the bed's "
     "grip on the wall; 0 = normal springs only; docs/dem.md)"},
    {"iterations", SA_PARAM_INT, P(iterations), "-", "1", 1, 50, 0, NULL,
     "most coupling iterations per step: 1 = one DEM pass and one FEM solve per step (the "
     "wall follows the bed with a lag, docs/dem.md); > 1 = the step is rolled back (DEM from "
     "an in-memory checkpoint, FEM from a snapshot) and repeated with quasi-Newton (IQN-ILS) "
     "wall positions until the wall the FEM returns is the wall the DEM saw"},
    {"iteration_tol", SA_PARAM_REAL, P(iteration_tol), "-", "0.03", 0, 1, SA_MIN_OPEN, NULL,
     "an iterated step is converged when the quasi-Newton update of the wall (2-norm over its "
     "nodes) is below this fraction of the wall's displacement by the grains so far (from its "
     "hanging shape before the pour); a step whose fixed-point residual is still above 10 times "
     "it after the last pass stops the run with a diagnosis"},
    {"cut_max", SA_PARAM_INT, P(cut_max), "-", "2", 0, 6, 0, NULL,
     "most halvings of an iterated coupling step that has not converged after its passes: the "
     "step is rolled back and done as two half steps, each of which may be halved again; a "
     "step still not converged at the last halving stops the run if its fixed-point residual "
     "is above the guard (0 = no halving)"},
    {"extrapolation", SA_PARAM_REAL, P(extrapolation), "-", "1", 0, 1, 0, NULL,
     "the first wall of an iterated step is the last step's wall moved on by this fraction of "
     "the last step's motion (scaled to the step's length; 0 = the wall where it is)"},
    {"initial_relaxation", SA_PARAM_REAL, P(initial_relaxation), "-", "1", 0, 1, SA_MIN_OPEN,
     NULL, "relaxation w of an iterated step's pass that has no quasi-Newton model (its first "
     "pass after a checkpoint or a halving, or after the model was dropped): the next wall is "
     "x + w (x~ - x) instead of the FEM's answer x~ (1 = plain substitution; below 1 for a "
     "stiff bed, whose x~ lies far beyond the fixed point: docs/dem.md)"},
    {"max_trial_change", SA_PARAM_REAL, P(max_trial_change), "-", "0", 0, 10, 0, NULL,
     "largest change of any wall node between two walls an iterated step hands to the DEM (its "
     "first trial against the accepted wall, each later one against the last), as a fraction "
     "of the bead diameter: a longer update is shortened along its direction (a trust region "
     "for a stiff bed, whose passes otherwise swing the wall by millimetres into the grains; "
     "0 = no limit; docs/dem.md)"},
    {"qn_reuse", SA_PARAM_INT, P(qn_reuse), "-", "8", 0, 1000, 0, NULL,
     "coupling steps whose quasi-Newton columns are reused (the bed's response changes slowly)"},
    {"damping", SA_PARAM_REAL, P(damping), "1/s", "30", 0, 1e6, 0, NULL,
     "mass-proportional (Rayleigh) damping of the silicone in the dynamic scheme"},
    {"sample_every", SA_PARAM_INT, P(sample_every), "-", "1", 1, 100000, 0, NULL,
     "DEM steps between wall updates and force samples within a coupling step (> 1 moves the "
     "wall in jumps, which pushes the grains along the motion: docs/dem.md)"},
    {"wall_every", SA_PARAM_INT, P(wall_every), "-", "1", 1, 100000, 0, NULL,
     "DEM steps between updates of the deforming wall's geometry in LIGGGHTS while the piston "
     "moves (1 = every step, exact; k > 1 places the wall at the middle of each window of k "
     "steps, its velocity set all along; forces and the piston still every sample_every steps; "
     "with the piston at rest see wall_every_rest: docs/dem.md)"},
    {"wall_every_rest", SA_PARAM_INT, P(wall_every_rest), "-", "1", 1, 100000, 0, NULL,
     "the same while the piston is at rest (the preload under the bed's weight): 1 = every "
     "step; above 1 only with [grains] wall_contact = silicone, whose resting overlaps (~10 um, "
     "the deepest 85 um on the scene's bed) dwarf a window's wall jump (the near-rigid "
     "contact's ~0.2 um do not: docs/dem.md)"},
    {"gravity", SA_PARAM_BOOL, P(gravity), "-", "1", 0, 0, 0, NULL,
     "gravity (-z, 9.81 m/s^2) on grains and silicone"},
    {"checkpoint_every", SA_PARAM_INT, P(checkpoint_every), "-", "20", 0, 100000, 0, NULL,
     "coupling steps between checkpoints in <out>/checkpoint (0 = only when interrupted); a "
     "run stopped by a signal between coupling steps writes one; inside a step it stops after "
     "the current DEM chunk or Newton iteration and keeps the last one"},
    {"checkpoint_poured", SA_PARAM_BOOL, P(checkpoint_poured), "-", "0", 0, 0, 0, NULL,
     "also write a checkpoint of the poured and settled bed, piston on it, before the preload "
     "(studies resume variants of the preload from one bed)"},
    {"resume", SA_PARAM_BOOL, P(resume), "-", "0", 0, 0, 0, NULL,
     "continue from <out>/checkpoint of an earlier run of the same case into the same --out "
     "folder, instead of pouring (same result as a run that was never stopped)"},
    {"resume_new_dt", SA_PARAM_BOOL, P(resume_new_dt), "-", "0", 0, 0, 0, NULL,
     "with resume: the checkpointed bed goes on with this case's DEM time step ([dem] "
     "dt_fraction) instead of refusing one that differs: a study variant of the bed (the DEM "
     "step study), not its continuation"},
    {"vtk_every", SA_PARAM_INT, P(vtk_every), "-", "25", 0, 100000, 0, NULL,
     "write VTK (silicone + grains) every this many coupling steps (0 = first and last only)"},
    {"wall_surface", SA_PARAM_STRING, P(wall_surface), "-", "cavity_wall", 0, 0, 0, NULL,
     "mesh surface in contact with the grains (cavity wall and floor)"},
    {"fixed_surface", SA_PARAM_STRING, P(fixed_surface), "-", "fixed_end", 0, 0, 0, NULL,
     "mesh surface clamped in x, y and z"},
    {"tip_surface", SA_PARAM_STRING, P(tip_surface), "-", "tip", 0, 0, 0, NULL,
     "surface whose mean normal defines the bending angle"},
};
#undef P
#define P(f) offsetof(DemNumericsCase, f)
static const SaParam dem_params[] = {
    {"dt_fraction", SA_PARAM_REAL, P(dt_fraction), "-", "0.2", 0, 0.35, SA_MIN_OPEN, NULL,
     "DEM time step as a fraction of the Rayleigh time step of the softened grains "
     "(above 0.35 is refused as unsafe)"},
    {"pour_softening", SA_PARAM_REAL, P(pour_softening), "-", "1", 1, 1e6, 0, NULL,
     "softening while pouring and settling (never stiffer than [grains] softening: 1 = pour at "
     "the working stiffness). Off by default: a softer pour locks its overlaps into the "
     "confined bed, and the stiffer contacts then press the wall ~10x harder (docs/dem.md)"},
    {"pour_speed", SA_PARAM_REAL, P(pour_speed), "m/s", "1", 0, 5, 0, NULL,
     "downward speed the grains are inserted with (a hopper's outflow): the column reaches the "
     "bed sooner than from rest; the impact speed is sqrt(pour_speed^2 + 2 g h) either way"},
    {"pour_friction", SA_PARAM_REAL, P(pour_friction), "-", "1", 0, 1, 0, NULL,
     "every friction coefficient (grain, wall, piston, rolling) times this while the grains "
     "fall and land, then the working values for settling and the stroke (0 = a frictionless "
     "pour: a denser bed, as tapping would make it; 1 = the working friction throughout)"},
    {"skin", SA_PARAM_REAL, P(skin), "-", "0.05", 0.01, 2, 0, NULL,
     "neighbour skin during the stroke as a fraction of the bead diameter (lists are rebuilt "
     "when a grain or wall node has moved half of it; 0.05 made a coupled DEM step 30 % "
     "cheaper than 0.2, docs/dem.md)"},
    {"pour_skin", SA_PARAM_REAL, P(pour_skin), "-", "0.2", 0.01, 2, 0, NULL,
     "neighbour skin while the grains are poured and settle, as a fraction of the bead "
     "diameter (falling grains cross a thin skin in a few steps and rebuild the lists)"},
    {"settle_speed", SA_PARAM_REAL, P(settle_speed), "m/s", "2e-3", 0, INFINITY, SA_MIN_OPEN,
     NULL, "the bed counts as settled when the rms grain speed falls below this"},
    {"settle_time_max", SA_PARAM_REAL, P(settle_time_max), "s", "1.5", 0, INFINITY, SA_MIN_OPEN,
     NULL, "give up settling after this much simulated time"},
    {"max_overlap", SA_PARAM_REAL, P(max_overlap), "-", "0.05", 0, 0.5, SA_MIN_OPEN, NULL,
     "stop when a contact overlap exceeds this fraction of the diameter (soften less); with "
     "[grains] wall_contact = silicone the silicone wall's contacts are checked by "
     "max_indentation instead"},
    {"max_indentation", SA_PARAM_REAL, P(max_indentation), "-", "0.4", 0, 0.5, SA_MIN_OPEN,
     NULL, "with [grains] wall_contact = silicone: stop when a bead indents the silicone wall "
     "by more than this fraction of its diameter (at 0.5 its centre reaches the wall's facet "
     "and it can tunnel; Hertz's law itself assumes indentations small against the radius: "
     "bending.csv reports the largest, docs/dem.md)"},
    {"rigid_band", SA_PARAM_REAL, P(rigid_band), "m", "0", 0, 0.05, 0, NULL,
     "take the cavity wall's top down to this depth below z = 0 as part of the rigid bore: "
     "the barrel's rigid mesh (and its friction_piston) extends over it and the FEM's wall "
     "there gets no grain load (0 = off; the collar clamps the top 5 mm: a stiff bed's beads "
     "indent the clamped silicone past what the Hertz contact on silicone represents, "
     "docs/dem.md)"},
    {"balance_tol", SA_PARAM_REAL, P(balance_tol), "-", "0.1", 0, 10, SA_MIN_OPEN, NULL,
     "stop when the grains' force balance misses by more than this fraction of the load"},
    {"seed", SA_PARAM_INT, P(seed), "-", "15485863", 10001, 2147483647, 0, NULL,
     "random seed of the pour (LIGGGHTS wants a prime > 10000)"},
    {"check_every", SA_PARAM_INT, P(check_every), "-", "10", 1, 100000, 0, NULL,
     "coupling steps between the tunnelling checks (grains inside the bore)"},
    {"mpi_ranks", SA_PARAM_INT, P(mpi_ranks), "-", "1", 1, 64, 0, NULL,
     "MPI ranks LIGGGHTS is decomposed over (the bore cut along y = 0 into slabs; the FEM, "
     "coupling and output stay on rank 0): > 1 starts softact again under `mpirun -np N "
     "--bind-to none` (Open MPI's root check waived for root), unless it already runs under "
     "mpirun, whose -np then counts (docs/dem.md, \"MPI scale-out\")"},
};
#undef P

static const SaParamTable grain_table = {"grains", "dem",
                                         "granular fill of the FEM-DEM scene (selects it)",
                                         grain_params, SA_NPARAMS(grain_params)};
static const SaParamTable piston_table = {"piston", "dem", "piston and feed barrel",
                                          piston_params, SA_NPARAMS(piston_params)};
static const SaParamTable coupling_table = {"coupling", "dem", "FEM-DEM exchange and outputs",
                                            coupling_params, SA_NPARAMS(coupling_params)};
static const SaParamTable numerics_table = {"dem", "dem", "DEM numerics and run checks",
                                            dem_params, SA_NPARAMS(dem_params)};
static const SaParamTable *const dem_tables[] = {
    &grain_table,  &piston_table, &coupling_table, &numerics_table, &fem_actuator_mesh_table,
    &fem_actuator_material_table, &fem_actuator_solver_table};

double dem_scene_rayleigh_dt(double diameter, double density, double young, double poisson) {
  double G = young / (2 * (1 + poisson));
  return M_PI * 0.5 * diameter * sqrt(density / G) / (0.1631 * poisson + 0.8766);
}

static int dem_check(const SaCase *c, void **out) {
  *out = NULL;
  DemScene *s;
  SA_CALLOC(s, 1);
  const char *f = sa_case_path(c);
  snprintf(s->case_path, sizeof s->case_path, "%s", f);
  int rc = fem_actuator_load(c, &s->act);
  if (!rc) rc = sa_params_load(&grain_table, c, &s->grains);
  if (!rc) rc = sa_params_load(&piston_table, c, &s->piston);
  if (!rc) rc = sa_params_load(&coupling_table, c, &s->coupling);
  if (!rc) rc = sa_params_load(&numerics_table, c, &s->dem);
  /* the bore is the cavity radius of meshes/actuator.geo (6 mm, /work/shared/ACTUATOR.md) */
  const double r_bore = 6e-3;
  const DemGrainCase *g = &s->grains;
  const DemPistonCase *p = &s->piston;
  if (!rc && g->diameter >= r_bore)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [grains] diameter = %g m: beads must be smaller than the "
                  "bore radius %g m (at least two across the bore)", f, g->diameter, r_bore);
  if (!rc && g->fill_height >= p->barrel_length - g->diameter)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [grains] fill_height = %g m must leave room for the piston "
                  "inside the barrel (barrel_length %g m minus one diameter)", f, g->fill_height,
                  p->barrel_length);
  if (!rc && p->stroke >= g->fill_height)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [piston] stroke = %g m is longer than the barrel below the "
                  "bed surface (fill_height = %g m): the piston would enter the deformable cavity "
                  "(allowed: stroke < fill_height)", f, p->stroke, g->fill_height);
  if (!rc && s->coupling.interval > p->stroke)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [coupling] interval = %g m is longer than the stroke %g m",
                  f, s->coupling.interval, p->stroke);
  if (!rc && s->coupling.wall_every_rest > 1 && strcmp(g->wall_contact, "silicone"))
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [coupling] wall_every_rest = %d needs [grains] wall_contact "
                  "= silicone: with the near-rigid contact a resting grain's wall overlap "
                  "(~0.2 um) is as large as the wall's jump between placements (allowed: 1)", f,
                  s->coupling.wall_every_rest);
  /* products of keys that size the run: the coupling steps (a loop, and a CSV row each kept in
   * memory for the checkpoint) and the grains poured (an int, and LIGGGHTS' memory) */
  double nsteps = !rc ? p->stroke / s->coupling.interval : 0;
  if (!rc && nsteps > DEM_MAX_COUPLING_STEPS)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [piston] stroke / [coupling] interval = %g / %g = %.4g coupling "
                  "steps; at most %.0e are allowed", f, p->stroke, s->coupling.interval, nsteps,
                  DEM_MAX_COUPLING_STEPS);
  double ngr = !rc ? dem_scene_pour_count(g) : 0;
  if (!rc && ngr > DEM_MAX_GRAINS)
    rc = SA_ERROR(SA_ERR_INPUT, "%s: [grains] diameter = %g m with fill_height = %g m and "
                  "packing_guess = %g pours %.4g grains; at most %.0e are allowed (raise the "
                  "diameter)", f, g->diameter, g->fill_height, g->packing_guess, ngr,
                  DEM_MAX_GRAINS);
  if (rc) {
    free(s);
    return sa_error_push(rc, __func__, __FILE__, __LINE__);
  }
  *out = s;
  return 0;
}

double dem_scene_pour_count(const DemGrainCase *g) {
  /* the pour column: the bore (cavity radius 6 mm, 80 mm deep below the barrel top) up to
   * fill_height, at packing_guess, 4 % extra */
  const double r_bore = 6e-3, depth = 80e-3;
  double V_bore = M_PI * r_bore * r_bore * (depth + g->fill_height);
  return ceil(1.04 * g->packing_guess * V_bore / (M_PI * pow(g->diameter, 3) / 6));
}

static void dem_write_resolved(const void *scene, FILE *f) {
  const DemScene *s = scene;
  const void *parts[] = {&s->grains, &s->piston, &s->coupling, &s->dem};
  for (int i = 0; i < 4; i++) {
    sa_params_write(dem_tables[i], parts[i], f);
    fprintf(f, "\n");
  }
  fem_actuator_write_resolved(&s->act, f);
}

static void dem_destroy(void **scene) {
  if (!scene) return;
  free(*scene);
  *scene = NULL;
}

/* The plugin's function `symbol` (the plugin loaded on first use). Its path is fixed at build
 * time (SOFTACT_DEM_PLUGIN); the environment variable SOFTACT_DEM_PLUGIN overrides it.
 * RTLD_GLOBAL: OpenMPI loads its own components with dlopen and needs libmpi's symbols global.
 * The plugin stays loaded: LIGGGHTS/OpenMPI do not support being unloaded. */
static int plugin_symbol(const char *symbol, void **fn) {
  const char *path = getenv("SOFTACT_DEM_PLUGIN");
#ifdef SOFTACT_DEM_PLUGIN
  if (!path || !path[0]) path = SOFTACT_DEM_PLUGIN;
#endif
  SA_REQUIRE(path && path[0], SA_ERR_LIBRARY, "this softact was built without the DEM plugin");
  void *h = dlopen(path, RTLD_NOW | RTLD_GLOBAL);
  SA_REQUIRE(h, SA_ERR_LIBRARY, "cannot load the FEM-DEM plugin %s: %s", path, dlerror());
  *fn = dlsym(h, symbol);
  SA_REQUIRE(*fn, SA_ERR_LIBRARY, "%s has no %s", path, symbol);
  sa_log(SA_LOG_DEBUG, "dem", "loaded %s", path);
  return 0;
}

/* Load the plugin and run. */
static int dem_run(void *scene, SaRun *run) {
  DemGranularRunFn fn;
  SA_CHECK(plugin_symbol(DEM_GRANULAR_RUN_SYMBOL, (void **)&fn));
  return fn(scene, run);
}

/* The MPI ranks the case asks for (apps/softact.c starts them). */
static int dem_ranks(const void *scene) { return ((const DemScene *)scene)->dem.mpi_ranks; }

/* A follower rank of an MPI job: the plugin's follower loop (dem_parallel.h). */
static int dem_follow(void *scene) {
  int (*fn)(const DemScene *);
  SA_CHECK(plugin_symbol(DEM_GRANULAR_FOLLOW_SYMBOL, (void **)&fn));
  return fn(scene);
}

/* A resumed run continues its own results folder (checkpoint/, the VTK files of the first part). */
static int dem_resumes(const void *scene) { return ((const DemScene *)scene)->coupling.resume; }

const SaModule dem_module = {
    .name = "dem",
    .trigger = "grains",
    .extends = "mesh",
    .help = "FEM-DEM granular bending: LIGGGHTS beads pushed by a piston into the FEM actuator",
    .tables = dem_tables,
    .ntables = SA_NPARAMS(dem_tables),
    .check = dem_check,
    .write_resolved = dem_write_resolved,
    .run = dem_run,
    .destroy = dem_destroy,
    .resumes = dem_resumes,
    .follow = dem_follow,
    .ranks = dem_ranks,
};
