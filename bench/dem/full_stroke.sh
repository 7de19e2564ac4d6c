#!/bin/sh
# The default FEM-DEM scene over the full 25 mm stroke of ACTUATOR.md (issue 12), with stiffer
# grains than the scene's softening 100 (which the overlap check stops near 4.5 mm, docs/dem.md
# "the long stroke"). Everything else is the scene's: 2 mm beads, 0.02 m/s, 0.25 mm coupling
# interval, iterated coupling, two MPI ranks. Hours of run time: the run writes a checkpoint
# every CKPT coupling steps and this script, run again with the same OUT, resumes an
# interrupted run (same result as a run that was never stopped). Results: OUT/bending.csv, summary.ini, plots.
#   bench/dem/full_stroke.sh OUT [SOFTENING=30] [STROKE_M=0.025] [CKPT=4] [KEY=VALUE...]
# (each KEY=VALUE after the fourth argument is passed on as --set KEY=VALUE, e.g.
# grains.wall_contact=grain for the old near-rigid bead-silicone contact; stop 42's stiff bed:
# dem.rigid_band=5e-3 coupling.max_trial_change=0.1, the trust region on the trial walls that
# took it past 8 mm, docs/dem.md)
# EXE and SOFTACT_DEM_PLUGIN may point at copies of the binaries (a rebuild of build/ must not
# swap the DEM plugin under a running study).
set -eu
OUT=$1
SOFT=${2:-30}
S=${3:-0.025}
CKPT=${4:-4}
if [ $# -gt 4 ]; then shift 4; else shift $#; fi
SETS=""
for kv in "$@"; do SETS="$SETS --set $kv"; done
EXE=${EXE:-build/apps/softact}
RESUME=""
if [ -f "$OUT/checkpoint/state.ckpt" ]; then
  if grep -q '^status = completed' "$OUT/summary.ini" 2>/dev/null; then
    echo "$OUT: completed (summary.ini)"
    exit 0
  fi
  RESUME="--set coupling.resume=true"
fi
# shellcheck disable=SC2086
"$EXE" run cases/granular_bending_dem.ini --out "$OUT" --set grains.softening="$SOFT" \
  --set piston.stroke="$S" --set coupling.checkpoint_every="$CKPT" --set coupling.vtk_every=4 \
  $SETS $RESUME
