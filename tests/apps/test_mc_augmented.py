#!/usr/bin/env python3
"""The Mohr-Coulomb actuator scene with the augmented Lagrangian ([mc_bending] augment): its
answer must not depend on the contact penalty (docs/contact.md, "Augmented Lagrangian"),
frictionless and (since 2026-12-06, tangential multipliers and path-consistent updates) with
the scene's friction.

Reference: the exact-contact limit, which penalty-only contact reaches only as the penalty grows
without bound. The fill is frictionless here, so that limit is unique: with friction the stick
state keeps the tangential penalty's elastic slip, which the normal augmentation does not
remove (measured on this mesh at 25 um: 12-35 % apart between penalties 1 and 0.3 with friction,
docs/contact.md). On the CI mesh (tet4, no rings, silicone h 6 mm, fill h 4 mm), 25 um in one
step, augmented (Uzawa updates until the overlap is below augment_tol of the displaced volume),
alpha = 1 and 0.3 must agree on the piston force, the cavity's volume change and the bending
angle's change from the settled state to 5 % (measured 1.8 / 1.3 / 3.5 %, 2026-12-02), each row
must balance its forces (1e-3, as tests/apps/test_mc_bending.py), and every step's
augmentation must converge. Penalty alone at alpha = 1 and 0.3 is far apart on the same run
(docs/contact.md).
"""
import csv, os, subprocess, sys, tempfile

exe, case = sys.argv[1], sys.argv[2]
# argv[3] "frictionless" or "friction": one pair only (two ctest tests, which run side by side)
ONLY = {"frictionless": "", "friction": "f"}.get(sys.argv[3]) if len(sys.argv) > 3 else None
BASE = ["mesh.order=1", "mesh.rings=0", "mesh.h=6e-3", "mc_bending.fill_h=4e-3",
        "mc_bending.stroke=2.5e-5", "mc_bending.n_steps=1", "mc_bending.vtk_every=0",
        "mc_bending.augment=40", "solver.rtol=1e-5", "run.threads=1", "run.plots=0",
        "fill.friction_wall=0", "fill.friction_piston=0"]


def rows(path):
    with open(path) as f:
        lines = [l for l in f if not l.startswith("#")]
    return [{k: float(v) for k, v in d.items()} for d in csv.DictReader(lines)]


def summary(path):
    d = {}
    for line in open(path):
        if "=" in line and not line.startswith(";"):
            k, v = line.split("=", 1)
            d[k.strip()] = v.split(";")[0].strip()
    return d


# With friction (the scene's wall and barrel coefficients) the tangential multipliers are
# augmented too and every augmented solve of a step is the whole step again from its start
# (solver state, stick points, plane and multipliers: one backward-Euler step, docs/contact.md).
# Measured 2026-12-06: piston force and cavity growth 0.9 / 1.8 % apart (before: 12 / 25 %),
# bound 5 %. The angle change is not a usable measure here: the settled state (frictionless,
# augmented incrementally from the first penalty-soft solve, whose plastic flow stays) differs
# by 1.9 % in angle between the penalties, 24 % of the 25 um change; so the frictional pair
# checks the angle itself at 25 um, within 2 % (measured 1.0 %: no more apart than the settled
# states).
FRICTION = [k for k in BASE if not k.startswith("fill.friction")]
BOUNDS = {"": {"force": 0.05, "dV": 0.05, "dangle": 0.05},
          "f": {"force": 0.05, "dV": 0.05, "angle": 0.02}}

fails, res = [], {}
with tempfile.TemporaryDirectory() as tmp:
    for variant, alpha in (("", "1"), ("", "0.3"), ("f", "1"), ("f", "0.3")):
        if ONLY is not None and variant != ONLY:
            continue
        out = os.path.join(tmp, variant + "a" + alpha)
        base = FRICTION if variant else BASE
        args = [exe, "run", case, "--out", out, "--quiet",
                "--set", "mc_bending.penalty=" + alpha] + sum([["--set", s] for s in base], [])
        r = subprocess.run(args, capture_output=True, text=True, timeout=600)
        label = ("with friction, " if variant else "") + "penalty " + alpha
        if r.returncode != 0:
            fails.append(f"{label}: exit {r.returncode}: " + r.stderr[-800:])
            continue
        t = rows(os.path.join(out, "bending.csv"))
        s = summary(os.path.join(out, "summary.ini"))
        if int(s.get("augment_unconverged_steps", "1")) != 0:
            fails.append(f"{label}: augmentation did not converge in a step")
        for d in t[1:]:
            if abs(d["force_balance_error"]) > 1e-3:
                fails.append(f"{label}: force balance {d['force_balance_error']:.3g}")
        res[variant + alpha] = {"force": t[-1]["piston_force"], "dV": t[-1]["volume_change_rel"],
                                "dangle": t[-1]["bending_angle"] - t[0]["bending_angle"],
                                "angle": t[-1]["bending_angle"],
                                "solves": s.get("augment_solves")}
for variant in ("", "f"):
    if variant + "1" not in res or variant + "0.3" not in res:
        continue
    a, b = res[variant + "1"], res[variant + "0.3"]
    for k, bound in BOUNDS[variant].items():
        rel = abs(a[k] - b[k]) / max(abs(a[k]), 1e-30)
        if not rel <= bound:
            fails.append(f"{'with friction, ' if variant else ''}{k}: penalty 1 gives {a[k]:.6g}, "
                         f"penalty 0.3 {b[k]:.6g} ({100 * rel:.1f} % apart, bound "
                         f"{100 * bound:.0f} %)")
    if os.environ.get("SA_TEST_VERBOSE"):
        print(res)
for f in fails:
    print(f)
sys.exit(1 if fails else 0)
