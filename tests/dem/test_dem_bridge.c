/* The LIGGGHTS bridge starts, takes a granular set-up, creates particles and counts them.
 * Reference: the lattice of create_atoms is exact: a box of 4x4x4 unit cells of an sc lattice
 * with spacing 2 mm gives 64 particles (counted by construction, independent of LIGGGHTS). */
#include <stdio.h>

#include "dem.h"
#include "sa_error.h"

int main(void) {
  DemBridge *b = NULL;
  if (dem_bridge_create(NULL, &b)) {
    sa_error_print();
    return 1;
  }
  const char *cmds[] = {
      "atom_style granular", "atom_modify map array", "boundary f f f", "newton off",
      "communicate single vel yes", "units si",
      "region box block 0 0.008 0 0.008 0 0.008 units box", "create_box 1 box",
      "lattice sc 0.002", "create_atoms 1 box"};
  for (size_t i = 0; i < sizeof cmds / sizeof *cmds; i++) dem_bridge_command(b, cmds[i]);
  int n = dem_bridge_count(b);
  dem_bridge_destroy(&b);
  if (n != 64) {
    printf("expected 64 particles, LIGGGHTS has %d\n", n);
    return 1;
  }
  return 0;
}
