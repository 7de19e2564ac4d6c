#!/bin/sh
# Grain size (issue 12): bending angle against piston displacement for 1, 2 and 3 mm beads on
# one plot, each its own pour with the default scene's settings and stroke (the iterated
# coupling at 0.25 mm, 20 mm/s). The 2 mm run is the default scene. 1 mm beads are ~14,800
# grains at half the time step: ~16x the 2 mm run's DEM cost (hours on one core), so they run
# only when asked (WITH_1MM=1).
#   bench/dem/grain_size_study.sh OUT [STROKE_M]
set -eu
OUT=$1
S=${2:-2.5e-3}
V="2mm_beads:grains.diameter=2e-3,piston.stroke=$S 3mm_beads:grains.diameter=3e-3,piston.stroke=$S"
[ "${WITH_1MM:-0}" = 1 ] && V="1mm_beads:grains.diameter=1e-3,piston.stroke=$S $V"
# shellcheck disable=SC2086
python3 "$(dirname "$0")/study.py" "$OUT" $V --marks 0,0.5,1,1.5,2,2.5 --relative
