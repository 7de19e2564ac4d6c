#!/usr/bin/env python3
"""The comparison scene ([compare], core/sa_compare.c) on synthetic results folders whose answer
is known in closed form, and its refusal of bad input (exit 1, message naming the key and the
file, nothing written).

Synthetic runs (bore radius r = 6 mm, A = pi r^2):
  dem       x = 0, 1, 2, 3 mm; angle 0.5, 1.0, 2.0, 2.5 deg; force 0, 10, 20, 30 N
  mc        x = 0, 1.5, 4 mm;  angle 0, 3, 5 deg;           force 0, 15, 40 N
  pressure  volume change V = 0, 1, 2, 3 x 1e-7 m^3; angle = 2e7 V deg (linear in V);
            p = 1e11 V Pa
so the pressure baseline at displacement x is angle 2e7 A x, force 1e11 A^2 x, for
x <= 3e-7 / A = 2.6526 mm, and the piecewise-linear granular curves give the values below.
Differences are compared with |a - b| <= 1e-12 + 1e-12 |b| (the table holds 17 digits; the
interpolation is a few flops).

Runs on different silicone meshes (the [mesh] order / h / h_band / h_ring / rings of the case.ini
softact writes into a results folder) are flagged: a warning and `meshes = differ` in summary.ini
(tet4 and tet10 silicones are different actuators: tet4 locks, docs/compare.md)."""
import math, os, subprocess, sys, tempfile

exe = sys.argv[1]
A = math.pi * 6e-3 ** 2
fails = []


def check(what, got, want, tol=1e-12):
    if want is None:
        if got is not None:
            fails.append(f"{what}: expected no value, got {got!r}")
    elif got is None or abs(got - want) > tol + tol * abs(want):
        fails.append(f"{what}: got {got!r}, expected {want!r}")


def write_csv(path, names, units, rows):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("# units: " + ", ".join(f"{n}={u}" for n, u in zip(names, units)) + "\n")
        f.write(",".join(names) + "\n")
        for r in rows:
            f.write(",".join(repr(float(v)) for v in r) + "\n")


def granular(path, xs_mm, angles, forces, drop=None, units=None, r=6e-3):
    names = ["piston_displacement", "bending_angle", "piston_force", "displaced_volume",
             "volume_change_rel"]
    u = units or ["m", "deg", "N", "m^3", "-"]
    rows = [[x * 1e-3, a, f, math.pi * r * r * x * 1e-3, 1e-3 * x] for x, a, f in
            zip(xs_mm, angles, forces)]
    if drop:
        k = names.index(drop)
        names, u = names[:k] + names[k + 1:], u[:k] + u[k + 1:]
        rows = [row[:k] + row[k + 1:] for row in rows]
    write_csv(os.path.join(path, "bending.csv"), names, u, rows)


def pressure(path, volumes):
    names = ["step", "pressure", "pressure_kpa", "bending_angle", "cavity_volume",
             "volume_change", "volume_change_rel", "tip_dx", "tip_dz", "newton_iterations"]
    units = ["-", "Pa", "kPa", "deg", "m^3", "m^3", "-", "m", "m", "-"]
    V0 = 9e-6
    rows = [[i, 1e11 * v, 1e8 * v, 2e7 * v, V0 + v, v, v / V0, 0, 0, 3]
            for i, v in enumerate(volumes)]
    write_csv(os.path.join(path, "bending.csv"), names, units, rows)


def read_table(path):
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f]
    assert lines[0].startswith("# units:"), lines[0]
    names = lines[1].split(",")
    rows = []
    for l in lines[2:]:
        rows.append({n: (float(v) if v != "" else None) for n, v in zip(names, l.split(","))})
    return names, rows


def run(tmp, name, compare, sets=(), command="run"):
    case = os.path.join(tmp, name + ".ini")
    with open(case, "w") as f:
        f.write("[run]\nplots = false\n\n[compare]\n" + compare)
    out = os.path.join(tmp, "out_" + name)
    args = [exe, command, case, "--out", out, "--quiet"]
    for s in sets:
        args += ["--set", s]
    r = subprocess.run(args, capture_output=True, text=True, errors="replace", timeout=60)
    return r, out


with tempfile.TemporaryDirectory() as tmp:
    granular(os.path.join(tmp, "dem"), [0, 1, 2, 3], [0.5, 1.0, 2.0, 2.5], [0, 10, 20, 30])
    granular(os.path.join(tmp, "mc"), [0, 1.5, 4], [0, 3, 5], [0, 15, 40])
    pressure(os.path.join(tmp, "pressure"), [0, 1e-7, 2e-7, 3e-7])

    # --- the closed-form answer; folders relative to the case file's folder ---
    r, out = run(tmp, "good", "dem = dem\nmc = mc\npressure = pressure\n")
    if r.returncode != 0:
        fails.append(f"good: exit {r.returncode}: {r.stderr[:600]}")
    else:
        names, rows = read_table(os.path.join(out, "comparison.csv"))
        x_end = 3e-7 / A  # the pressure run's reach [m]
        # every sample of every curve where at least two exist: 4 mm (MC alone) is left out
        want_x = sorted([0, 1e-3, 2e-3, 3e-3, 1.5e-3, 1e-7 / A, 2e-7 / A, x_end])
        if len(rows) != len(want_x):
            fails.append(f"good: {len(rows)} table rows, expected {len(want_x)}: "
                         f"{[r['piston_displacement'] for r in rows]}")
        else:
            for row, x in zip(rows, want_x):
                check(f"x {x}", row["piston_displacement"], x)

        def dem(xmm):  # piecewise linear through (0,0.5) (1,1) (2,2) (3,2.5)
            return 0.5 + 0.5 * xmm if xmm <= 1 else (xmm if xmm <= 2 else 2 + 0.5 * (xmm - 2))

        def mc(xmm):  # through (0,0) (1.5,3) (4,5)
            return 2 * xmm if xmm <= 1.5 else 3 + 0.8 * (xmm - 1.5)

        for row in rows:
            x = row["piston_displacement"]
            xmm = 1e3 * x
            tag = f"x = {xmm:.4f} mm"
            p = 2e7 * A * x if x <= x_end * (1 + 1e-12) else None
            check(tag + " angle_dem", row["angle_dem"], dem(xmm))
            check(tag + " angle_mc", row["angle_mc"], mc(xmm))
            check(tag + " angle_pressure", row["angle_pressure"], p)
            check(tag + " mc_minus_dem", row["mc_minus_dem"], mc(xmm) - dem(xmm))
            check(tag + " mc_minus_dem_rel", row["mc_minus_dem_rel"], (mc(xmm) - dem(xmm)) / dem(xmm))
            check(tag + " pressure_minus_dem", row["pressure_minus_dem"], None if p is None else p - dem(xmm))
            check(tag + " pressure_minus_mc_rel", row["pressure_minus_mc_rel"],
                  None if p is None or mc(xmm) == 0 else (p - mc(xmm)) / mc(xmm))
            check(tag + " force_pressure", row["force_pressure"], None if p is None else 1e11 * A * A * x)
            check(tag + " pressure", row["pressure"], None if p is None else 1e11 * A * x)
            check(tag + " displaced_volume", row["displaced_volume"], A * x)
        # by hand at 1.5 mm: DEM 1.5, MC 3, pressure 2e7 A 1.5e-3 = 3.3929 deg
        at = [r for r in rows if abs(r["piston_displacement"] - 1.5e-3) < 1e-15]
        if at:
            check("1.5 mm by hand: pressure", at[0]["angle_pressure"], 3.392920065876977, 1e-12)
            check("1.5 mm by hand: mc - dem", at[0]["mc_minus_dem"], 1.5)
        # by hand at 3 mm: DEM 2.5, MC 3 + 0.8 x 1.5 = 4.2, relative (4.2 - 2.5) / 2.5 = 0.68
        at = [r for r in rows if abs(r["piston_displacement"] - 3e-3) < 1e-15]
        if at:
            check("3 mm by hand: mc_minus_dem_rel", at[0]["mc_minus_dem_rel"], 0.68)
        summary = open(os.path.join(out, "summary.ini")).read()
        for needle in ["pressure_baseline = ends before", "[mc_minus_dem]", "[pressure_minus_dem]",
                       "table_rows = 8"]:
            if needle not in summary:
                fails.append(f"good: summary.ini lacks {needle!r}")
        if "pressure baseline ends at 2.653 mm" not in r.stderr:
            fails.append(f"good: no warning that the pressure baseline ends: {r.stderr[:400]}")
        for f in ["curve_dem.csv", "curve_mc.csv", "curve_pressure.csv", "case.ini", "softact.log"]:
            if not os.path.exists(os.path.join(out, f)):
                fails.append(f"good: {f} not written")

    # --- runs on different silicone meshes are flagged (their [mesh] in case.ini) ---
    def mesh_case(path, order, rings):
        with open(os.path.join(path, "case.ini"), "w") as f:
            f.write(f"[mesh]\ngeo = x.geo ; [-] source\nh = 0.004   ; [m] size\nh_band = 0.002\n"
                    f"h_ring = 0.002\norder = {order}   ; [-] element order\nrings = {rings}\n")
    for name, order, rings in (("dem_m", 2, 1), ("mc_m", 1, 0), ("mc_same", 2, 1)):
        src = "dem" if name == "dem_m" else "mc"
        granular(os.path.join(tmp, name), *( ([0, 1, 2, 3], [0.5, 1.0, 2.0, 2.5], [0, 10, 20, 30])
                                             if src == "dem" else ([0, 1.5, 4], [0, 3, 5], [0, 15, 40])))
        mesh_case(os.path.join(tmp, name), order, rings)
    for name, mc, want in (("mesh_differ", "mc_m", "differ"), ("mesh_same", "mc_same", "same")):
        r, out = run(tmp, name, f"dem = dem_m\nmc = {mc}\n")
        if r.returncode != 0:
            fails.append(f"{name}: exit {r.returncode}: {r.stderr[:600]}")
            continue
        summary = open(os.path.join(out, "summary.ini")).read()
        if f"meshes = {want} ;" not in summary:
            fails.append(f"{name}: summary.ini lacks 'meshes = {want}'")
        warned = "silicone meshes differ" in r.stderr
        if warned != (want == "differ"):
            fails.append(f"{name}: warning about the meshes {'missing' if not warned else 'given'}: "
                         f"{r.stderr[:400]}")
        if want == "differ" and "mc: tet4, h 0.004 m, h_band 0.002 m, h_ring 0.002 m, rings 0" not in summary:
            fails.append(f"{name}: the MC run's mesh is not described: {summary[:600]}")

    # --- two inputs suffice; the pressure curve is clipped at the DEM's end (3 mm) ---
    pressure(os.path.join(tmp, "pressure_long"), [0, 2e-7, 4e-7, 6e-7])
    r, out = run(tmp, "two", "dem = dem\npressure = " + os.path.join(tmp, "pressure_long") + "\n")
    if r.returncode != 0:
        fails.append(f"two: exit {r.returncode}: {r.stderr[:600]}")
    else:
        names, rows = read_table(os.path.join(out, "curve_pressure.csv"))
        last = rows[-1]
        check("two: pressure curve ends at the DEM's 3 mm", last["piston_displacement_mm"], 3.0)
        check("two: its angle there", last["bending_angle"], 2e7 * A * 3e-3)
        check("two: marked as interpolated (run_state 0)", last["run_state"], 0.0)
        check("two: the states before it are the run's", rows[-2]["run_state"], 1.0)
        names, rows = read_table(os.path.join(out, "comparison.csv"))
        if any(r["angle_mc"] is not None for r in rows):
            fails.append("two: MC column not empty without an mc input")

    # --- bad input: exit 1, the key and the file named, nothing written ---
    granular(os.path.join(tmp, "dem_noangle"), [0, 1], [0, 1], [0, 1], drop="bending_angle")
    granular(os.path.join(tmp, "dem_mm"), [0, 1], [0, 1], [0, 1], units=["mm", "deg", "N", "m^3", "-"])
    granular(os.path.join(tmp, "dem_r5"), [0, 1], [0, 1], [0, 1], r=5e-3)
    pressure(os.path.join(tmp, "pressure_back"), [0, 2e-7, 1e-7])
    os.makedirs(os.path.join(tmp, "empty_folder"))
    bad = [
        ("missing_folder", "dem = no_such_run\nmc = mc\n", ["[compare] dem", "no_such_run", "does not exist"]),
        ("missing_column", "dem = dem_noangle\nmc = mc\n",
         ["[compare] dem", os.path.join("dem_noangle", "bending.csv"), "no column 'bending_angle'"]),
        ("one_input", "dem = dem\n", ["[compare]", "at least two of dem, mc, pressure"]),
        ("no_input", "", ["at least two"]),
        ("no_bending_csv", "mc = mc\npressure = empty_folder\n", ["[compare] pressure", "empty_folder", "no bending.csv"]),
        ("wrong_unit", "dem = dem_mm\nmc = mc\n", ["[compare] dem", "piston_displacement", "'mm', expected 'm'"]),
        ("bore_mismatch", "dem = dem_r5\nmc = mc\n", ["[compare] dem", "dem_r5", "bore_radius"]),
        ("volume_not_monotone", "dem = dem\npressure = pressure_back\n",
         ["[compare] pressure", "pressure_back", "increase strictly"]),
    ]
    for name, text, needles in bad:
        r, out = run(tmp, name, text)
        if r.returncode != 1:
            fails.append(f"{name}: exit {r.returncode}, expected 1; stderr: {r.stderr[:400]}")
        for n in needles:
            if n not in r.stderr:
                fails.append(f"{name}: message lacks {n!r}: {r.stderr[:400]}")
        if os.path.exists(out):
            fails.append(f"{name}: {out} was written: {os.listdir(out)}")

    # `softact check` accepts folders that do not exist yet (the committed case is checked
    # before any run was made) and says so
    r, out = run(tmp, "check_missing", "dem = no_such_run\nmc = mc\n", command="check")
    if r.returncode != 0 or "does not exist (yet)" not in r.stderr:
        fails.append(f"check_missing: exit {r.returncode}, stderr: {r.stderr[:400]}")

for f in fails:
    print(f)
sys.exit(1 if fails else 0)
