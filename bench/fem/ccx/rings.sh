#!/bin/sh
# bench/fem/ccx/rings.sh - CalculiX points WITH the radial rings for the FEM's work-precision plot
# (issue 14, item 3; a benchmark, never a test).
#
#   sh bench/fem/ccx/rings.sh [RUN...]      (default: the runs of $RUNS; "table" prints only)
#
# Problem: the reference actuator of meshes/actuator.geo WITH the rings (rings = 1): Yeoh silicone
# C10 = 0.11 MPa, C20 = 0.02 MPa, kappa = 500 mu0; band E = 1 GPa, rings E = 2 GPa (nu = 0.3,
# compressible neo-Hooke); top 5 mm of the outside and the top annulus clamped; follower pressure
# on the cavity wall and floor ramped 0 -> $PMAX in one *STATIC step. The tip displacements are
# printed at the step times $TIMES (*TIME POINTS: ccx cuts its increments to hit them) and the
# table gives the bending angle at the step times $AT (30, 60, 90, 120 kPa for PMAX = 120 kPa):
# the rotation of the tip surface's mean outward normal in the x-z plane (ccx_post tip,
# fem_bending_angle's definition). Runs:
#   t_4e-3      ccx C3D10 on our default tet10 mesh, fem_mesh_generate(h = 4 mm, h_band = 2 mm,
#               h_ring = 2 mm), written by ccx_export (same mesh as our solver's default run)
#   x_H[rHR]    ccx C3D20R on ccx_hex's structured half model (u_y = 0 on y = 0), h = H
#               (radial size HR); H_HEX lists them as H[:HR]
#   NAME_LABEL  the same mesh as NAME with other settings (e.g. INC, TIMES given in the
#               environment when the deck is first written); the table reads each run's
#               increment settings back from its deck
# Each ccx run is cached in $WORK (delete NAME.done to redo it) under /usr/bin/time -v with
# OMP_NUM_THREADS=2 CCX_NPROC_EQUATION_SOLVER=2 (as run.sh) and `nice -n 5` (the machine is
# shared: the load average at the start is recorded). A run that stops short of PMAX keeps
# its table row: the angles it reached, "-" beyond, the last converged load and the angle at
# the last printed time (print every 0.05 with TIMES to get it close to the stop).
# dof = free dofs: 3 x nodes minus the constrained (node, dof) pairs of the deck's *BOUNDARY.
set -eu
ROOT=$(cd "$(dirname "$0")/../../.." && pwd)
BUILD=${BUILD:-$ROOT/build-ccx}
WORK=${WORK:-$BUILD/bench/ccx_rings}
PMAX=${PMAX:-120e3}
TIMES=${TIMES:-0.25,0.5,0.75,1}   # print times (step fractions) of new decks
AT=${AT:-0.25,0.5,0.75,1}         # table columns (each must be a print time)
INC=${INC:-"--inc0 0.05 --incmin 1e-5 --incmax 0.25"}   # step fractions: 6 kPa first, <= 30 kPa
H_TET=${H_TET:-4e-3}
H_HEX=${H_HEX:-"2e-3 1.5e-3"}
GEO=$ROOT/meshes/actuator.geo
export OMP_NUM_THREADS=2 CCX_NPROC_EQUATION_SOLVER=2

tag() { echo "$1" | sed 's/:/r/'; }   # run-name tag of a hex size h[:hr]
RUNS=${RUNS:-"t_$H_TET $(for h in $H_HEX; do printf 'x_%s ' "$(tag "$h")"; done)"}
[ $# -gt 0 ] || set -- $RUNS

command -v ccx > /dev/null 2>&1 || {
  echo "rings.sh: installing calculix-ccx (Debian)"
  if [ "$(id -u)" = 0 ]; then apt-get install -y calculix-ccx; else sudo apt-get install -y calculix-ccx; fi
}
[ -f "$BUILD/CMakeCache.txt" ] || cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$BUILD" --target ccx_export ccx_hex ccx_post -j2 > /dev/null
T=$BUILD/bench/fem/ccx
mkdir -p "$WORK"
cd "$WORK"

# deck NAME: write NAME.inp and NAME.tip unless present
deck() {
  [ -f "$1.inp" ] && return 0
  case $1 in t_*|x_*) ;; *) echo "rings.sh: unknown run $1 (t_H or x_H[rHR], [_LABEL])"; return 1 ;; esac
  h=$(echo "$1" | cut -d_ -f2)   # mesh size: t_H[_LABEL], x_H[rHR][_LABEL]
  case $1 in
    t_*) "$T/ccx_export" --geo "$GEO" --h "$h" --set rings=1 --set h_band=2e-3 --set h_ring=2e-3 \
           --pressure "$PMAX" $INC --time-points "$TIMES" --out "$1" > "$1.export" 2>&1 ;;
    x_*) "$T/ccx_hex" actuator --h "${h%%r*}" --hr "$(echo "$h" | sed 's/^[^r]*$/0/; s/.*r//')" --rings 1 \
           --pressure "$PMAX" $INC --time-points "$TIMES" --out "$1" > "$1.export" 2>&1 ;;
  esac || { cat "$1.export"; rm -f "$1.inp"; return 1; }
}
# run NAME: ccx on NAME.inp (cached; its exit status kept in NAME.rc)
run() {
  if [ ! -f "$1.done" ]; then
    echo "rings.sh: ccx $1 ($(grep -c '' "$1.inp") lines), load $(cut -d' ' -f1-3 /proc/loadavg)"
    uptime > "$1.load"
    rc=0
    nice -n 5 /usr/bin/time -v ccx -i "$1" > "$1.log" 2> "$1.time" || rc=$?
    echo "$rc" > "$1.rc"
    touch "$1.done"
  fi
}
# free dofs of a deck
dofs() {
  awk -F', *' '/^\*/ { mode = ""
      if ($0 ~ /^\*NODE, NSET=NALL/) mode = "node"
      else if ($0 ~ /^\*NSET, NSET=/) { mode = "nset"; cur = substr($2, 6) }
      else if ($0 ~ /^\*BOUNDARY/) mode = "bc"
      next }
    mode == "node" { n++ }
    mode == "nset" { for (i = 1; i <= NF; i++) if ($i != "") set[cur] = set[cur] " " $i }
    mode == "bc" { m = split(set[$1], L, " ")
      for (k = 1; k <= m; k++) for (d = $2; d <= $3; d++) if (!((L[k], d) in fix)) { fix[L[k], d] = 1; c++ } }
    END { print 3 * n - c }' "$1.inp"
}
row() {
  n=$1
  [ -f "$n.done" ] || { echo "| $n | (not run) |"; return; }
  "$T/ccx_post" tip "$n" --log "$n.log" --at "$AT" > "$n.res"
  inc=$(awk '/^\*STATIC/{getline; gsub(/ /, ""); print; exit}' "$n.inp")
  ntp=$(awk '/^\*TIME POINTS/{t=1; next} /^\*/{t=0} t{n+=split($0, x, ",")} END{print n+0}' "$n.inp")
  awk -v n="$n" -v dof="$(dofs "$n")" -v pmax="$PMAX" -v rc="$(cat "$n.rc" 2>/dev/null || echo '?')" \
      -v set="$inc; $ntp" '
    FILENAME ~ /\.res$/ && $1 == "#" && $2 == "at" { a[++na] = ($4 == "angle") ? sprintf("%.4f", $5) : "-" }
    FILENAME ~ /\.res$/ && $1 == "#" && $2 == "last" { lt = $4; la = $6 }
    FILENAME ~ /\.res$/ && $1 == "#" && $2 == "reached" { reached = $3 }
    FILENAME ~ /\.res$/ && $1 == "#" && $2 == "increments" { inc = $3 " (" $5 " att.)"; its = $7 }
    FILENAME ~ /\.time$/ && /Elapsed \(wall clock\)/ { k = split($NF, t, ":"); w = 0; for (i = 1; i <= k; i++) w = w * 60 + t[i] }
    FILENAME ~ /\.time$/ && /User time/ { u = $NF }
    FILENAME ~ /\.time$/ && /System time/ { s = $NF }
    FILENAME ~ /\.time$/ && /Maximum resident/ { rss = $NF / 1024 }
    FILENAME ~ /\.load$/ { for (i = 1; i <= NF; i++) if ($i == "average:") { ld = $(i + 1); sub(",", "", ld) } }
    END {
      note = (rc == 0) ? "" : sprintf(" (ccx exit %s: converged to %.2f kPa; %.4f deg at %.1f kPa)",
        rc, reached * pmax / 1e3, la, lt * pmax / 1e3)
      printf "| %s%s | %s | %s |", n, note, set, dof; for (i = 1; i <= na; i++) printf " %s |", a[i]
      printf " %s | %s | %.0f | %.0f | %.0f | %s |\n", inc, its, w, u + s, rss, ld }' "$n.res" "$n.time" "$n.load"
}

for n in "$@"; do
  [ "$n" = table ] && continue
  deck "$n"
  run "$n"
done
echo "# ccx $(dpkg-query -W -f '${Version}' calculix-ccx 2>/dev/null || echo '?'), p_max = $PMAX Pa;" \
  "settings: *STATIC inc0, period, incmin, incmax; number of print times"
echo "$AT" | awk -F, -v p="$PMAX" '{ printf "| run | settings | dof |"; for (i = 1; i <= NF; i++) printf " angle %g kPa [deg] |", $i * p / 1e3
  printf " increments | Newton its | wall [s] | CPU [s] | peak RSS [MB] | load at start |\n|---|---|---|"
  for (i = 1; i <= NF; i++) printf "---|"; print "---|---|---|---|---|---|" }'
# the default runs, then any other run of $WORK (retries), oldest first
done_rows=
for n in $RUNS $(ls -tr -- *.done 2>/dev/null | sed 's/\.done$//'); do
  case " $done_rows " in *" $n "*) continue ;; esac
  done_rows="${done_rows:-} $n"
  row "$n"
done
