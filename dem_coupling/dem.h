/* dem.h - the LIGGGHTS bridge of the FEM-DEM coupling (dem_coupling module).
 *
 * Foundation stage: only the library handle exists, so that the build, the dependency and the
 * "a scene without particles never starts LIGGGHTS or MPI" rule are in place. The coupling
 * (particle set-up, wall mesh exchange, contact forces every coupling step) is the FEM-DEM issue.
 * LIGGGHTS aborts the process on a bad command: callers validate before sending, and DEM tests
 * run as separate processes (ctest label `dem`). */
#ifndef DEM_H
#define DEM_H

typedef struct DemBridge DemBridge;

/* Start a serial LIGGGHTS instance (no MPI_Init by us: LIGGGHTS' lammps_open_no_mpi).
 * *out [owned]. */
int dem_bridge_create(DemBridge **out);
/* Send one input-script command (validated by the caller). */
int dem_bridge_command(DemBridge *b, const char *cmd);
/* Number of particles currently in the simulation. */
int dem_bridge_count(DemBridge *b);
void dem_bridge_destroy(DemBridge **b);

#endif
