# seeded_beds.sh - sourced by the bench/dem studies that compare variants on several poured beds
# (interval_long_study.sh, speed_long_study.sh), after OUT, D, S, EXE and CASE are set: the
# pour seeds (primes > 10000, LIGGGHTS' rule; SEEDS overrides), one MPI rank and one thread per
# run (two or three runs share the machine), and pour_bed / resume_variant.
SEEDS=${SEEDS:-"15485863 32452843 49979687 67867967 86028121 104395301"}
ONE="dem.mpi_ranks=1 run.threads=1"
mkdir -p "$OUT"
. "$(dirname "$0")/resume_variant.sh"
