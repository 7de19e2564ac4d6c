#!/usr/bin/env python3
"""The granular actuator with a Mohr-Coulomb continuum fill (cases/granular_bending_mc.ini,
docs/mohr_coulomb.md "The actuator scene") on a very coarse mesh with a short stroke, checked
against references the scene does not use to compute its state:

- force balance of the fill body, from the contact forces alone: the piston, the barrel and the
  cavity (wall + floor) forces on the fill and its weight sum to zero in z, relative to the sum
  of the piston force, the weight and the contact normal forces. The solver balances nodal
  forces to rtol = 1e-5 of the internal-force norm of the whole model, so the bound is 1e-3
  (measured: 1e-9 to 1e-8, docs/mohr_coulomb.md);
- volume balance: the fill occupies the bore, so its volume change (its surface integral, i.e.
  its elastic + plastic volumetric strain) equals the cavity's volume change minus the displaced
  volume A d plus the change of the penalty overlap volume. The overlap is a nodal sum at the
  slave nodes (the silicone's nodes pressing into the fill's faces are not counted), which at
  this 20 um stroke leaves 32-33 % of A d unexplained (measured 2026-12-01); over 0.5 and 1 mm
  on the 3 mm mesh it closes to 4.1 and 3.0 % (docs/mohr_coulomb.md). Bound 0.5 here: a weak
  check that catches a sign or bookkeeping error, not the quadrature;
- the bending angle grows with the stroke (the strain-limiting layer bends the cavity toward -x)
  and the piston force is positive and grows;
- the run never loads LIGGGHTS or MPI (LD_DEBUG=files, as tests/apps/test_no_liggghts.sh).
"""
import csv, os, subprocess, sys, tempfile

exe, case = sys.argv[1], sys.argv[2]
# tet4, no rings, silicone h 6 mm, fill h 4 mm; the geostatic stage (the fill has no stiffness
# at zero confinement: without gravity the first push inverts its top elements) and 20 um of
# stroke in two steps
SETS = ["mesh.order=1", "mesh.rings=0", "mesh.h=6e-3", "mc_bending.fill_h=4e-3",
        "mc_bending.penalty=1", "mc_bending.stroke=2e-5", "mc_bending.n_steps=2", "mc_bending.vtk_every=0",
        "solver.rtol=1e-5", "run.threads=1", "run.plots=0"]

def rows(path):
    with open(path) as f:
        lines = [l for l in f if not l.startswith("#")]
    r = list(csv.DictReader(lines))
    return [{k: float(v) for k, v in d.items()} for d in r]

fails = []
with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "r")
    args = [exe, "run", case, "--out", out, "--quiet"] + sum([["--set", s] for s in SETS], [])
    env = dict(os.environ, LD_DEBUG="files")
    r = subprocess.run(args, capture_output=True, text=True, timeout=300, env=env)
    ld = [l for l in r.stderr.splitlines() if "file=" in l.lower()]
    bad = [l for l in ld if "liggghts" in l.lower() or "libmpi" in l.lower()]
    if bad:
        fails.append("the continuum scene loaded LIGGGHTS/MPI: " + bad[0])
    if r.returncode != 0:
        err = [l for l in r.stderr.splitlines() if "file=" not in l and "calling" not in l]
        fails.append(f"exit {r.returncode}: " + "\n".join(err[-8:]))
    else:
        t = rows(os.path.join(out, "bending.csv"))
        if len(t) < 3:
            fails.append(f"{len(t)} rows in bending.csv, expected 3 (settled + 2 steps)")
        for d in t[1:]:
            if abs(d["force_balance_error"]) > 1e-3:
                fails.append(f"force balance at {d['piston_displacement']:.3g} m: "
                             f"{d['force_balance_error']:.3g} (bound 1e-3)")
            if abs(d["volume_balance_error"]) > 0.5:
                fails.append(f"volume balance at {d['piston_displacement']:.3g} m: "
                             f"{d['volume_balance_error']:.3g} (bound 0.5)")
        ang = [d["bending_angle"] for d in t]
        frc = [d["piston_force"] for d in t]
        if not all(b > a for a, b in zip(ang, ang[1:])):
            fails.append(f"bending angle does not grow with the stroke: {ang}")
        if not (frc[-1] > 0 and all(b > a for a, b in zip(frc[1:], frc[2:]))):
            fails.append(f"piston force not positive and growing: {frc}")
        for fn in ("summary.ini", "fem.vtk.series", "case.ini"):
            if not os.path.exists(os.path.join(out, fn)):
                fails.append(f"{fn} missing")
        if os.environ.get("SA_TEST_VERBOSE"):
            for d in t:
                print({k: d[k] for k in ("piston_displacement", "bending_angle", "piston_force",
                                         "force_balance_error", "volume_balance_error",
                                         "newton_iterations", "time")})
for f in fails:
    print(f)
sys.exit(1 if fails else 0)
