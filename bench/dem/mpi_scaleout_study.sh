#!/bin/sh
# MPI scale-out (issue 12): LIGGGHTS domain-decomposed over two ranks ([dem] mpi_ranks = 2; the
# FEM, the coupling and the output on rank 0) against one rank, on the default scene.
#  whole/ : two whole runs, each its own pour (serial, 2 ranks): wall time and its split
#           (summary.ini [timing]); the beds differ, so their curves differ by grain noise;
#  stroke/: one bed poured and preloaded on one rank, its stroke resumed on one and on two
#           ranks: the same bed, so what differs is the decomposition's round-off, grown by
#           the bed (compare with the tolerance-level perturbations of docs/dem.md).
# Runs one after the other (parallel runs distort each other's timings); an idle machine.
#   bench/dem/mpi_scaleout_study.sh OUT [STROKE_M]
set -eu
OUT=$1
S=${2:-2.5e-3}
EXE=${EXE:-build/apps/softact}
CASE=${CASE:-cases/granular_bending_dem.ini}
D=2e-3
here=$(dirname "$0")
python3 "$here/study.py" "$OUT/whole" "ranks1:dem.mpi_ranks=1,piston.stroke=$S" \
  "ranks2:dem.mpi_ranks=2,piston.stroke=$S" --exe "$EXE" --case "$CASE" \
  --marks 0,0.5,1,1.5,2,2.5 --relative
OUT=$OUT/stroke
mkdir -p "$OUT"
# shellcheck source=bench/dem/resume_variant.sh
. "$here/resume_variant.sh"
pour_bed bed 2.5e-4 dem.mpi_ranks=1 # a checkpoint after the 5 preload steps
resume_variant bed ranks1 "$S" dem.mpi_ranks=1
resume_variant bed ranks2 "$S" dem.mpi_ranks=2
python3 "$here/study.py" "$OUT" ranks1: ranks2: --collect-only --marks 0,0.5,1,1.5,2,2.5 --relative
