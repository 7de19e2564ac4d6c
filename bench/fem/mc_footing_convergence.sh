#!/bin/sh
# Mesh-convergence series of the strip footing (cases/mc_footing.ini) against Prandtl's N_c.
# usage: bench/fem/mc_footing_convergence.sh [build dir] [out dir] [friction angles] [cells]
#   e.g. bench/fem/mc_footing_convergence.sh build /tmp/footing "0 10 20 30" "4 6 8 12"
# Writes <out>/convergence.csv (phi, cells, nodes, edge cell / B, N_c FEM, Prandtl, relative
# error, rise over the last tenth of the settlement, Newton iterations, wall seconds) and prints
# it with the commit and date. Associated flow (dilation_angle = friction_angle). Each run uses
# one thread; runs are niced (the machine is shared).
set -eu
build=${1:-build}
out=${2:-/tmp/softact_footing}
phis=${3:-"0 10 20 30"}
cells=${4:-"4 6 8"}
src=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
csv="$out/convergence.csv"
echo "phi,cells,nodes,edge_cell,bearing_capacity_factor,prandtl_N_c,rel_error,last_tenth_rise,newton_iterations,wall_s" > "$csv"
for phi in $phis; do
  for n in $cells; do
    dir="$out/phi${phi}_n${n}"
    nice -n 5 "$build/apps/softact" run "$src/cases/mc_footing.ini" --out "$dir" --quiet \
      --set run.threads=1 --set footing.cells="$n" \
      --set fill.friction_angle="$phi" --set fill.dilation_angle="$phi" || echo "phi=$phi cells=$n failed" >&2
    s="$dir/summary.ini"
    [ -f "$s" ] || continue
    get() { sed -n "s/^$1 = \([^ ;]*\).*/\1/p" "$s"; }
    echo "$phi,$n,$(get nodes),$(get edge_cell),$(get bearing_capacity_factor),$(get prandtl_N_c),$(get bearing_capacity_rel_error),$(get last_tenth_rise),$(get newton_iterations),$(get wall_s)" >> "$csv"
  done
done
echo "# commit $(git -C "$src" rev-parse --short HEAD) $(date -u +%Y-%m-%d)"
column -s, -t < "$csv"
