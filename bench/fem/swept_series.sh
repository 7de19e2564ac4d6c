#!/bin/sh
# The pressure ramp 0 -> 120 kPa of the reference actuator with rings on swept meshes
# ([mesh] kind = swept, fem/fem_mesh_swept.c), against the converged estimate of
# docs/fem_time_to_accuracy.md (16.82 / 36.66 / 59.32 / 84.20 deg at 30 / 60 / 90 / 120 kPa).
#   bench/fem/swept_series.sh OUT "h,h_radial,h_band,h_ring,grade" ...
# One run per quintuple (sizes in mm), each in OUT/<name>; a table on stdout. The case is
# cases/pressure_bending.ini (its solver settings) with p_max 120 kPa in 12 output steps.
# EXE may point at a copy of the binary.
set -eu
OUT=$1
shift
EXE=${EXE:-build/apps/softact}
mkdir -p "$OUT"
printf '%-28s %9s %8s %8s %8s %8s %6s %6s %8s\n' run dofs 30kPa 60kPa 90kPa 120kPa fact newton wall_s
for spec in "$@"; do
  IFS=, read -r h hr hb hg gr <<SPEC
$spec
SPEC
  name="h${h}_r${hr}_b${hb}_g${hg}_x${gr}"
  d="$OUT/$name"
  if [ ! -f "$d/summary.ini" ] || ! grep -q '^status = completed' "$d/summary.ini"; then
    "$EXE" run cases/pressure_bending.ini --out "$d" --quiet --set mesh.kind=swept \
      --set mesh.h="${h}e-3" --set mesh.h_radial="${hr}e-3" --set mesh.h_band="${hb}e-3" \
      --set mesh.h_ring="${hg}e-3" --set mesh.grade="$gr" --set loading.p_max=120e3 \
      --set loading.n_steps=12 > "$d.out" 2>&1 || true
  fi
  python3 - "$d" "$name" <<'PY'
import csv, sys, re
d, name = sys.argv[1], sys.argv[2]
try:
    rows = list(csv.DictReader(l for l in open(d + "/bending.csv") if not l.startswith("#")))
except OSError:
    print(f"{name:<28} (no bending.csv)"); sys.exit(0)
ang = {round(float(r["pressure_kpa"])): float(r["bending_angle"]) for r in rows}
s = open(d + "/summary.ini").read()
def g(k):
    m = re.search(r"^%s = ([^ ;\n]+)" % k, s, re.M)
    return m.group(1) if m else "-"
log = open(d + "/softact.log").read()
m = re.search(r"(\d+) free dofs", log)
dofs = m.group(1) if m else "-"
m = re.search(r"Newton: \d+ assemblies", log)
nit = sum(int(r["newton_iterations"]) for r in rows)
print(f"{name:<28} {dofs:>9} " + " ".join(f"{ang.get(p, float('nan')):8.4f}" for p in (30, 60, 90, 120))
      + f" {g('factorisations'):>6} {nit:>6} {g('wall_s'):>8}")
PY
done
