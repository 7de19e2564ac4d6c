#!/bin/sh
# Design and limit variants of the FEM-DEM scene (issue 12, docs/dem.md): rings on/off, a
# frictionless barrel and piston, a frictionless fill, a piston ten times faster. A bed is
# poured, settled and preloaded once per set of grain properties (checkpoint after the 5
# preload steps; a checkpoint refuses other grain properties, so a frictionless barrel or fill
# is poured anew); every variant copies its bed and resumes with its own settings. Rings off = the ring region made of
# silicone (same mesh, so the FEM checkpoint fits; the rings are flush with the outer surface,
# so this is exactly the design without rings). Runs one after the other.
#   bench/dem/design_study.sh OUT [BEAD_DIAMETER_M] [STROKE_M] [STROKE_FRICTIONLESS_BARREL_M]
set -eu
OUT=$1
D=${2:-3e-3}
S=${3:-2e-3}
S2=${4:-4e-3}   # the frictionless barrel goes further
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
mkdir -p "$OUT"
. "$(dirname "$0")/resume_variant.sh"
pour() { # bed key=value ...   (grain properties of the pour)
  b=$1; shift
  pour_bed "$b" 1e-3 "$@"
}
run() { # bed label stroke key=value ...
  resume_variant "$@"
}
NORINGS='material.regions=silicone:silicone,strain_limit:limit,reinforcement:silicone'
NOBARREL='grains.friction_piston=0'
NOFRICTION='grains.friction=0 grains.friction_wall=0 grains.friction_piston=0 grains.rolling_friction=0'
pour base
run base reference "$S"
run base rings_off "$S" "$NORINGS"
run base speed_x10 "$S" piston.speed=0.2
pour base_barrel_frictionless $NOBARREL
run base_barrel_frictionless barrel_frictionless "$S2" $NOBARREL
run base_barrel_frictionless barrel_frictionless_rings_off "$S2" $NOBARREL "$NORINGS"
pour base_fill_frictionless $NOFRICTION
run base_fill_frictionless fill_frictionless "$S" $NOFRICTION
python3 bench/dem/study.py "$OUT" --collect-only --marks 0,0.5,1,1.5,2,3,4 \
  reference: rings_off:rings=off barrel_frictionless:friction_piston=0 \
  barrel_frictionless_rings_off:friction_piston=0,rings=off speed_x10:piston.speed=0.2 \
  fill_frictionless:all_friction=0
