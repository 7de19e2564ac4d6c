/* dem_bridge.c - thin handle around the LIGGGHTS C library interface (library.h). */
#include "dem.h"

#include <library.h>
#include <stdlib.h>

#include "sa_error.h"

struct DemBridge {
  void *lmp;
};

int dem_bridge_create(DemBridge **out) {
  *out = NULL;
  DemBridge *b;
  SA_CALLOC(b, 1);
  /* -log none: LIGGGHTS writes log.liggghts by default; -screen none keeps stdout clean. */
  char *argv[] = {"softact", "-log", "none", "-screen", "none", NULL};
  lammps_open_no_mpi(5, argv, &b->lmp);
  if (!b->lmp) {
    free(b);
    return SA_ERROR(SA_ERR_LIBRARY, "LIGGGHTS failed to start");
  }
  *out = b;
  return 0;
}

int dem_bridge_command(DemBridge *b, const char *cmd) {
  SA_REQUIRE(b && b->lmp, SA_ERR_INTERNAL, "DEM bridge not started");
  lammps_command(b->lmp, (char *)cmd);
  return 0;
}

int dem_bridge_count(DemBridge *b) { return b && b->lmp ? lammps_get_natoms(b->lmp) : 0; }

void dem_bridge_destroy(DemBridge **b) {
  if (!*b) return;
  if ((*b)->lmp) lammps_close((*b)->lmp);
  free(*b);
  *b = NULL;
}
