#!/usr/bin/env python3
"""Strip footing scene (cases/mc_footing.ini) on a coarse mesh against Prandtl's N_c, and its bad
input.

Reference (independent of the code): N_c = (N_q - 1) cot phi, N_q = e^(pi tan phi) tan^2(45 deg +
phi/2), 2 + pi at phi = 0, computed here.
Tolerances come from the measured convergence (docs/mohr_coulomb.md, bench/fem/
mc_footing_convergence.sh): displacement-based tet10 limit loads lie ABOVE N_c and approach it
slowly (volumetric locking under isochoric / dilatant plastic flow). On the coarse CI meshes
(cells = 2, 1 to 3 s each) the measured excess is given per case below (commit of the mesh
with matched edge cells, 2026-12-01; it falls monotonically with refinement, e.g. 12.1, 8.3,
6.9 % at cells 2, 3, 4 for phi = 0); the test asks for
  N_c (1 - 0.01) <= factor <= N_c (1 + measured excess + 0.03),
i.e. the upper-bound side (1 % allowance for the finite settlement not reaching the plateau)
and no more than 3 points of excess beyond what was measured, so a regression in the element,
the law or the reaction read-back shows while the known locking error does not fail the test.
It also checks that the summary's prandtl_N_c is the closed form (1e-8)."""
import math, os, subprocess, sys, tempfile

exe, case = sys.argv[1], sys.argv[2]

def summary(path):
    d = {}
    for line in open(path):
        line = line.split(";")[0].strip()
        if "=" in line:
            k, v = (s.strip() for s in line.split("=", 1))
            d[k] = v
    return d

def prandtl(phi):
    if phi == 0:
        return 2 + math.pi
    p = math.radians(phi)
    nq = math.exp(math.pi * math.tan(p)) * math.tan(math.pi / 4 + p / 2) ** 2
    return (nq - 1) / math.tan(p)

# phi [deg], cells, measured excess over N_c on that mesh (docs/mohr_coulomb.md)
CASES = [(0, 2, 0.121), (20, 2, 0.111)]
BAD = [
    ("zero_cohesion", ["fill.cohesion=0", "fill.friction_angle=20", "fill.dilation_angle=20"], ["cohesion", "expected cohesion > 0"]),
    ("narrow_domain", ["footing.domain_width=0.4"], ["domain_width", "0.5"]),
    ("negative_settlement", ["footing.settlement=-0.01"], ["settlement", "expected a real number in"]),
]

fails = []
with tempfile.TemporaryDirectory() as tmp:
    for phi, n, excess in CASES:
        name = f"phi{phi}_n{n}"
        out = os.path.join(tmp, name)
        args = [exe, "run", case, "--out", out, "--quiet", "--set", f"footing.cells={n}",
                "--set", f"fill.friction_angle={phi}", "--set", f"fill.dilation_angle={phi}",
                "--set", "run.threads=1"]
        r = subprocess.run(args, capture_output=True, text=True, timeout=300)
        if r.returncode != 0:
            fails.append(f"{name}: exit {r.returncode}: {r.stderr[-400:]}")
            continue
        s = summary(os.path.join(out, "summary.ini"))
        nc = prandtl(phi)
        f = float(s["bearing_capacity_factor"])
        if abs(float(s["prandtl_N_c"]) - nc) > 1e-8 * nc:
            fails.append(f"{name}: prandtl_N_c {s['prandtl_N_c']} vs {nc:.9g}")
        lo, hi = nc * (1 - 0.01), nc * (1 + excess + 0.03)
        if not lo <= f <= hi:
            fails.append(f"{name}: bearing_capacity_factor {f:.5g} outside [{lo:.5g}, {hi:.5g}] "
                         f"(Prandtl {nc:.5g}, {100 * (f / nc - 1):+.1f} %)")
        if os.environ.get("SA_TEST_VERBOSE"):
            print(f"{name}: factor {f:.5g}, Prandtl {nc:.5g} ({100 * (f / nc - 1):+.2f} %), "
                  f"wall {s.get('wall_s')} s")
        for fn in ("footing.csv", "footing.vtk.series"):
            if not os.path.exists(os.path.join(out, fn)):
                fails.append(f"{name}: {fn} missing")
    for name, sets, needles in BAD:
        out = os.path.join(tmp, "bad_" + name)
        args = [exe, "run", case, "--out", out, "--quiet"] + sum([["--set", s] for s in sets], [])
        r = subprocess.run(args, capture_output=True, text=True, timeout=60)
        if r.returncode != 1:
            fails.append(f"{name}: exit {r.returncode}, expected 1: {r.stderr[:300]}")
        for nd in needles:
            if nd not in r.stderr:
                fails.append(f"{name}: message lacks {nd!r}: {r.stderr[:300]}")
        if os.path.exists(out) and os.listdir(out):
            fails.append(f"{name}: results folder has content: {os.listdir(out)}")
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
