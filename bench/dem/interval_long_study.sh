#!/bin/sh
# Does the bending curve converge as the coupling interval shrinks, over a stroke that loads
# the bed? (issue 12; the 1 mm study of docs/dem.md, "Iterated coupling", was within the grain
# noise.) 3 mm beads (425 grains), 3 mm stroke, the scene's iterated coupling, one MPI rank and
# one thread per run. One bed is poured, settled and preloaded; the intervals 0.5, 0.25 and 0.125 mm resume
# from its checkpoint. A second pour (another seed) at 0.25 mm gives the grain noise the
# differences must be read against. Two runs at a time (two lanes), so the costs are the CPU
# times of summary.ini ([timing] cpu), fair on a shared machine; about 1 h on 2 cores.
#   bench/dem/interval_long_study.sh OUT [BEAD_DIAMETER_M] [STROKE_M]
# Ends with bench/dem/error_vs_time.py (OUT/error_vs_time.{md,png}) and the curves' table.
set -eu
OUT=$1
D=${2:-3e-3}
S=${3:-3e-3}
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
SEED2=32452843
mkdir -p "$OUT"
. "$(dirname "$0")/resume_variant.sh"
ONE="dem.mpi_ranks=1 run.threads=1"
lane_a() {
  pour_bed bed 2.5e-4 $ONE > "$OUT/bed.log" 2>&1
  resume_variant bed interval_0.25mm "$S" $ONE > "$OUT/interval_0.25mm.log" 2>&1
  # the shorter averaging window of the first steps' small load (docs/dem.md)
  resume_variant bed interval_0.125mm "$S" coupling.interval=1.25e-4 dem.balance_tol=0.25 $ONE \
    > "$OUT/interval_0.125mm.log" 2>&1
}
lane_b() {
  pour_bed seed2 2.5e-4 dem.seed=$SEED2 $ONE > "$OUT/seed2.log" 2>&1
  resume_variant seed2 seed2_0.25mm "$S" dem.seed=$SEED2 $ONE > "$OUT/seed2_0.25mm.log" 2>&1
  while [ ! -f "$OUT/bed/summary.ini" ]; do sleep 10; done
  resume_variant bed interval_0.5mm "$S" coupling.interval=5e-4 $ONE > "$OUT/interval_0.5mm.log" 2>&1
}
lane_a &
lane_b &
wait
python3 "$(dirname "$0")/error_vs_time.py" "$OUT" --at 1,2,3 \
  "coupling interval=interval_0.125mm:interval_0.25mm,interval_0.5mm" \
  "second pour (grain noise)=interval_0.25mm:seed2_0.25mm"
