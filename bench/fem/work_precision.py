#!/usr/bin/env python3
"""Work-precision of the FEM pressure ramp (issue 14; docs/fem_time_to_accuracy.md): the error of
the bending angle against the mesh-converged reference versus the ramp's run time, at each of the
four output pressures, for runs of bench/fem/fem_ramp over meshes and solver settings (and
CalculiX runs written in the same format).

  work_precision.py --ref A30,A60,A90,A120 --out BASE [--time wall|cpu] SERIES:LABEL=FILE [...]

FILE is a key = value file (lines starting with '#' are comments): angle_30 .. angle_120 [deg],
wall, cpu [s], nfree, factorisations, newton_iterations, completed (1 = the ramp reached 120 kPa)
and, for a ramp that stopped early, reached_kPa. A missing or non-numeric value ("-") is treated
as not measured. SERIES must not contain ':' and LABEL must not contain '=' or '@'; LABEL@POS
places the point's label at POS (n, ne, e, se, s, sw, w, nw of the point; default ne), LABEL@-
leaves the point unlabelled on the plot (crowded points; the table still names it). The
reference angles [deg] come from the refinement series (docs/fem_time_to_accuracy.md's converged
estimate).

The error of a run at pressure p is (angle_p - A_p) / A_p, signed (negative = too stiff); at
120 kPa it is the issue's measure. Runs that stopped short of 120 kPa are kept: they have an error
at the pressures they reached, "-" at the others.

Writes BASE.md: one row per run, with the 120 kPa angle, the signed error at 30, 60, 90 and 120
kPa ("-" where the run has no angle), the largest |error| over the pressures it reached, the
counts and the wall and CPU times.

Writes BASE.png: four log-log panels, |error| [%] at 30, 60, 90 and 120 kPa against the time of
the ramp (the whole ramp as run, also for a run that stopped early), one curve per SERIES with
the same style in every panel, points labelled with LABEL, the 1 % line dashed; a run is drawn in
every panel for which it has that pressure's angle and a time (a run without the chosen time is in
the table only, and its legend entry says so). The legend sits below the panels;
a series with a run that stopped early is marked "(stopped at R kPa)" in it unless its name
already says "stopped". --time cpu plots the process CPU time instead of the wall time (fairer
when the runs shared the machine with other jobs); the x axis label names the one plotted."""
import os, subprocess, sys, tempfile

P = [30, 60, 90, 120]
# per-series colours and point types (the same in every panel)
COLORS = ["#d62728", "#1f77b4", "#9467bd", "#8c564b", "#2ca02c", "#e66100", "#000000", "#17becf"]
PTYPES = [5, 7, 9, 11, 13, 15, 4, 6]
# point-label positions (LABEL@POS): character offsets and justification
POS = {"ne": (0.5, 0.75, "left"), "e": (0.9, 0, "left"), "se": (0.5, -0.75, "left"),
       "s": (0, -1.0, "center"), "sw": (-0.5, -0.75, "right"), "w": (-0.9, 0, "right"),
       "nw": (-0.5, 0.75, "right"), "n": (0, 1.0, "center")}


def read(path):
    kv = {}
    for line in open(path):
        if line.lstrip().startswith("#"):
            continue
        if " = " in line:
            k, v = line.split(" = ", 1)
            kv[k.strip()] = v.split()[0] if v.split() else ""
    return kv


def num(kv, key):
    try:
        return float(kv[key])
    except (KeyError, ValueError):
        return None


def pct(e, signed=True):
    if e is None:
        return "-"
    return f"{100 * e:+.2f} %" if signed else f"{100 * e:.2f} %"


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
            label, _, pos = label.partition("@")
            if pos and pos not in POS and pos != "-":
                sys.exit(f"label position {pos}: one of {', '.join(POS)}")
            runs.append((series, label, pos or "ne", read(path)))
    if not ref or len(ref) != len(P) or not base or not runs or tkey not in ("wall", "cpu"):
        sys.exit(__doc__)
    rows = []
    for series, label, pos, kv in runs:
        ang = [num(kv, f"angle_{p}") for p in P]
        err = [None if a is None else (a - r) / r for a, r in zip(ang, ref)]
        have = [abs(e) for e in err if e is not None]
        if not have:
            print(f"{series}:{label}: no angle at any pressure, left out", file=sys.stderr)
            continue
        stop = None
        if kv.get("completed") != "1":
            stop = kv.get("reached_kPa", "?")
            print(f"{series}:{label}: ramp stopped at {stop} kPa, drawn where it has angles",
                  file=sys.stderr)
        rows.append(dict(series=series, label=label, pos=pos, kv=kv, ang=ang, err=err, emax=max(have),
                         t=num(kv, tkey), stop=stop))

    with open(base + ".md", "w") as f:
        f.write("| series | run | free dofs | angle 120 kPa [deg] | error 30 kPa | error 60 kPa | "
                "error 90 kPa | error 120 kPa | largest error 30-120 kPa | factorisations | "
                "Newton its | wall [s] | CPU [s] |\n")
        f.write("|---" * 13 + "|\n")
        for r in rows:
            kv = r["kv"]
            run = r["label"] + (f" (stopped at {r['stop']} kPa)"
                                if r["stop"] and "stopped" not in r["series"] else "")
            a120 = "-" if r["ang"][3] is None else f"{r['ang'][3]:.4f}"
            f.write(f"| {r['series']} | {run} | {kv.get('nfree', '-')} | {a120} | "
                    + " | ".join(pct(e) for e in r["err"])
                    + f" | {pct(r['emax'], False)} | {kv.get('factorisations', '-')} | "
                    f"{kv.get('newton_iterations', '-')} | {kv.get('wall', '-')} | "
                    f"{kv.get('cpu', '-')} |\n")

    series_names = list(dict.fromkeys(r["series"] for r in rows))
    titles = []
    for s in series_names:
        stops = sorted({r["stop"] for r in rows if r["series"] == s and r["stop"]})
        titles.append(s if not stops or "stopped" in s else f"{s} (stopped at {', '.join(stops)} kPa)")
    plotted = [r for r in rows if r["t"] is not None and r["t"] > 0]
    if len(plotted) < len(rows):
        print(f"{len(rows) - len(plotted)} run(s) without a {tkey} time: in the table only",
              file=sys.stderr)
    titles = [t if any(r["series"] == s for r in plotted) else f"{t} (no {tkey} time: table only)"
              for s, t in zip(series_names, titles)]
    if not plotted:
        sys.exit(f"no run has a {tkey} time: nothing to plot")
    tmin = min(r["t"] for r in plotted)
    tmax = max(r["t"] for r in plotted)
    x0, x1 = tmin / 1.6, tmax * 2.5

    # layout (screen coordinates): 2 x 2 panels above, the shared legend below in two columns
    W, H = 1400, 1400
    nkey = len(series_names) + 1
    # two legend columns if they fit (estimated 0.72 font sizes a character), else one
    KF = 14
    chars = [len(t) for t in titles] + [len("1 % error")]
    key_rows = (nkey + 1) // 2
    c1 = 0.02 + (0.72 * KF * max(chars[:key_rows]) + 90) / W
    if c1 + (0.72 * KF * max(chars[key_rows:]) + 70) / W > 0.99:
        key_rows, c1 = nkey, None
    key_h = 0.0235 * key_rows + 0.01
    L, R, B, T, GX, GY = 0.075, 0.975, key_h + 0.07, 0.925, 0.06, 0.08
    pw, ph = (R - L - GX) / 2, (T - B - GY) / 2
    tname = "CPU" if tkey == "cpu" else "wall"
    tmp = tempfile.mkdtemp(prefix="work_precision.")
    g = [f"set terminal pngcairo size {W},{H} font ',16' linewidth 1.5", f"set output '{base}.png'",
         "set multiplot",
         f"set label 1 'FEM pressure ramp with rings: bending-angle error against {tname} time' "
         "at screen 0.5, 0.975 center font ',19'",
         "set logscale xy", "set format x '%g'", "set format y '%g'",
         "set grid xtics ytics mxtics mytics lc rgb 'gray85', lc rgb 'gray93'",
         f"set xrange [{x0:g}:{x1:g}]", "set yrange [0.08:40]",
         "set ytics ('0.1' 0.1, '0.3' 0.3, '1' 1, '3' 3, '10' 10, '30' 30)",
         "set style textbox opaque noborder margins 0.3,0.3", "unset key"]
    for i, s in enumerate(series_names):
        g.append(f"set style line {i + 1} lc rgb '{COLORS[i % len(COLORS)]}' lw 2 "
                 f"pt {PTYPES[i % len(PTYPES)]} ps 1.8")
    for k, p in enumerate(P):
        col, row = k % 2, k // 2
        xl, yt = L + col * (pw + GX), T - row * (ph + GY)
        g += [f"set lmargin at screen {xl:.4f}", f"set rmargin at screen {xl + pw:.4f}",
              f"set tmargin at screen {yt:.4f}", f"set bmargin at screen {yt - ph:.4f}",
              f"set title '{p} kPa' font ',18' offset 0,-0.3",
              f"set xlabel '{tname} time of the ramp [s]'" if row == 1 else "set xlabel ''",
              "set ylabel '|angle error| vs converged [%]' offset 1,0" if col == 0 else "set ylabel ''"]
        plots = []
        for i, s in enumerate(series_names):
            pts = [r for r in plotted if r["series"] == s and r["err"][k] is not None]
            if not pts:
                continue
            dat = os.path.join(tmp, f"p{p}_s{i}.dat")
            with open(dat, "w") as f:
                for j, r in enumerate(pts):
                    f.write(f"{r['t']:.6g} {max(100 * abs(r['err'][k]), 1e-3):.6e} "
                            f"\"{r['label']}\" {list(POS).index(r['pos']) if r['pos'] in POS else -1}\n")
            plots.append(f"'{dat}' using 1:2 with linespoints ls {i + 1}")
            for q, (dx, dy, just) in POS.items():
                if any(r["pos"] == q for r in pts):
                    iq = list(POS).index(q)
                    plots.append(f"'{dat}' using 1:($4 == {iq} ? $2 : NaN):3 with labels boxed offset "
                                 f"{dx},{dy} {just} font ',13' tc ls {i + 1}")
        plots.append("1 with lines dt 2 lw 2 lc rgb 'gray30'")
        g.append("plot " + ", ".join(plots))
    # the legend: empty plots over the bottom strip, its two columns side by side
    g += ["unset title", "unset label 1", "unset xlabel", "unset ylabel", "unset border", "unset tics",
          "unset grid", "unset logscale", "set xrange [0:1]", "set yrange [0:1]",
          f"set tmargin at screen {key_h:.4f}", "set bmargin at screen 0.002"]
    entries = [f"NaN with linespoints ls {i + 1} title '{t}'" for i, t in enumerate(titles)]
    entries.append("NaN with lines dt 2 lw 2 lc rgb 'gray30' title '1 % error'")
    for c, x in enumerate((0.02, c1) if c1 else (0.02,)):
        g += [f"set lmargin at screen {x:.3f}", "set rmargin at screen 0.995",
              f"set key at screen {x:.3f},{key_h:.4f} left top vertical Left reverse "
              f"samplen 2.5 spacing 1.1 font ',{KF}'",
              "plot " + ", ".join(entries[c * key_rows:(c + 1) * key_rows])]
    g.append("unset multiplot")
    try:
        subprocess.run(["gnuplot"], input="\n".join(g) + "\n", text=True, check=True)
    finally:
        for f in os.listdir(tmp):
            os.remove(os.path.join(tmp, f))
        os.rmdir(tmp)


if __name__ == "__main__":
    main()
