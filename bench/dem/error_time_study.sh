#!/bin/sh
# Error against run time of the FEM-DEM scene (issue 12): the bending angle over a short stroke
# for each numerical parameter the issue names (coupling interval, DEM time step, grain
# softening, piston speed, FEM mesh), each against its finest variant, versus the variant's CPU
# time; plus a second pour (another seed) for the grain noise the errors must be read against.
# 3 mm beads (425 grains): ~7 min of CPU per bed, 2-6 min per variant, ~1.5 h in all; the scene's iterated
# coupling. One bed per set of grain properties or mesh (a checkpoint refuses others) is poured,
# settled and preloaded; every variant copies its bed and resumes over the stroke.
#   bench/dem/error_time_study.sh OUT [BEAD_DIAMETER_M] [STROKE_M]
# Ends with bench/dem/error_vs_time.py on the groups below (OUT/error_vs_time.{md,png}); the
# overhead of the coupling is base against rigid ([timing] cpu in their summary.ini).
set -eu
OUT=$1
D=${2:-3e-3}
S=${3:-1e-3}
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
mkdir -p "$OUT"
. "$(dirname "$0")/resume_variant.sh"
pour() { # bed key=value ...   (grain properties or mesh of the pour)
  b=$1; shift
  pour_bed "$b" 2.5e-4 "$@" > "$OUT/$b.log" 2>&1
}
run() { # bed label key=value ...
  b=$1; l=$2; shift 2
  resume_variant "$b" "$l" "$S" "$@" > "$OUT/$l.log" 2>&1
}
pour bed
run bed base
# overhead of the coupling: the same stroke with LIGGGHTS alone (wall held where the bed left it)
run bed rigid coupling.scheme=rigid
run bed interval_0.5mm coupling.interval=5e-4
# the first steps' small load with the shorter averaging window (docs/dem.md: 11.4 % of 0.17 N)
run bed interval_0.125mm coupling.interval=1.25e-4 dem.balance_tol=0.25
# a checkpoint refuses another DEM step, so the finer step has its own pour (same seed; the
# bed then differs by the chaotic pour as well: read it against the second pour's noise)
pour bed_dt01 dem.dt_fraction=0.1
run bed_dt01 dt_0.1 dem.dt_fraction=0.1
run bed speed_0.01 piston.speed=0.01
run bed speed_0.04 piston.speed=0.04
# the issue's extreme case "a piston ten times faster" (the staggered scheme stopped it on the
# force balance in its first step, docs/dem.md); the run checks decide
run bed speed_0.2 piston.speed=0.2
pour bed_soft30 grains.softening=30
run bed_soft30 softening_30 grains.softening=30
pour bed_soft300 grains.softening=300
run bed_soft300 softening_300 grains.softening=300
pour bed_h6 mesh.h=6e-3
run bed_h6 mesh_h6 mesh.h=6e-3
pour bed_seed2 dem.seed=32452843
run bed_seed2 seed2 dem.seed=32452843
python3 "$(dirname "$0")/error_vs_time.py" "$OUT" --at 0.5,1 \
  "coupling interval=interval_0.125mm:interval_0.5mm,base" "DEM time step=dt_0.1:base" \
  "piston speed=speed_0.01:base,speed_0.04,speed_0.2" "softening=softening_30:base,softening_300" \
  "FEM mesh=base:mesh_h6" "second pour (grain noise)=base:seed2"
