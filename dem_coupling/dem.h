/* dem.h - the LIGGGHTS bridge of the FEM-DEM coupling (dem_coupling module).
 *
 * LIGGGHTS 3.8 (Debian libliggghts-dev) runs in-process through its C library interface
 * (library.h), serial, or domain-decomposed over the ranks of `mpirun -np N` with rank 0 driving
 * and the others following its calls (dem_parallel.h, dem_bridge_follow below); the few things that interface cannot do (move individual nodes of a wall mesh,
 * read per-triangle forces) go through a small C++ shim (dem_shim.cpp, extern "C", private).
 * LIGGGHTS writes its own output to the log file given at creation, never to the terminal.
 * LIGGGHTS aborts the process on a bad command: every value is validated here before a command
 * is sent, and DEM tests run as separate processes (ctest label `dem`).
 *
 * Units: SI throughout (m, kg, s, N, Pa).
 *
 * Lifecycle (handle first, outputs last; destroy accepts NULL):
 *   dem_bridge_create(log_path, &b)
 *   dem_bridge_setup(b, &params)               box, particle + wall materials, contact model
 *   dem_bridge_add_mesh(b, ...)                 wall meshes (before the first run)
 *   dem_bridge_insert_cylinder(b, ...)          pour grains into a region
 *   [dem_bridge_finalize_walls(b)]              else done by the first dem_bridge_run
 *   loop: dem_bridge_set_mesh_nodes / dem_bridge_run / dem_bridge_mesh_forces / particles
 *         [/ dem_bridge_write_checkpoint after a run]
 *   dem_bridge_destroy(&b)
 * Resume: dem_bridge_setup_from_checkpoint instead of dem_bridge_setup and the insertion, the
 * same meshes added again (see "checkpoint and resume" below), then the loop.
 *
 * Material types: every grain has type 1; a wall mesh names the contact partner type
 * DEM_WALL_SILICONE (friction_wall) or DEM_WALL_STEEL (friction_piston: piston and barrel). */
#ifndef DEM_H
#define DEM_H

typedef struct DemBridge DemBridge;

typedef enum { DEM_WALL_SILICONE = 2, DEM_WALL_STEEL = 3 } DemWallType;

typedef struct {
  /* grains (type 1) */
  double diameter;         /* [m] */
  double density;          /* [kg/m^3] */
  double young;            /* [Pa] already softened: the value LIGGGHTS uses */
  double poisson;          /* [-] */
  double restitution;      /* [-] (0, 1] */
  double friction;         /* grain-grain Coulomb coefficient [-] >= 0 */
  double friction_wall;    /* grain-silicone [-] >= 0 */
  double friction_piston;  /* grain-piston and grain-barrel [-] >= 0 */
  double rolling_friction; /* rolling-resistance coefficient (epsd2 model) [-] >= 0 */
  /* walls: elastic properties of the wall side of a contact */
  double wall_young, wall_poisson; /* [Pa], [-]: the steel walls (DEM_WALL_STEEL), and the
                                    * silicone wall too while silicone_young = 0 */
  double silicone_young, silicone_poisson; /* [Pa], [-]: the silicone wall (DEM_WALL_SILICONE)
                                    * when silicone_young > 0: a compliant wall whose grain
                                    * contacts indent it (dem_bridge_max_indentation) */
  /* simulation */
  double dt;               /* DEM time step [s]; dem_bridge_setup refuses one above
                            * dt_safety * dem_rayleigh_dt(...) */
  double dt_safety;        /* fraction of the Rayleigh time step allowed, e.g. 0.2 */
  double gravity[3];       /* [m/s^2] */
  double box_lo[3], box_hi[3]; /* simulation box [m]; grains leaving it are lost (counted) */
  double skin;             /* neighbour skin [m] (e.g. 0.2 diameter) */
  int seed;                /* random seed for insertion (> 0; the bridge's own generator) */
  int resume_new_dt;       /* dem_bridge_setup_from_checkpoint: 1 = dt and dt_safety may differ
                            * from the checkpoint's (a study variant of the bed, not the same
                            * run); 0 = every parameter must match bit for bit */
} DemParams;

/* Rayleigh time step of a Hertz contact [s]: pi R sqrt(rho / G) / (0.1631 nu + 0.8766). */
double dem_rayleigh_dt(double diameter, double density, double young, double poisson);
/* Hertz contact time of two equal spheres colliding at relative speed v [s] (elastic):
 * t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5), m* = m/2, R* = R/2, E* = E / (2 (1 - nu^2)). */
double dem_hertz_contact_time(double diameter, double density, double young, double poisson,
                              double v);
/* Hertz contact time of a sphere striking a flat wall of elastic properties (wall_young,
 * wall_poisson) at normal speed v [s] (elastic): the same formula with m* = m, R* = R,
 * 1/E* = (1 - nu^2)/E + (1 - nu_w^2)/E_w. */
double dem_hertz_wall_contact_time(double diameter, double density, double young, double poisson,
                                   double wall_young, double wall_poisson, double v);

/* Start a serial LIGGGHTS instance writing its log to log_path [in] (NULL: no log).
 * *out [owned]. */
int dem_bridge_create(const char *log_path, DemBridge **out);
/* Validate params [in] (each value named with its allowed range on failure) and issue the
 * set-up commands: units, box, atom style, materials, granular pair style (Hertz with history,
 * tangential friction, rolling friction epsd2), gravity, integrator, time step. */
int dem_bridge_setup(DemBridge *b, const DemParams *params);

/* A triangulated wall: nverts vertices xyz [in] 3*nverts, ntri triangles tri [in] 3*ntri
 * (vertex indices; no orientation is required: LIGGGHTS walls are two-sided). name [in]:
 * letters, digits, '_' (at most 31). Forces on it are tracked (stress mesh). The mesh may later
 * be moved node by node with dem_bridge_set_mesh_nodes. Returns the mesh id (>= 0) in *id.
 * Refused (SA_ERR_INPUT): a vertex outside the box, a degenerate, needle-like (an angle below
 * 0.1 degree) or duplicate triangle. After dem_bridge_setup, before the walls are finalized.
 * On a bridge resumed from a checkpoint the mesh must be the checkpoint's next one (refused
 * otherwise, naming the difference); adding its last one finalizes the walls. */
int dem_bridge_add_mesh(DemBridge *b, const char *name, int nverts, const double *xyz, int ntri,
                        const int *tri, DemWallType type, int *id);
/* Create the wall contact (one fix wall/gran over every mesh added so far, same contact model
 * as the grains). dem_bridge_run calls it at its first call if the caller has not; no mesh can
 * be added afterwards. */
int dem_bridge_finalize_walls(DemBridge *b);
/* New vertex positions xyz [in] 3*nverts and velocities v [in] 3*nverts (NULL: zero) of mesh
 * id; LIGGGHTS' contact model sees the velocities. No allocation; re-neighbours when a vertex
 * moved more than half the skin since the last neighbour build. A vertex outside the box is
 * refused with SA_ERR_DOMAIN (LIGGGHTS would abort on a lost wall element). */
int dem_bridge_set_mesh_nodes(DemBridge *b, int id, const double *xyz, const double *v);
/* A mesh moved every DEM step, cheaply. dem_bridge_set_mesh_path sends a straight path once:
 * from x0 to x1 [in] 3*nverts, node velocities v [in] 3*nverts (NULL: zero), both ends checked
 * as dem_bridge_set_mesh_nodes checks (the box is convex); dem_bridge_place_on_path then puts
 * every node at x0 + a (x1 - x0), 0 <= a <= 1, sending only a. dem_bridge_place_flat_mesh moves
 * a flat mesh (every vertex at one height, refused otherwise) to height z [m] with velocity
 * (0, 0, vz) and recomputes no normal. Both give LIGGGHTS the bits dem_bridge_set_mesh_nodes
 * gives it for those nodes, but skip the mesh's global bounding box and total area (reductions
 * over the ranks that only insertion faces read). */
int dem_bridge_set_mesh_path(DemBridge *b, int id, const double *x0, const double *x1,
                             const double *v);
int dem_bridge_place_on_path(DemBridge *b, int id, double a);
int dem_bridge_place_flat_mesh(DemBridge *b, int id, double z, double vz);
/* Force the grains exert on each triangle of mesh id, f [out] 3*ntri [N], at the last step. */
int dem_bridge_mesh_forces(DemBridge *b, int id, double *f);
int dem_bridge_mesh_ntri(DemBridge *b, int id);
/* Running sums of the per-triangle forces over many steps without communication: _add adds the
 * force of the last step on every triangle of every mesh to the mesh's sum (each rank its own
 * triangles); _take writes mesh id's sum, added over the ranks, to sum [out] 3*ntri (rank 0;
 * NULL allowed on the others) and restarts it at zero. On one rank the sum is the one a caller
 * would add from dem_bridge_mesh_forces, term by term in the same order. */
int dem_bridge_mesh_forces_add(DemBridge *b);
int dem_bridge_mesh_forces_take(DemBridge *b, int id, double *sum);
/* The node positions LIGGGHTS holds for mesh id, in the caller's vertex order, xyz [out]
 * 3*nverts (a check of dem_bridge_set_mesh_nodes); SA_ERR_INTERNAL if the copies of one vertex
 * in different triangles disagree. */
int dem_bridge_mesh_nodes(DemBridge *b, int id, double *xyz);

/* Pour grains: insert n grains at random non-overlapping positions inside the vertical
 * cylinder (axis x = cx, y = cy, radius r) between z_lo and z_hi [m], with zero velocity. Returns
 * the number actually inserted in *inserted (fewer when the region is too full). */
int dem_bridge_insert_cylinder(DemBridge *b, double cx, double cy, double r, double z_lo,
                               double z_hi, int n, int *inserted);
/* Advance nsteps DEM steps. */
int dem_bridge_run(DemBridge *b, int nsteps);
/* Change the Young's modulus of the grains and of the walls to young [Pa] and the time step to
 * dt [s] (checked against dt_safety x the Rayleigh step of the new modulus, SA_ERR_INPUT),
 * e.g. to pour at a softer stiffness and press at the working one. Takes effect at the next
 * dem_bridge_run; existing tangential contact springs keep their stored displacement. */
int dem_bridge_set_young(DemBridge *b, double young, double dt);
/* Scale every friction coefficient of the set-up parameters (grain-grain, grain-silicone,
 * grain-piston/barrel, rolling) by scale in [0, 1]: 1 restores them. E.g. a frictionless pour
 * packs densely, and the switch back to the working friction leaves the settled bed in
 * equilibrium (a frictionless equilibrium has no tangential forces to cap). Takes effect at
 * the next dem_bridge_run; the contact model stays (rolling resistance keeps its model with a
 * zero coefficient). */
int dem_bridge_scale_friction(DemBridge *b, double scale);
/* Change the neighbour skin to skin [m] (checked as in dem_bridge_setup), e.g. a wide one
 * while grains fall fast and a thin one for the slow stroke. The neighbour lists are rebuilt
 * at the next dem_bridge_run; contact detection is exact for any skin. */
int dem_bridge_set_skin(DemBridge *b, double skin);
/* Number of grains currently in the simulation (lost ones excluded). */
int dem_bridge_count(DemBridge *b);
/* Copy grain data out (any may be NULL): x, v, f [out] 3*n, radius [out] n; n = count. The
 * order is LIGGGHTS' own and may change from one dem_bridge_run to the next. */
int dem_bridge_particles(DemBridge *b, double *x, double *v, double *f, double *radius);
/* The grain-wall contacts LIGGGHTS tracks on mesh id (its fix contacthistory/mesh): grain id,
 * triangle and tangential spring [m] of each, grain [out] max, tri [out] max, shear [out]
 * 3 max; their number in *n (only the first max written). After the first run. For checks. */
int dem_bridge_wall_contacts(DemBridge *b, int id, int max, int *grain, int *tri, double *shear,
                             int *n);
/* LIGGGHTS' id of each grain, id [out] n, in the order of dem_bridge_particles (ids stay with
 * their grains across runs and checkpoints). */
int dem_bridge_particle_ids(DemBridge *b, int *id);
/* Largest overlap over all grain-grain and grain-wall contacts, as a fraction of the grain
 * diameter [-] (grain-grain: from positions; grain-wall: from the meshes). A compliant silicone
 * wall (silicone_young > 0) is left out: its contacts' overlaps are the indentation of the
 * silicone, physical rather than a softening artefact, and measured apart (below). */
double dem_bridge_max_overlap(DemBridge *b);
/* Largest indentation of a grain into a compliant silicone wall found by the last
 * dem_bridge_max_overlap, as a fraction of the grain diameter [-] (0 without such a wall). */
double dem_bridge_max_indentation(const DemBridge *b);
/* Where: pos [out] the centre [m] of the grain of that deepest indentation (NaN when there is
 * none), to tell a dent at the clamped top from one in the free wall (docs/dem.md). */
void dem_bridge_indentation_site(const DemBridge *b, double pos[3]);
/* Where the last dem_bridge_max_overlap found its largest overlap: returns the wall mesh's
 * LIGGGHTS fix id ("mesh_<name>"), or "two grains"; pos [out] the grain's centre [m]. */
const char *dem_bridge_overlap_site(const DemBridge *b, double pos[3]);
/* Total kinetic energy of the grains [J]. */
double dem_bridge_kinetic_energy(DemBridge *b);
/* Write a restart file (LIGGGHTS write_restart: grains, their contact histories, box) to
 * path [in] (no whitespace and none of # $ * % & ' " in it). Reading one back is not part of
 * this interface yet. */
int dem_bridge_write_restart(DemBridge *b, const char *path);
/* ---- checkpoint and resume (issue 12). A checkpoint is one file holding LIGGGHTS' restart
 * (grains, time step counter, grain-grain and grain-wall contact histories, wall nodes) and
 * what that restart lacks (node velocities of the meshes, the forces and torques of the last
 * step, the parameters, the insertion generator), framed with a version, sizes and a hash;
 * format in dem_bridge.c, contents and measurements in docs/dem.md.
 *
 * Write, right after a dem_bridge_run and before the walls are moved for the next step:
 *   dem_bridge_write_checkpoint(b, path)
 * Resume, in a new process or on a new bridge:
 *   dem_bridge_create(log, &b)
 *   dem_bridge_setup_from_checkpoint(b, &params, path, expected_count)   instead of setup
 *   dem_bridge_add_mesh(b, ...)   every mesh again, same order, names, types, triangles, and
 *                                 the node positions of the checkpoint (bitwise); their node
 *                                 velocities come back from the checkpoint
 *   then the loop as before (dem_bridge_set_mesh_nodes / dem_bridge_run / ...).
 * Both bridges, the writer right after writing and the resumed one when its last mesh is added,
 * do a LIGGGHTS set-up pass (run 0: a resumed LIGGGHTS needs one) and then put back the grain
 * forces and torques of the checkpoint's last step. Their continuations are the same bit for
 * bit, and they differ from a run without a checkpoint by round-off (summation order)
 * (tests/dem/test_dem_checkpoint.c). Until the next step, dem_bridge_mesh_forces returns the
 * set-up pass's wall forces. */
typedef struct {
  long long step; /* LIGGGHTS time step counter at the checkpoint */
  int count;      /* grains */
  int nmesh;      /* wall meshes */
  double diameter, dt; /* [m], [s] */
} DemCheckpointInfo;

/* Write a checkpoint of the bridge's state to path [in] (any file name; the file appears
 * complete or not at all: a temporary file beside it, fsync'ed, is renamed), then do the
 * set-up pass described above. Finalizes the walls if the caller had not. SA_ERR_IO if the file
 * cannot be written: checked before LIGGGHTS is asked for anything, so the bridge and an
 * existing file are left as they were. SA_ERR_INPUT when there are no grains. */
int dem_bridge_write_checkpoint(DemBridge *b, const char *path);
/* Read the header of checkpoint path [in] into info [out], after checking the whole file
 * (type, version, byte order, sizes, hash). No bridge needed: for the caller's own checks
 * (e.g. the step of its FEM state). */
int dem_bridge_checkpoint_info(const char *path, DemCheckpointInfo *info);
/* Set up a fresh bridge (instead of dem_bridge_setup) from checkpoint path [in]. params [in]
 * must equal the checkpoint's, every field bitwise (a field that differs is named);
 * expected_count >= 0 must equal its grain count (< 0: not checked). Every check on the file
 * and the arguments happens before LIGGGHTS sees anything: a refusal (SA_ERR_IO for a file
 * that cannot be read, SA_ERR_INPUT for a damaged, truncated or mismatching one, the message
 * naming the file) leaves the bridge fresh, to be set up again. After LIGGGHTS has read the
 * restart, the grains it holds are checked bitwise against the checkpoint (SA_ERR_LIBRARY;
 * then only dem_bridge_destroy is left). */
int dem_bridge_setup_from_checkpoint(DemBridge *b, const DemParams *params, const char *path,
                                     int expected_count);
/* Append LIGGGHTS' log from now on to path [in] (a bridge created with no log, e.g. one
 * resumed to repeat a coupling step, writes on in the run's log). A path LIGGGHTS cannot take
 * (whitespace or # $ * % & ' ") is refused with SA_ERR_INPUT. */
int dem_bridge_log_append(DemBridge *b, const char *path);
/* Send one raw input-script command (validated by the caller; tests and studies only). */
int dem_bridge_command(DemBridge *b, const char *cmd);
/* Several MPI ranks: the processor grid px x py x pz (product = ranks) LIGGGHTS decomposes the
 * box into, before dem_bridge_setup or dem_bridge_setup_from_checkpoint (default: LIGGGHTS'
 * choice, which splits the longest side of the box). Ignored on one rank. */
int dem_bridge_set_processors(DemBridge *b, int px, int py, int pz);
/* A follower rank (not rank 0) of a several-rank job: make every bridge call rank 0 makes,
 * until rank 0 releases the followers (dem_parallel.h). Returns 0, or an SA_ERR code when the
 * calls could not be received. */
int dem_bridge_follow(void);
void dem_bridge_destroy(DemBridge **b);

#endif
