#!/bin/sh
# Grain softening against the grain noise (issue 12: "the effect of grain softening on the
# result", and its error against run time): 3 mm beads, 3 mm stroke, the scene's interval and
# speed, softening 100 (the scene's, the reference of the paired columns: the finest that a
# study of this size affords), 30 and 300. The softening sets the pour's contact stiffness too,
# so every softening pours its own beds with the same seeds; the differences are therefore
# between beds, not paired ones (the standard errors of paired_stats.py then hold the noise of
# both sets). Two lanes, one rank and one thread per run; the CPU times include the pour.
#   bench/dem/softening_long_study.sh OUT [BEAD_DIAMETER_M] [STROKE_M] [SOFTENINGS] [REFERENCE]
# Ends with bench/dem/paired_stats.py (OUT/softening_stats.md, .png).
# Stop 35: at softening 30 both first beds broke down with the old near-rigid bead-silicone
# contact (docs/dem.md "The full stroke with stiffer grains"); stop 38 reruns the study with
# the silicone's contact (the scene's wall_contact = silicone since stop 37).
set -eu
OUT=$1
D=${2:-3e-3}
S=${3:-3e-3}
SOFTS=${4:-"100 30 300"}
REF=${5:-100}
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
. "$(dirname "$0")/seeded_beds.sh"
lane() { # every second seed from the first-th, each softening in turn
  for sf in $SOFTS; do
    k=0
    for s in $SEEDS; do
      if [ $((k % 2)) -eq "$1" ] && [ ! -f "$OUT/s${s}_sf$sf/summary.ini" ]; then
        rm -rf "${OUT:?}/s${s}_sf$sf"
        # shellcheck disable=SC2086
        pour_bed "s${s}_sf$sf" "$S" dem.seed=$s grains.softening=$sf $ONE \
          > "$OUT/s${s}_sf$sf.log" 2>&1
      fi
      k=$((k + 1))
    done
  done
}
lane 0 &
lane 1 &
wait
vars=$(for sf in $SOFTS; do printf 'sf%s,' "$sf"; done)
labels=$(for sf in $SOFTS; do printf 'softening %s,' "$sf"; done)
python3 "$(dirname "$0")/paired_stats.py" "$OUT" --at 1,2,3 --variants "${vars%,}" \
  --ref "sf$REF" --seeds "$(echo $SEEDS | tr ' ' ,)" --title "Grain softening" \
  --name softening_stats.md --labels "${labels%,}"
