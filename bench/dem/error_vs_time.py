#!/usr/bin/env python3
"""Error against run time for the FEM-DEM scene (issue 12): for each studied parameter, the
bending angle of its variants against the parameter's finest variant (the reference), versus
the variant's run time.

  bench/dem/error_vs_time.py OUTDIR NAME=REF:LABEL,LABEL [NAME=REF:LABEL ...] [--at 0.5,1]

REF and LABEL are result folders under OUTDIR (as the bench/dem studies write them). The error
of a variant is taken on the bend the piston makes, b(x) = angle(x) - angle(0): the actuator
already hangs at ~0.45 deg under the bed's weight, the same for every variant of a bed, and that
would hide errors in the few tenths of a degree the stroke adds. It is the largest
|b - b_REF| over the displacements --at [mm], divided by the largest |b_REF| there (the row
within 0.02 mm of each mark; a variant that misses a mark is listed, not plotted). The
cost is summary.ini [timing] cpu (user + system of the process: fair on a shared machine), or
wall where an older summary has no cpu; a resumed variant's cost excludes its bed's pour.
Writes OUTDIR/error_vs_time.md (table) and OUTDIR/error_vs_time.png (log-log, one series per
parameter, the references drawn at the error floor 1e-3 with open symbols)."""
import os, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_io import read_summary, read_curve, value_at

FLOOR = 1e-3

def cost(s):
    return float(s.get("timing.cpu") or s.get("timing.wall") or 0)

def main():
    args = sys.argv[1:]
    marks = [1.0]
    if "--at" in args:
        i = args.index("--at"); marks = [float(x) for x in args[i + 1].split(",")]; del args[i:i + 2]
    if len(args) < 2:
        sys.exit(__doc__)
    outdir, groups = args[0], []
    for g in args[1:]:
        name, _, rest = g.partition("=")
        ref, _, labels = rest.partition(":")
        groups.append((name, ref, [l for l in labels.split(",") if l]))
    load = lambda l: (read_summary(os.path.join(outdir, l, "summary.ini")),
                      read_curve(os.path.join(outdir, l, "bending.csv")))
    md = ["| parameter | variant | cost [s CPU] | "
          + " | ".join(f"bend at {m:g} mm [deg]" for m in marks)
          + " | error against the reference |", "|---|---|---|" + "---|" * len(marks) + "---|"]
    def angles(label):
        """(summary, angles at the marks) of a variant, or (None, why) when it has none."""
        if not os.path.exists(os.path.join(outdir, label, "summary.ini")):
            return None, ("not run",)
        s, rows = load(label)
        a = [value_at(rows, m * 1e-3, "bending_angle") for m in [0.0] + marks]
        if any(x is None for x in a):
            return None, (f"{cost(s):.0f}", "does not reach every mark")
        return s, [x - a[0] for x in a[1:]]
    ncol = 4 + len(marks)
    row = lambda *cells: "| " + " | ".join(list(cells) + [""] * (ncol - len(cells))) + " |"
    plot = []
    for name, ref, labels in groups:
        rs, ra = angles(ref)
        if rs is None:
            md.append(row(name, f"{ref} (reference)", *ra))
            continue
        md.append(f"| {name} | {ref} (reference) | {cost(rs):.0f} | "
                  + " | ".join(f"{a:.3f}" for a in ra) + " | - |")
        pts = [(cost(rs), FLOOR, ref, 1)]
        for l in labels:
            s, a = angles(l)
            if s is None:
                md.append(row(name, l, *a))
                continue
            e = max(abs(x - r) for x, r in zip(a, ra)) / max(abs(r) for r in ra)
            md.append(f"| {name} | {l} | {cost(s):.0f} | " + " | ".join(f"{x:.3f}" for x in a)
                      + f" | {100 * e:.1f} % |")
            pts.append((cost(s), max(e, FLOOR), l, 0))
        plot.append((name, sorted(pts)))
    open(os.path.join(outdir, "error_vs_time.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md))
    series = []
    for k, (name, pts) in enumerate(plot):
        fn = f"error_vs_time_{k}.dat"
        with open(os.path.join(outdir, fn), "w") as f:
            f.write("# cpu_s error is_reference label\n")
            for c, e, l, r in pts:
                f.write(f"{c:.3f} {e:.6g} {r} {l}\n")
        series.append(f"'{fn}' using 1:($3==0?$2:1/0) with linespoints pt {5 + 2 * k} ps 1.5 "
                      f"lc {k + 1} title '{name}', "
                      f"'{fn}' using 1:($3==1?$2:1/0) with points pt {4 + 2 * k} ps 2 lc {k + 1} "
                      "notitle, "
                      f"'{fn}' using 1:2:4 with labels offset 1,0.7 left font ',8' notitle")
    g = ["set terminal pngcairo noenhanced size 1000,650", "set output 'error_vs_time.png'",
         "set logscale xy", "set grid", "set key top right",
         "set title 'FEM-DEM: error of the bend angle(x) - angle(0) against cost (open: each reference)'",
         "set xlabel 'CPU time of the variant [s]'",
         f"set ylabel 'relative error of the bend at {','.join(f'{m:g}' for m in marks)} mm'",
         f"set yrange [{FLOOR / 2}:*]", "plot " + ", ".join(series)]
    if series:
        subprocess.run(["gnuplot"], input="\n".join(g) + "\n", text=True, cwd=outdir)

main()
