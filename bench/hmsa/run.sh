#!/usr/bin/env bash
# run.sh - work-precision study of softact's HMSA integrators against GNU Octave's ode45/ode15s
# (issue 4). Builds hmsa_bench, installs Debian's octave if it is missing, runs both sides on the
# same protocol (bench/hmsa/hmsa_protocol.m, hmsa_bench.c) and writes
#   bench/hmsa/results/*.csv            raw numbers (C medians of >= 3 runs; Octave once)
#   docs/hmsa_benchmark.md              tables, commit and date
#   docs/img/hmsa_*.png                 gnuplot figures
# Usage: bench/hmsa/run.sh [all|c|octave|report]   (default all)
# Environment: BUILD_DIR (default <repo>/build), HMSA_BENCH_EXE (use this binary, skip the build),
#              REPS (3), QUICK=1 (fewer tolerances and periods, a smoke test of a few minutes:
#              results and report go to bench/hmsa/results-quick/, docs/ is left alone).
# Needs: cmake, a C compiler, gnuplot, python3, and apt-get (root or sudo) if octave is missing.
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
RES=$HERE/results
DOCS=$ROOT/docs
if [[ ${QUICK:-0} == 1 ]]; then
  RES=$HERE/results-quick
  DOCS=$RES/docs
fi
BUILD_DIR=${BUILD_DIR:-$ROOT/build}
REPS=${REPS:-3}
STAGE=${1:-all}
mkdir -p "$RES"

log() { printf '[run.sh %s] %s\n' "$(date -u +%H:%M:%S)" "$*" >&2; }

# Wall time of a command in seconds (outside the program), appended to $RES/walltime.csv.
walltime() {
  local name=$1
  shift
  local t0 t1
  t0=$(date +%s.%N)
  "$@"
  t1=$(date +%s.%N)
  echo "$name,$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')" >>"$RES/walltime.csv"
}

if [[ ${QUICK:-0} == 1 ]]; then
  RTOLS=1e-4,1e-6,1e-8
  ORTOLS="[1e-4 1e-6]"
  PERIODS=(--trans 20 --meas 5)
  OPER="20, 5"
  NOMEGA=4
else
  RTOLS=1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10
  ORTOLS="[1e-3 1e-4 1e-5 1e-6 1e-7 1e-8 1e-9 1e-10]"
  PERIODS=(--trans 140 --meas 40)
  OPER="140, 40"
  NOMEGA=26
fi

run_c() {
  local exe=${HMSA_BENCH_EXE:-}
  if [[ -z $exe ]]; then
    log "building hmsa_bench in $BUILD_DIR"
    cmake -S "$ROOT" -B "$BUILD_DIR" >/dev/null
    if ! cmake --build "$BUILD_DIR" --target hmsa_bench -j2 >/dev/null; then
      log "cannot build target hmsa_bench (is add_subdirectory(bench) in CMakeLists.txt?)"
      exit 1
    fi
    exe=$BUILD_DIR/bench/hmsa/hmsa_bench
  fi
  cut -d' ' -f1-3 /proc/loadavg >"$RES/load_c.txt"
  log "C work-precision, non-stiff (eta_bar 50)"
  "$exe" wp 50 2.13 "$RES/c_wp_nonstiff.csv" --reps "$REPS" --rtols "$RTOLS" "${PERIODS[@]}"
  log "C work-precision, stiff (eta_bar 1e-3): dirk, bdf"
  "$exe" wp 1e-3 2.13 "$RES/c_wp_stiff.csv" --reps "$REPS" --rtols "$RTOLS" "${PERIODS[@]}" \
    --methods dirk,bdf,auto
  # Explicit steps are stability-bound here (h r <= ~3, r = 12 beta/eta_bar = 2.4e4): the cost
  # does not depend on the tolerance, three tolerances show it.
  log "C work-precision, stiff: erk (stability-bound, ~4 s a run)"
  "$exe" wp 1e-3 2.13 "$RES/c_wp_stiff_erk.csv" --reps "$REPS" --rtols 1e-3,1e-6,1e-9 \
    "${PERIODS[@]}" --methods erk --ref-check 0
  log "C sweep ($NOMEGA frequencies)"
  "$exe" sweep "$RES/c_sweep.csv" --reps "$REPS" --n "$NOMEGA" "${PERIODS[@]}" \
    --rtols "$(echo "$RTOLS" | sed 's/^1e-3,1e-4,//')" --methods erk,dirk,bdf
}

run_octave() {
  if ! command -v octave >/dev/null 2>&1; then
    log "installing octave (Debian package, --no-install-recommends)"
    local sudo=
    [[ $(id -u) -ne 0 ]] && sudo=sudo
    $sudo apt-get update -q
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends octave
  fi
  octave --version | head -n 1 >"$RES/octave_version.txt"
  : >"$RES/walltime.csv"
  cut -d' ' -f1-3 /proc/loadavg >"$RES/load_octave.txt"
  local oct=(octave --no-gui --quiet --no-window-system --eval)
  local pre="addpath('$HERE');"
  log "Octave work-precision, non-stiff: ode45"
  walltime octave_wp_nonstiff_ode45 "${oct[@]}" \
    "$pre octave_wp('$RES/octave_wp_nonstiff_ode45.csv', 'ode45', 50, 2.13, $ORTOLS, $OPER)"
  log "Octave work-precision, non-stiff: ode15s"
  walltime octave_wp_nonstiff_ode15s "${oct[@]}" \
    "$pre octave_wp('$RES/octave_wp_nonstiff_ode15s.csv', 'ode15s', 50, 2.13, $ORTOLS, $OPER)"
  log "Octave work-precision, stiff: ode15s"
  walltime octave_wp_stiff_ode15s "${oct[@]}" \
    "$pre octave_wp('$RES/octave_wp_stiff_ode15s.csv', 'ode15s', 1e-3, 2.13, $ORTOLS, $OPER)"
  # ode45 on the stiff case needs ~3.7e6 steps for 180 periods (~25 min): time 2 periods and
  # scale by steps (the step size is stability-bound, so steps grow linearly with the span).
  log "Octave stiff: ode45 on 1 + 1 periods only"
  walltime octave_wp_stiff_ode45_2periods "${oct[@]}" \
    "$pre octave_wp('$RES/octave_wp_stiff_ode45_2periods.csv', 'ode45', 1e-3, 2.13, [1e-6], 1, 1)"
  log "Octave sweep: ode45 rtol 1e-8 ($NOMEGA frequencies; minutes)"
  walltime octave_sweep_ode45_1e-8 "${oct[@]}" \
    "$pre octave_sweep('$RES/octave_sweep_ode45_1e-8.csv', 'ode45', 1e-8, 50, $NOMEGA, 1.5, 2.75, $OPER)"
  log "Octave sweep: ode45 rtol 1e-6"
  walltime octave_sweep_ode45_1e-6 "${oct[@]}" \
    "$pre octave_sweep('$RES/octave_sweep_ode45_1e-6.csv', 'ode45', 1e-6, 50, $NOMEGA, 1.5, 2.75, $OPER)"
}

report() {
  {
    echo "commit=$(git -C "$ROOT" rev-parse HEAD 2>/dev/null || echo none)"
    echo "dirty_files=$(git -C "$ROOT" status --porcelain 2>/dev/null | wc -l)"
    echo "date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
    echo "nproc=$(nproc)"
    echo "loadavg=$(cut -d' ' -f1-3 /proc/loadavg)"
    echo "sundials=$(dpkg-query -W -f='${Version}' libsundials-dev 2>/dev/null || echo unknown)"
    echo "quick=${QUICK:-0}"
    echo "reps=$REPS"
  } >"$RES/meta.txt"
  python3 "$HERE/analyse.py" "$RES" "$DOCS"
}

case $STAGE in
  all) run_c; run_octave; report ;;
  c) run_c ;;
  octave) run_octave ;;
  report) report ;;
  *) echo "usage: $0 [all|c|octave|report]" >&2; exit 1 ;;
esac
log "done"
