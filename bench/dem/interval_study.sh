#!/bin/sh
# Coupling interval and Robin interface stiffness, from one poured bed (issue 12, docs/dem.md).
# The bed is poured, settled and preloaded once; its checkpoint (after the 5 preload steps) is
# copied into every variant, which resumes from it with its own settings (the settings that
# matter only after the preload may differ from the base run's). Variants run one after the
# other (parallel runs on 2 cores distort each other's timings).
#   bench/dem/interval_study.sh OUT [BEAD_DIAMETER_M] [STROKE_M]
set -eu
OUT=$1
D=${2:-3e-3}
S=${3:-2e-3}
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
mkdir -p "$OUT"
. "$(dirname "$0")/resume_variant.sh"
pour_bed base 1e-3
run() { # label key=value ...
  l=$1; shift
  resume_variant base "$l" "$S" "$@"
}
run interval_0.5mm coupling.interval=5e-4
run interval_0.25mm coupling.interval=2.5e-4
run interval_0.125mm coupling.interval=1.25e-4
run k_0.5 coupling.interface_stiffness=0.5
run k_2 coupling.interface_stiffness=2
run normal_only_0.125mm coupling.interval=1.25e-4 coupling.interface_tangential=0
python3 bench/dem/study.py "$OUT" --collect-only --marks 0,0.5,1,1.5,2 \
  interval_0.5mm:coupling.interval=5e-4 interval_0.25mm:coupling.interval=2.5e-4 \
  interval_0.125mm:coupling.interval=1.25e-4 k_0.5:coupling.interface_stiffness=0.5 \
  k_2:coupling.interface_stiffness=2 \
  normal_only_0.125mm:coupling.interval=1.25e-4,coupling.interface_tangential=0
