#!/bin/sh
# Piston speed against the grain noise (issue 12: "the effect of piston speed on the result"),
# on the beds of bench/dem/interval_long_study.sh (same OUT, waits for each bed): 3 mm beads,
# 3 mm stroke, interval 0.25 mm, piston 0.01 and 0.04 m/s against the scene's 0.02 m/s (the
# interval study's iv2.5e-4 runs), paired by bed. One run at a time, one rank, one thread.
#   bench/dem/speed_long_study.sh OUT [BEAD_DIAMETER_M] [STROKE_M]
# Ends with bench/dem/paired_stats.py (OUT/speed_stats.md).
set -eu
OUT=$1
D=${2:-3e-3}
S=${3:-3e-3}
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
. "$(dirname "$0")/seeded_beds.sh"
for s in $SEEDS; do
  while [ ! -f "$OUT/bed_$s/summary.ini" ]; do sleep 10; done
  for v in 0.04 0.01; do
    resume_variant bed_$s "s${s}_v$v" "$S" dem.seed=$s piston.speed=$v $ONE \
      > "$OUT/s${s}_v$v.log" 2>&1
  done
done
python3 "$(dirname "$0")/paired_stats.py" "$OUT" --at 1,2,3 --variants v0.04,iv2.5e-4,v0.01 \
  --ref v0.01 --seeds "$(echo $SEEDS | tr ' ' ,)" --title "Piston speed" --name speed_stats.md \
  --labels "0.04 m/s,0.02 m/s,0.01 m/s"
