#!/bin/sh
# The DEM time step's share of the bending angle (issue 12, "error against run time"), paired on
# one bed: a bed is poured, settled and preloaded once (3 mm beads by default), and its
# checkpoint is resumed over the stroke with [dem] dt_fraction 0.2 (the scene's), 0.1 and 0.05
# of the Rayleigh step (`[coupling] resume_new_dt`: the same bed with another time step).
# A resumed pair at the scene's step that differs only in the FEM's round-off (one FEM thread
# against two: docs/dem.md, "Resume bit for bit needs one FEM thread") measures how far the
# bed's chaos alone moves the answer; a time-step effect must stand above it.
# One MPI rank and one lane (the runs one after the other), so CPU times compare.
#   bench/dem/dem_step_study.sh OUT [BEAD_DIAMETER_M] [STROKE_M] [SEED]
# then: python3 bench/dem/study.py-style tables from OUT/*/bending.csv (docs/dem.md lists them).
set -eu
OUT=$1
D=${2:-3e-3}
S=${3:-3e-3}
SEED=${4:-}
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
mkdir -p "$OUT"
. "$(dirname "$0")/resume_variant.sh"
common="dem.mpi_ranks=1 run.threads=1 run.plots=0"
[ -n "$SEED" ] && common="$common dem.seed=$SEED"
# shellcheck disable=SC2086
pour_bed bed 2.5e-4 $common > "$OUT/bed.log" 2>&1
for v in "dt_0.2 dem.dt_fraction=0.2" "dt_0.2_threads2 dem.dt_fraction=0.2 run.threads=2" \
         "dt_0.1 dem.dt_fraction=0.1" "dt_0.05 dem.dt_fraction=0.05"; do
  # shellcheck disable=SC2086
  set -- $v
  label=$1
  shift
  # shellcheck disable=SC2086
  resume_variant bed "$label" "$S" $common "$@" coupling.resume_new_dt=true > "$OUT/$label.log" 2>&1
  echo "$label: $(grep -E '^(status|cpu|wall)' "$OUT/$label/summary.ini" 2>/dev/null | tr '\n' ' ')"
done
echo "# commit $(git rev-parse --short HEAD) $(date -u +%Y-%m-%d)"
