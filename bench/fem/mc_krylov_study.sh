#!/bin/sh
# Newton directions of the Mohr-Coulomb actuator scene by GMRES on earlier LU factors against a
# fresh UMFPACK LU every iteration: the augmented frictional step of tests/apps/test_mc_augmented.py
# (CI mesh: tet4, no rings, silicone h 6 mm, fill h 4 mm, penalty 0.3, 25 um, augmented until
# the overlap is below 0.005 of the displaced volume) for each [solver] krylov_max / krylov_rtol.
# usage: bench/fem/mc_krylov_study.sh [build dir] [out dir] [runs per setting]
#        [settings "max/rtol ..."]
#   e.g. bench/fem/mc_krylov_study.sh build /tmp/mc_krylov 3 "0/1e-3 30/1e-3 30/1e-2 50/1e-2"
# Writes <out>/krylov.csv (setting, run, wall s, Newton iterations, factorisations, Krylov
# directions / abandoned / iterations, piston force, cavity volume change, angle) and prints it
# with the per-setting medians, the commit and the date. One thread per run, runs one after
# another: time it on an idle machine.
set -eu
build=${1:-build}
out=${2:-/tmp/softact_mc_krylov}
runs=${3:-3}
settings=${4:-"0/1e-3 10/1e-3 30/1e-3 30/1e-2 50/1e-2 30/1e-1"}
src=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
csv="$out/krylov.csv"
echo "krylov_max,krylov_rtol,run,wall_s,newton_iterations,factorisations,krylov_directions,krylov_failed,krylov_iterations,piston_force,volume_change_rel,bending_angle" > "$csv"
for set in $settings; do
  kmax=${set%/*}
  krtol=${set#*/}
  r=1
  while [ "$r" -le "$runs" ]; do
    dir="$out/k${kmax}_r${krtol}_$r"
    "$build/apps/softact" run "$src/cases/granular_bending_mc.ini" --out "$dir" --quiet \
      --set mc_bending.penalty=0.3 --set mesh.order=1 --set mesh.rings=0 --set mesh.h=6e-3 \
      --set mc_bending.fill_h=4e-3 --set mc_bending.stroke=2.5e-5 --set mc_bending.n_steps=1 \
      --set mc_bending.vtk_every=0 --set mc_bending.augment=40 --set solver.rtol=1e-5 \
      --set run.threads=1 --set run.plots=0 \
      --set solver.krylov_max="$kmax" --set solver.krylov_rtol="$krtol" ||
      echo "krylov_max=$kmax krylov_rtol=$krtol run $r failed" >&2
    s="$dir/summary.ini"
    if [ -f "$s" ]; then
      get() { sed -n "s/^$1 = \([^ ;]*\).*/\1/p" "$s"; }
      last=$(tail -n 1 "$dir/bending.csv")
      # bending.csv columns 2, 3, 5: bending_angle, piston_force, volume_change_rel
      angle=$(echo "$last" | cut -d, -f2)
      force=$(echo "$last" | cut -d, -f3)
      dv=$(echo "$last" | cut -d, -f5)
      echo "$kmax,$krtol,$r,$(get wall_s),$(get newton_iterations),$(get factorisations),$(get krylov_directions),$(get krylov_failed),$(get krylov_iterations),$force,$dv,$angle" >> "$csv"
    fi
    r=$((r + 1))
  done
done
echo "# commit $(git -C "$src" rev-parse --short HEAD) $(date -u +%Y-%m-%d)"
column -s, -t < "$csv"
python3 - "$csv" <<'EOF'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
keys = sorted({(r["krylov_max"], r["krylov_rtol"]) for r in rows}, key=lambda k: (int(k[0]), float(k[1])))
print("median wall s per setting:")
for k in keys:
    w = [float(r["wall_s"]) for r in rows if (r["krylov_max"], r["krylov_rtol"]) == k]
    print(f"  krylov_max {k[0]:>3} krylov_rtol {k[1]:>5}: {statistics.median(w):7.1f} s over {len(w)} run(s)")
EOF
