#!/usr/bin/env python3
"""Refinement series of the reference actuator with rings (issue 14; docs/fem_time_to_accuracy.md).

Runs bench/fem/fem_ramp (0 -> 120 kPa in 30 kPa output steps) on meshes h/h_band/h_ring =
h/(h/2)/(h/2), collects the bending angle at 30, 60, 90, 120 kPa and estimates the
mesh-converged angle by Richardson extrapolation from the three finest meshes, a_i = a + C h_i^p
with the observed order p fitted at each pressure (any ratios between the meshes). Prints a Markdown table
with every mesh's relative error against the extrapolated angle.

  refine.py FEM_RAMP [--meshes 6,4,3] [--from DIR] [solver keys...]
Mesh entries are h in mm with h_band = h_ring = h/2, or h:h_band:h_ring in mm (e.g.
2:2:2,1.5:1.5:1.5,1:1:1, or the ring series 2:2:2,2:2:1,2:2:0.5); the Richardson fit of the
three last meshes uses the size that varies most among them. --from DIR reads DIR/<h>_<hb>_<hr>.out
(or DIR/<h>.out for the h/2 family) of earlier runs instead of running. Each run's full output
is kept in DIR (default refine_out)."""
import math, os, subprocess, sys

args = sys.argv[1:]
exe = args.pop(0)
meshes, outdir, keys = [(6.0, 3.0, 3.0), (4.0, 2.0, 2.0), (3.0, 1.5, 1.5)], "refine_out", []
reuse = False
while args:
    a = args.pop(0)
    if a == "--meshes": meshes = [tuple(float(y) for y in x.split(":")) if ":" in x else
                                  (float(x), 0.5 * float(x), 0.5 * float(x))
                                  for x in args.pop(0).split(",")]
    elif a == "--from": outdir = args.pop(0); reuse = True
    else: keys.append(a)
os.makedirs(outdir, exist_ok=True)
res = {}
for m in meshes:
    h, hb, hr = m
    path = os.path.join(outdir, f"{h:g}_{hb:g}_{hr:g}.out")
    if reuse and not os.path.exists(path):
        path = os.path.join(outdir, f"{h:g}.out")
    if not reuse:
        cmd = [exe, f"h={h * 1e-3:.6g}", f"hb={hb * 1e-3:.6g}", f"hr={hr * 1e-3:.6g}", "n_out=4",
               "ref=0"] + keys
        with open(path, "w") as f:
            subprocess.run(cmd, stdout=f, stderr=subprocess.DEVNULL, check=False)
    kv = {}
    for line in open(path):
        if " = " in line:
            k, v = line.split(" = ", 1)
            kv[k.strip()] = v.split()[0]
    res[m] = kv
P = [30, 60, 90, 120]
ext, order = {}, {}
fam = meshes[-3:]
# the Richardson size: the component (h, h_band or h_ring) that varies most over the family
k = max(range(3), key=lambda c: max(m[c] for m in fam) / min(m[c] for m in fam))
hs = [m[k] for m in fam]
a = [[float(res[m].get(f"angle_{p}", "nan")) for p in P] for m in fam]


def fit(a1, a2, a3):
    """a_i = a + C h_i^p through three meshes (any ratios): p by bisection on
    (a1 - a2)/(a2 - a3) = (h1^p - h2^p)/(h2^p - h3^p); returns (a, p)."""
    q = (a1 - a2) / (a2 - a3)
    g = lambda p: (hs[0] ** p - hs[1] ** p) / (hs[1] ** p - hs[2] ** p) - q
    lo, hi = 0.05, 8.0
    if not q > 0 or g(lo) * g(hi) > 0:
        return float("nan"), float("nan")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0: hi = mid
        else: lo = mid
    p = 0.5 * (lo + hi)
    C = (a2 - a3) / (hs[1] ** p - hs[2] ** p)
    return a3 - C * hs[2] ** p, p


for j, p in enumerate(P):
    ext[p], order[p] = fit(a[0][j], a[1][j], a[2][j])
print("| mesh h/h_band/h_ring [mm] | free dofs | " + " | ".join(f"{p} kPa [deg] (err)" for p in P)
      + " | wall [s] | cpu [s] | factorisations |")
print("|---" * (len(P) + 5) + "|")
for m in meshes:
    kv = res[m]
    cells = []
    for p in P:
        v = float(kv.get(f"angle_{p}", "nan"))
        cells.append(f"{v:.4f} ({100 * (v - ext[p]) / ext[p]:+.2f} %)")
    print(f"| {m[0]:g}/{m[1]:g}/{m[2]:g} | {kv.get('nfree')} | " + " | ".join(cells) +
          f" | {kv.get('wall')} | {kv.get('cpu')} | {kv.get('factorisations')} |")
print("| Richardson | | " + " | ".join(f"{ext[p]:.4f} (p = {order[p]:.2f})" for p in P) + " | | | |")
