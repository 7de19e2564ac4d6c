#!/usr/bin/env python3
"""FEM-DEM studies (issue 12): run the granular scene with variants, one after the other, and
collect their bending curves into one table and one plot.

  bench/dem/study.py OUTDIR LABEL:key=value,key=value [LABEL:...] [--case CASE] [--exe EXE]
                     [--collect-only] [--marks 0,5,10,15,20,25] [--relative]

Each variant runs `softact run CASE --out OUTDIR/LABEL --set key=value ...` unless
OUTDIR/LABEL/summary.ini already exists (a study can be interrupted and continued; a stopped
run counts: its summary says how far it got). Writes OUTDIR/study.md (a Markdown table: status,
stroke reached, angle and piston force at every 5 mm, timing split) and OUTDIR/angle.png,
OUTDIR/force.png (every variant on one plot, gnuplot; --relative plots the bend from each bed's
rest angle, angle - angle(0), for beds that rest at different angles). Runs are sequential: on a 2-core machine
parallel runs only distort each other's timings."""
import os, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_io import read_summary, read_curve

def at(rows, s, key):
    best = min(rows, key=lambda r: abs(r["piston_displacement"] - s)) if rows else None
    if not best or abs(best["piston_displacement"] - s) > 0.2e-3:
        return ""
    return f"{best[key]:.2f}"

def main():
    args = sys.argv[1:]
    case, exe, collect = "cases/granular_bending_dem.ini", "build/apps/softact", False
    if "--case" in args:
        i = args.index("--case"); case = args[i + 1]; del args[i:i + 2]
    if "--exe" in args:
        i = args.index("--exe"); exe = args[i + 1]; del args[i:i + 2]
    marks = [0, 5, 10, 15, 20, 25]
    if "--marks" in args:
        i = args.index("--marks"); marks = [float(x) for x in args[i + 1].split(",")]; del args[i:i + 2]
    relative = "--relative" in args
    if relative:
        args.remove("--relative")
    if "--collect-only" in args:
        args.remove("--collect-only"); collect = True
    if len(args) < 2:
        sys.exit(__doc__)
    outdir, variants = args[0], []
    for v in args[1:]:
        label, _, sets = v.partition(":")
        variants.append((label, [s for s in sets.split(",") if s]))
    os.makedirs(outdir, exist_ok=True)
    for label, sets in variants:
        d = os.path.join(outdir, label)
        if collect or os.path.exists(os.path.join(d, "summary.ini")):
            continue
        cmd = [exe, "run", case, "--out", d]
        for s in sets:
            cmd += ["--set", s]
        print("study:", " ".join(cmd), file=sys.stderr, flush=True)
        subprocess.run(cmd)
    md = ["| variant | settings | status | stroke [mm] | "
          + " | ".join(f"angle@{m:g}" for m in marks) + " | "
          + " | ".join(f"F@{m:g} [N]" for m in marks)
          + " | overlap | I_max | wall [s] | DEM [s] | exch/DEM | FEM/DEM |",
          "|" + "---|" * (10 + 2 * len(marks))]
    plots = []
    for label, sets in variants:
        d = os.path.join(outdir, label)
        sp, cp = os.path.join(d, "summary.ini"), os.path.join(d, "bending.csv")
        if not os.path.exists(sp) or not os.path.exists(cp):
            md.append(f"| {label} | {' '.join(sets)} | not run |" + " |" * (7 + 2 * len(marks)))
            continue
        s, rows = read_summary(sp), read_curve(cp)
        g = lambda k: s.get(k, "")
        md.append(f"| {label} | {' '.join(sets)} | {g('result.status')} | "
                  f"{float(g('result.piston_displacement') or 0) * 1e3:.1f} | "
                  + " | ".join(at(rows, m * 1e-3, "bending_angle") for m in marks) + " | "
                  + " | ".join(at(rows, m * 1e-3, "piston_force") for m in marks)
                  + f" | {g('result.max_overlap')} | {g('result.inertial_number_max')} | "
                  f"{float(g('timing.wall') or 0):.0f} | {float(g('timing.dem') or 0):.0f} | "
                  f"{g('timing.exchange_over_dem')} | {g('timing.fem_over_dem')} |")
        plots.append((cp, label))
    open(os.path.join(outdir, "study.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))
    for col, name, ylabel in ((2, "angle", "bending angle [deg]"), (3, "force", "piston force [N]")):
        body = ["set terminal pngcairo size 900,600", f"set output '{outdir}/{name}.png'",
                "set datafile separator ','", "set grid", "set key top left",
                "set xlabel 'piston displacement [mm]'", f"set ylabel '{ylabel}'"]
        def y(p):
            if col != 2 or not relative:
                return f"{col}"
            a0 = read_curve(p)[0]["bending_angle"]
            return f"(${col}-{a0:.9g})"
        if relative and col == 2:
            body[-1] = "set ylabel 'bend from the rest angle [deg]'"
        body.append("plot " + ", ".join(f"'{p}' skip 2 using ($1*1e3):{y(p)} with linespoints lw 2 "
                                        f"title '{l}'" for p, l in plots))
        if plots:
            subprocess.run(["gnuplot"], input="\n".join(body) + "\n", text=True)

main()
