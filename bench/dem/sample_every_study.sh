#!/bin/sh
# Wall updates every DEM step or every k (issue 12: exchange below 5 % of the DEM time). The
# exchange phase moves the FEM wall in LIGGGHTS (node positions, centres, normals of the 3992
# triangles) every `sample_every` DEM steps; every step costs ~10-15 % of the DEM time on the
# default scene. Jumps of 8.6 um every 20 steps pushed a bed along its moving container
# (docs/dem.md, "What made the first runs diverge"); in the coupled scene the wall moves ~1e-4 um
# per DEM step, so jumps every 10 steps are ~1e-3 um against contact overlaps of ~1-40 um.
# One poured 2 mm bed (the scene's settings, pour seed SEED, default 32452843: a second pour
# beside the scene's own), preloaded; then the scene's stroke resumed with sample_every = 1
# (the scene's) and 10, one after the other.
#   [SEED=prime] bench/dem/sample_every_study.sh OUT [STROKE_M]
set -eu
OUT=$1
S=${2:-2.5e-3}
D=2e-3
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
mkdir -p "$OUT"
. "$(dirname "$0")/resume_variant.sh"
pour_bed bed 2.5e-4 dem.seed=${SEED:-32452843}
resume_variant bed se1 "$S" coupling.sample_every=1 dem.seed=${SEED:-32452843}
resume_variant bed se10 "$S" coupling.sample_every=10 dem.seed=${SEED:-32452843}
python3 "$(dirname "$0")/study.py" "$OUT" se1:coupling.sample_every=1 \
  se10:coupling.sample_every=10 --collect-only --marks 0,0.5,1,1.5,2,2.5
