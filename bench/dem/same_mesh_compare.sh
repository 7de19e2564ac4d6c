#!/bin/sh
# The three fills on ONE silicone mesh: the FEM-DEM scene, the Mohr-Coulomb scene and the
# pressure baseline, all on the MC scene's mesh (tet4, h 3 mm, no rings), then the comparison
# scene on the three (docs/compare.md, "The MC scene's silicone"). The MC scene's tet4 silicone
# locks, so its angles can only be compared with runs on the same mesh.
# usage: bench/dem/same_mesh_compare.sh [build dir] [out dir] [stroke m] [MC augment updates]
#   e.g. bench/dem/same_mesh_compare.sh build /tmp/same_mesh 2.5e-3 40
# Environment: MESH (the --set options of the shared silicone mesh; default the MC scene's tet4
# mesh above), PENALTY (MC contact penalty, default 0.3; with augment 0 the run is penalty-only),
# PMAX / PSTEPS (the pressure run; the pressure must reach the cavity growth of the stroke's
# displaced volume). The tet10 actuator without rings (docs/compare.md, "The three fills on one
# tet10 actuator without rings"):
#   MESH="--set mesh.order=2 --set mesh.h=4e-3 --set mesh.rings=0 --set mc_bending.fill_h=4e-3" \
#   PENALTY=0.1 PMAX=10e3 PSTEPS=20 bench/dem/same_mesh_compare.sh build /tmp/norings 2.5e-3 0
# The DEM run takes ~15 min on 2 cores (LIGGGHTS on two ranks), the augmented MC run hours
# (interrupt it with Ctrl-C: the states computed so far are kept and compared).
set -u
build=${1:-build}
out=${2:-/tmp/softact_same_mesh}
stroke=${3:-2.5e-3}
augment=${4:-40}
src=$(cd "$(dirname "$0")/../.." && pwd)
exe="$build/apps/softact"
mesh=${MESH:-"--set mesh.order=1 --set mesh.h=3e-3 --set mesh.rings=0"}
penalty=${PENALTY:-0.3}
mkdir -p "$out"
# shellcheck disable=SC2086
"$exe" run "$src/cases/pressure_bending.ini" --out "$out/pressure" --quiet $mesh \
  --set loading.p_max="${PMAX:-30e3}" --set loading.n_steps="${PSTEPS:-6}"
# shellcheck disable=SC2086
"$exe" run "$src/cases/granular_bending_dem.ini" --out "$out/dem" --quiet \
  $(echo "$mesh" | sed 's/--set mc_bending[^ ]*//g') \
  --set piston.stroke="$stroke"
n_steps=$(python3 -c "print(max(1, round($stroke / 5e-4)))")
# shellcheck disable=SC2086
"$exe" run "$src/cases/granular_bending_mc.ini" --out "$out/mc" --quiet $mesh \
  --set mc_bending.penalty="$penalty" --set mc_bending.augment="$augment" \
  --set mc_bending.stroke="$stroke" --set mc_bending.n_steps="$n_steps"
"$exe" run "$src/cases/compare_bending.ini" --out "$out/compare" --set compare.dem="$out/dem" \
  --set compare.mc="$out/mc" --set compare.pressure="$out/pressure"
echo "# commit $(git -C "$src" rev-parse --short HEAD) $(date -u +%Y-%m-%d); results in $out/compare"
