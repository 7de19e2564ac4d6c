/* dem_scene.h - the granular bending scene (FEM-DEM coupling), private to dem_coupling/.
 *
 * Two halves so that a scene without particles never loads LIGGGHTS or MPI:
 *   dem_scene.c     case tables, validation and the module glue; linked into softact; knows no
 *                   LIGGGHTS (no MPI either).
 *   dem_granular.c  the coupled run; built with the LIGGGHTS bridge into the plugin
 *                   libsoftact_dem.so, which dem_scene.c dlopen()s only when such a scene runs.
 * Geometry, materials and grains: /work/shared/ACTUATOR.md; the coupling scheme: docs/dem.md. */
#ifndef DEM_SCENE_H
#define DEM_SCENE_H

#include "fem_actuator.h"
#include "sa_params.h"
#include "sa_run.h"

typedef struct {
  double diameter, density, young, poisson, restitution, friction, friction_wall,
      friction_piston, rolling_friction, softening, fill_height, packing_guess;
  char wall_contact[SA_STR_MAX]; /* grain | silicone: the silicone wall's side of a contact */
} DemGrainCase;

typedef struct {
  double stroke, speed, approach_speed, barrel_length, contact_force;
  int ramp_steps; /* coupling steps of uniform acceleration from rest to speed */
} DemPistonCase;

typedef struct {
  double interval, relaxation, damping, interface_stiffness, interface_tangential;
  double iteration_tol, initial_relaxation, extrapolation;
  double max_trial_change; /* fraction of the bead diameter; 0 = no limit */
  int sample_every, wall_every, wall_every_rest, gravity, vtk_every, checkpoint_every, resume, resume_new_dt, iterations,
      qn_reuse;
  int cut_max; /* halvings of an iterated step that does not converge */
  int checkpoint_poured;
  char scheme[SA_STR_MAX];
  char wall_surface[SA_STR_MAX], fixed_surface[SA_STR_MAX], tip_surface[SA_STR_MAX];
} DemCouplingCase;

typedef struct {
  double dt_fraction, skin, settle_speed, max_overlap, max_indentation, rigid_band, balance_tol,
      settle_time_max;
  double pour_softening, pour_speed, pour_friction, pour_skin;
  int seed, check_every, mpi_ranks;
} DemNumericsCase;

typedef struct {
  FemActuatorCase act;
  DemGrainCase grains;
  DemPistonCase piston;
  DemCouplingCase coupling;
  DemNumericsCase dem;
  char case_path[SA_STR_MAX];
} DemScene;

/* The plugin's entry point (dem_granular.c), looked up by name with dlsym. */
typedef int (*DemGranularRunFn)(const DemScene *sc, const SaRun *run);
#define DEM_GRANULAR_RUN_SYMBOL "dem_granular_run"
int dem_granular_run(const DemScene *sc, const SaRun *run);
/* A follower rank of `mpirun -np N softact run` (rank > 0): LIGGGHTS' share of the lead's run,
 * nothing else (dem_parallel.h). */
#define DEM_GRANULAR_FOLLOW_SYMBOL "dem_granular_follow"
int dem_granular_follow(const DemScene *sc);

/* Rayleigh time step of a Hertz contact [s] (Li, Xu & Thornton 2005):
 * pi R sqrt(rho / G) / (0.1631 nu + 0.8766), G = E / (2 (1 + nu)). */
/* Grains the pour inserts (bore volume up to fill_height at packing_guess), as a double so
 * that dem_check can compare it with DEM_MAX_GRAINS before it becomes an int. */
double dem_scene_pour_count(const DemGrainCase *g);
#define DEM_MAX_GRAINS 1e6
#define DEM_MAX_COUPLING_STEPS 1e6

double dem_scene_rayleigh_dt(double diameter, double density, double young, double poisson);

#endif
