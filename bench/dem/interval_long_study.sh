#!/bin/sh
# Does the bending curve converge as the coupling interval shrinks, over a stroke that loads
# the bed? (issue 12; the 1 mm study of docs/dem.md, "Iterated coupling", was within the grain
# noise.) 3 mm beads (~430 grains), 3 mm stroke, the scene's iterated coupling, one MPI rank and
# one thread per run. For each pour seed a bed is poured, settled and preloaded once, and the
# intervals 0.5, 0.25 and 0.125 mm resume from its checkpoint: the differences between
# intervals are then paired (same bed), and the spread over the seeds is the grain noise they
# must be read against. Two runs at a time (a lane per half of the seeds), so the costs are the
# CPU times of summary.ini ([timing] cpu), fair on a shared machine; ~4 min per run here.
#   bench/dem/interval_long_study.sh OUT [BEAD_DIAMETER_M] [STROKE_M]
# SEEDS (primes > 10000, LIGGGHTS' rule) overrides the six seeds. Existing results are kept
# (a rerun completes a study). Ends with bench/dem/paired_stats.py (OUT/interval_stats.md, .png).
set -eu
OUT=$1
D=${2:-3e-3}
S=${3:-3e-3}
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
. "$(dirname "$0")/seeded_beds.sh"
one_seed() {
  s=$1
  pour_bed bed_$s 2.5e-4 dem.seed=$s $ONE > "$OUT/bed_$s.log" 2>&1
  for iv in 5e-4 2.5e-4 1.25e-4; do
    # the shorter averaging window of the first steps' small load (docs/dem.md)
    extra=""
    [ "$iv" = 1.25e-4 ] && extra=dem.balance_tol=0.25
    resume_variant bed_$s "s${s}_iv$iv" "$S" dem.seed=$s coupling.interval=$iv $extra $ONE \
      > "$OUT/s${s}_iv$iv.log" 2>&1
  done
}
lane() { # every second seed from the first-th
  k=0
  for s in $SEEDS; do
    [ $((k % 2)) -eq "$1" ] && one_seed "$s"
    k=$((k + 1))
  done
}
lane 0 &
lane 1 &
wait
python3 "$(dirname "$0")/paired_stats.py" "$OUT" --at 1,2,3 --variants iv5e-4,iv2.5e-4,iv1.25e-4 \
  --ref iv1.25e-4 --seeds "$(echo $SEEDS | tr ' ' ,)" --title "Coupling interval" \
  --name interval_stats.md --labels "0.5 mm,0.25 mm,0.125 mm"
