#!/usr/bin/env python3
"""The pressure scene (cases/pressure_bending.ini) on the swept mesh ([mesh] kind = swept,
fem/fem_mesh_swept.c) against the converged bending angle of the reference actuator with rings
at 30 kPa, 16.82 deg (docs/fem_time_to_accuracy.md: Richardson extrapolation of a refinement
series of the Gmsh meshes, an independent family of meshes, with an uncertainty of about
+-0.5 %).

The swept mesh at h 4 mm with the rings' corners at 0.5 mm (135k dofs) measured -1.13 % at
30 kPa (stop 41, docs/fem_time_to_accuracy.md "Swept meshes"); the bound is 2 %: the estimate's
+-0.5 % plus this mesh's discretisation error, which the h and ring series there bound by
~1.5 % at 30 kPa. The default Gmsh mesh of similar cost (4/2/2 mm, 71k dofs) is 6.6 % low, so
a swept mesh that lost its ring-aligned grid (or its band or rings) fails this test. Also: the
cavity volume grows (the pressure does work), and the ramp needed no LU factorisation (a
symmetric tangent: a mesh with a crack or an inconsistent mid-node makes the follower pressure's
stiffness unsymmetric and the solver falls back to LU, as the first swept mesh did).
"""
import csv, os, re, subprocess, sys, tempfile

exe, case = sys.argv[1], sys.argv[2]
REF, TOL = 16.82, 0.02
SETS = ["mesh.kind=swept", "mesh.h=4e-3", "mesh.h_band=2e-3", "mesh.h_ring=0.5e-3",
        "mesh.grade=1.5", "loading.p_max=30e3", "loading.n_steps=1", "output.vtk_every=0",
        "run.plots=0"]
fails = []
with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "r")
    cmd = [exe, "run", case, "--out", out, "--quiet"] + sum([["--set", s] for s in SETS], [])
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-3000:])
        sys.exit(f"run failed: exit {r.returncode}")
    with open(os.path.join(out, "bending.csv")) as f:
        rows = list(csv.DictReader(l for l in f if not l.startswith("#")))
    last = rows[-1]
    p, ang, dv = float(last["pressure_kpa"]), float(last["bending_angle"]), float(last["volume_change_rel"])
    err = ang / REF - 1
    print(f"swept h 4 mm: {ang:.4f} deg at {p:.1f} kPa, {100 * err:+.2f} % against {REF} "
          f"(bound {100 * TOL:.0f} %), cavity volume {100 * dv:+.2f} %")
    if abs(p - 30) > 1e-9:
        fails.append(f"last row at {p} kPa, expected 30")
    if not abs(err) <= TOL:
        fails.append(f"angle {ang:.4f} deg is {100 * err:+.2f} % from the converged {REF} deg")
    if not dv > 0:
        fails.append(f"cavity volume change {dv} not positive")
    s = open(os.path.join(out, "softact.log")).read()
    m = re.search(r"factorisations \((\d+) Cholesky, (\d+) LU\)", s)
    if not m or int(m.group(2)) != 0:
        fails.append("the ramp used LU factorisations (tangent not symmetric): " + (m.group(0) if m else "no count"))
if fails:
    print("\n".join(fails))
    sys.exit(1)
print("ok")
