#!/usr/bin/env python3
"""Work-precision of the FEM pressure ramp (issue 14; docs/fem_time_to_accuracy.md): the error of
the bending angle against the mesh-converged reference versus the ramp's run time, for runs of
bench/fem/fem_ramp over meshes and solver settings.

  work_precision.py --ref A30,A60,A90,A120 --out BASE [--time wall|cpu] SERIES:LABEL=FILE [...]

FILE is a fem_ramp output (key = value lines, angle_30 .. angle_120, wall, cpu, nfree,
factorisations, newton_iterations). The reference angles [deg] come from the refinement series
(bench/fem/refine.py's Richardson row). The error of a run is |angle_120 - A120| / A120 (the
issue's measure) and, as a second column, the largest relative error over the four pressures.
Writes BASE.md (table) and BASE.png (log-log error against wall time, one curve per SERIES,
points labelled with LABEL, the 1 % line dashed). --time cpu plots the process CPU time instead
of the wall time (fairer when the runs shared the machine with other jobs)."""
import os, subprocess, sys, tempfile

P = [30, 60, 90, 120]


def read(path):
    kv = {}
    for line in open(path):
        if " = " in line:
            k, v = line.split(" = ", 1)
            kv[k.strip()] = v.split()[0]
    return kv


def main():
    args = sys.argv[1:]
    ref, base, runs, tkey = None, None, [], "wall"
    while args:
        a = args.pop(0)
        if a == "--ref": ref = [float(x) for x in args.pop(0).split(",")]
        elif a == "--out": base = args.pop(0)
        elif a == "--time": tkey = args.pop(0)
        else:
            name, path = a.split("=", 1)
            series, label = name.split(":", 1)
            runs.append((series, label, read(path)))
    if not ref or not base or not runs:
        sys.exit(__doc__)
    rows = []
    for series, label, kv in runs:
        if kv.get("completed") != "1":
            print(f"{series}:{label}: ramp not completed, left out", file=sys.stderr)
            continue
        ang = [float(kv[f"angle_{p}"]) for p in P]
        err = [abs(a - r) / r for a, r in zip(ang, ref)]
        rows.append((series, label, kv, ang[3], err[3], max(err)))
    with open(base + ".md", "w") as f:
        f.write("| series | run | free dofs | angle 120 kPa [deg] | error 120 kPa | largest error "
                "30-120 kPa | factorisations | Newton its | wall [s] | CPU [s] |\n")
        f.write("|---" * 10 + "|\n")
        for series, label, kv, a120, e120, emax in rows:
            f.write(f"| {series} | {label} | {kv.get('nfree')} | {a120:.4f} | {100 * e120:.2f} % | "
                    f"{100 * emax:.2f} % | {kv.get('factorisations')} | "
                    f"{kv.get('newton_iterations')} | {kv.get('wall')} | {kv.get('cpu')} |\n")
    series_names = list(dict.fromkeys(r[0] for r in rows))
    g = ["set terminal pngcairo size 900,600 font ',11'", f"set output '{base}.png'",
         "set logscale xy", f"set xlabel '{tkey} time of the 0-120 kPa ramp [s]'",
         "set ylabel 'bending-angle error at 120 kPa (vs mesh-converged)'",
         "set format y '%g'", "set key top right", "set grid", "set yrange [0.005:0.3]",
         "set title 'FEM pressure ramp with rings: error against run time'"]
    plots = []
    tmp = tempfile.mkdtemp(prefix="work_precision.")
    for i, sname in enumerate(series_names):
        dat = os.path.join(tmp, f"series_{i}.dat")
        with open(dat, "w") as f:
            for series, label, kv, a120, e120, emax in rows:
                if series == sname:
                    f.write(f"{kv.get(tkey)} {max(e120, 1e-5):.6e} \"{label}\"\n")
        plots.append(f"'{dat}' using 1:2 with linespoints pt {5 + i} ps 1.4 lw 2 title '{sname}'")
        plots.append(f"'{dat}' using 1:2:3 with labels offset 1,0.7 font ',9' notitle")
    plots.append("0.01 with lines dt 2 lc rgb 'gray40' title '1 %'")
    g.append("plot " + ", ".join(plots))
    try:
        subprocess.run(["gnuplot"], input="\n".join(g) + "\n", text=True, check=True)
    finally:
        for f in os.listdir(tmp):
            os.remove(os.path.join(tmp, f))
        os.rmdir(tmp)


if __name__ == "__main__":
    main()
