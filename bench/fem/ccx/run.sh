#!/bin/sh
# bench/fem/ccx/run.sh - the CalculiX peer comparison of the FEM solver (a benchmark, never a test).
#
#   sh bench/fem/ccx/run.sh [verify|a|b|all]      (default all; then writes docs/calculix.md)
#
# verify  exporter conventions on exact solutions: a block in uniaxial stress (Yeoh, follower
#         pressure on its top) as C3D10 (Gmsh tets via ccx_export) and as C3D20R (ccx_hex box);
#         ccx_post compares every node with the analytic field.
# a       compressible variant K/mu = 5 (no locking in either code): our tet10 mixed element and
#         ccx C3D10 on the SAME tet10 mesh (mesh signature printed by both), same materials and
#         pressure; ccx C3D20R on the structured hex half model as a cross-check.
# b       near-incompressible reference K/mu = 500: ours (tet10 mixed) vs ccx C3D10 (locks) and
#         ccx C3D20R on structured hex meshes at two sizes (mesh convergence).
# Geometry: the reference actuator of meshes/actuator.geo WITHOUT the rings (rings = 0; band
# kept), so the tet mesh stays < 100k dof and the hex mesh is shared; pressure $PRESSURE on the
# cavity wall and floor, ramped 0 -> P in one static step by each code's own load stepping.
# Each solver run is cached in $WORK (delete a NAME.done to redo it); ccx outputs stay there
# (never committed). Times: /usr/bin/time -v wall and CPU (user + sys), OMP_NUM_THREADS=2,
# CCX_NPROC_EQUATION_SOLVER=2 for ccx, 2 threads for ours; the load average is recorded because
# the machine is shared.
set -eu
ROOT=$(cd "$(dirname "$0")/../../.." && pwd)
BUILD=${BUILD:-$ROOT/build-ccx}
WORK=${WORK:-$BUILD/bench/ccx_runs}
PRESSURE=${PRESSURE:-30e3}
H_TET=${H_TET:-3e-3}              # tet10 size shared by both codes (89.5k dof)
H_TET_OURS=${H_TET_OURS:-"4e-3 3e-3 2e-3 1.5e-3"}   # our mesh-convergence series (b): 82k-142k dof
H_HEX=${H_HEX:-"2e-3 1.5e-3 1.5e-3:0.5e-3 1e-3 0.75e-3"}  # C3D20R half model, h[:radial h] (33k-277k dof)
H_HEX_A=${H_HEX_A:-2e-3}          # C3D20R cross-check of stage a
GEO=$ROOT/meshes/actuator.geo
WHAT=${1:-all}
export OMP_NUM_THREADS=2 CCX_NPROC_EQUATION_SOLVER=2

command -v ccx > /dev/null 2>&1 || {
  echo "run.sh: installing calculix-ccx (Debian)"
  if [ "$(id -u)" = 0 ]; then apt-get install -y calculix-ccx; else sudo apt-get install -y calculix-ccx; fi
}

# ---------------------------------------------------------------------------------- tools
T=$BUILD/bench/fem/ccx
if ! cmake --build "$BUILD" --target ccx_export ccx_hex ccx_post ccx_ours -j2 > /dev/null 2>&1; then
  # bench/ not (yet) in the CMake tree: build by hand against the libraries of $BUILD.
  T=$BUILD/bench/ccx_tools
  mkdir -p "$T"
  cmake --build "$BUILD" --target sa_core sa_fem_mesh sa_fem_kernels sa_fem -j2 > /dev/null
  S=$ROOT/bench/fem/ccx
  CF="-std=c17 -O2 -Wall -Wextra -D_XOPEN_SOURCE=700 -I$ROOT/core -I$ROOT/fem -I$S"
  L="$BUILD/core/libsa_core.a -linih -lm -lpthread"
  gcc $CF "$S/ccx_hex.c" "$S/ccx_inp.c" $L -o "$T/ccx_hex"
  gcc $CF "$S/ccx_post.c" $L -o "$T/ccx_post"
  gcc $CF "$S/ccx_export.c" "$S/ccx_inp.c" "$S/ccx_sig.c" "$BUILD/fem/libsa_fem_mesh.a" $L -lgmsh \
    -o "$T/ccx_export"
  gcc $CF -fopenmp "$S/ccx_ours.c" "$S/ccx_sig.c" "$BUILD/fem/libsa_fem.a" \
    "$BUILD/fem/libsa_fem_kernels.a" "$BUILD/fem/libsa_fem_mesh.a" $L -lgmsh -lumfpack -lcholmod \
    -lamd -lcolamd -lcamd -lccolamd -lsuitesparseconfig -lmetis -lopenblas -o "$T/ccx_ours"
fi
mkdir -p "$WORK"
cd "$WORK"

# ------------------------------------------------------------------------------- helpers
# ccx NAME: run ccx on NAME.inp (cached), then post-process NAME.dat -> NAME.res
ccx_run() {
  if [ ! -f "$1.done" ]; then
    echo "run.sh: ccx $1 ($(grep -c '' "$1.inp") lines), load $(cut -d' ' -f1-3 /proc/loadavg)"
    uptime > "$1.load"
    /usr/bin/time -v ccx -i "$1" > "$1.log" 2> "$1.time" || { echo "ccx $1 failed: $WORK/$1.log"; return 1; }
    touch "$1.done"
  fi
  "$T/ccx_post" tip "$1" --log "$1.log" > "$1.res"
}
# ours NAME ARGS...: our solver (cached), NAME.u -> NAME.res (needs the matching NAME.tip)
ours_run() {
  n=$1; shift
  if [ ! -f "$n.done" ]; then
    echo "run.sh: ours $n, load $(cut -d' ' -f1-3 /proc/loadavg)"
    uptime > "$n.load"
    /usr/bin/time -v "$T/ccx_ours" --verbose --out "$n" "$@" > "$n.ours" 2> "$n.time" || { echo "ours $n failed: $WORK/$n.time"; return 1; }
    touch "$n.done"
  fi
  "$T/ccx_post" field "$n" "$n.u" > "$n.res"
}
# the tip side file of a tet mesh (ccx_export writes it with the deck)
tet_deck() { # NAME H KRATIO [extra]
  n=$1 h=$2 k=$3
  [ -f "$n.inp" ] || "$T/ccx_export" --geo "$GEO" --h "$h" --set rings=0 --kappa-ratio "$k" \
    --pressure "$PRESSURE" --inc0 0.25 --incmax 1 --out "$n" > "$n.export" 2>&1
}
hex_deck() { # NAME H[:HR] KRATIO
  [ -f "$1.inp" ] || "$T/ccx_hex" actuator --h "${2%%:*}" --hr "$(echo "$2" | sed 's/^[^:]*$/0/; s/.*://')" \
    --rings 0 --kappa-ratio "$3" \
    --pressure "$PRESSURE" --inc0 0.25 --incmax 1 --out "$1" > "$1.export" 2>&1
}

tag() { echo "$1" | sed 's/:/r/'; }   # run-name tag of a hex size h[:hr]

# ------------------------------------------------------------------------------ stages
verify() {
  "$T/ccx_export" --geo "$ROOT/bench/fem/ccx/cube.geo" --h 4e-3 --out v_tet --fix none \
    --roller x0:1 --roller y0:2 --roller z0:3 --load top --tip top --kappa-ratio 5 \
    --pressure 30e3 --print-all --inc0 0.25 --incmax 0.25 > v_tet.export 2>&1
  "$T/ccx_hex" box --lx 0.01 --ly 0.01 --lz 0.01 --nx 2 --ny 2 --nz 2 --kappa-ratio 5 \
    --pressure 30e3 --print-all --inc0 0.25 --incmax 0.25 --out v_hex > v_hex.export
  for v in v_tet v_hex; do
    rm -f $v.done
    ccx_run $v
    "$T/ccx_post" uniaxial $v --c10 0.11e6 --c20 0.02e6 --kappa 1.1e6 --pressure 30e3 | tee $v.check
  done
}
stage_a() {
  tet_deck a_tet "$H_TET" 5
  cp a_tet.tip a_ours.tip
  ours_run a_ours --geo "$GEO" --h "$H_TET" --set rings=0 --kappa-ratio 5 --pressure "$PRESSURE"
  ccx_run a_tet
  for h in $H_HEX_A; do hex_deck a_hex_$(tag $h) "$h" 5; ccx_run a_hex_$(tag $h); done
}
stage_b() {
  # ours starts with ccx's first increment (0.25 of the load; *STATIC 0.25, 1)
  for h in $H_TET_OURS; do
    tet_deck b_mesh_$h "$h" 500
    cp b_mesh_$h.tip b_ours_dl_$h.tip
    ours_run b_ours_dl_$h --geo "$GEO" --h "$h" --set rings=0 --kappa-ratio 500 \
      --pressure "$PRESSURE" --dl-init 0.25
  done
  for h in $H_HEX; do hex_deck b_hex_$(tag $h) "$h" 500; ccx_run b_hex_$(tag $h); done
  tet_deck b_mesh_$H_TET "$H_TET" 500
  ccx_run b_mesh_$H_TET
}

case $WHAT in
  verify) verify ;;
  a) stage_a ;;
  b) stage_b ;;
  all) verify; stage_a; stage_b ;;
  report) ;;
  *) echo "usage: run.sh [verify|a|b|all|report]"; exit 1 ;;
esac
[ "$WHAT" = all ] || [ "$WHAT" = report ] || exit 0
sh "$ROOT/bench/fem/ccx/report.sh" "$WORK" "$ROOT/docs/calculix.md" "$PRESSURE" "$H_TET" "$H_HEX"
