#!/bin/sh
# The wall every k DEM steps against the chaos floor of one bed (issue 12: exchange below 5 %
# of the DEM; docs/dem.md, "Session 2026-12-06"). One poured 2 mm bed (the scene's pour,
# preloaded with the wall every step), then its stroke resumed from the preload checkpoint:
#  - exact runs (wall every step) perturbed only at tolerance level: solver.rtol 0.9e-6,
#    coupling.qn_reuse 7, and the scene's own solver: their spread is the floor;
#  - wall_every = 2, 5, 10, 25 (the scene uses 10 while the piston moves).
# Two variants at a time fit the 2 cores (PAR=1 runs them one after the other).
#   bench/dem/wall_every_study.sh OUT [STROKE_M]
set -eu
OUT=$1
S=${2:-2.5e-3}
D=2e-3
EXE=${EXE:-build/apps/softact}
CASE=cases/granular_bending_dem.ini
mkdir -p "$OUT"
. "$(dirname "$0")/resume_variant.sh"
pour_bed bed 2.5e-4
run_pair() {
  if [ "${PAR:-2}" = 1 ]; then resume_variant bed "$@"; else resume_variant bed "$@" & fi
}
run_pair exact_rtol "$S" coupling.wall_every=1 solver.rtol=0.9e-6
resume_variant bed exact_qn "$S" coupling.wall_every=1 coupling.qn_reuse=7; wait
run_pair exact "$S" coupling.wall_every=1
resume_variant bed we2 "$S" coupling.wall_every=2; wait
run_pair we5 "$S" coupling.wall_every=5
resume_variant bed we10 "$S" coupling.wall_every=10; wait
resume_variant bed we25 "$S" coupling.wall_every=25
python3 "$(dirname "$0")/study.py" "$OUT" exact:coupling.wall_every=1 \
  exact_rtol:solver.rtol=0.9e-6 exact_qn:coupling.qn_reuse=7 we2:coupling.wall_every=2 \
  we5:coupling.wall_every=5 we10:coupling.wall_every=10 we25:coupling.wall_every=25 \
  --collect-only --marks 0,0.5,1,1.5,2,2.5
