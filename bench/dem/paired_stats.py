#!/usr/bin/env python3
"""Variants of the FEM-DEM scene resumed from the same beds, read against the grain noise
(bench/dem/interval_long_study.sh, speed_long_study.sh).

  bench/dem/paired_stats.py OUT --at 1,2,3 --variants iv5e-4,iv2.5e-4,iv1.25e-4 --ref iv1.25e-4
      --seeds S1,S2,... [--title TEXT] [--name FILE] [--labels L1,L2,...]

For every seed (one poured bed) and variant, the bend the piston makes, b(x) = angle(x) -
angle(0), at the displacements --at [mm] (from OUT/s<seed>_<variant>/bending.csv; the
actuator's rest angle under the bed's weight is the same for every variant of a bed). Per
variant: the mean bend over the seeds and its standard error (the grain noise), and the
difference to the reference variant paired by bed (mean, standard error, and how many standard
errors from zero), the piston force likewise, and the median CPU time of a run
(summary.ini [timing] cpu). A difference within two standard errors is not resolved by the
study: the variant's effect is then below the grain noise of this many beds.
Writes OUT/<FILE> (default paired_stats.md) and prints it, and OUT/<FILE>.png: the mean bend
of every variant against the displacement (every 0.25 mm up to the last mark), with error bars
of one standard error over the beds."""
import math, os, statistics, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_io import read_summary, read_curve, value_at

def arg(name, default=None):
    a = sys.argv
    return a[a.index(name) + 1] if name in a else default

def mean_se(xs):
    if not xs:
        return float("nan"), float("nan")
    m = statistics.fmean(xs)
    return m, (statistics.stdev(xs) / math.sqrt(len(xs)) if len(xs) > 1 else float("nan"))

def main():
    out = sys.argv[1]
    marks = [float(x) for x in arg("--at", "1,2,3").split(",")]
    ivs = arg("--variants", "iv5e-4,iv2.5e-4,iv1.25e-4").split(",")
    seeds = arg("--seeds", "").split(",")
    finest = arg("--ref", ivs[-1])
    data, cpu, skipped = {}, {}, []  # (seed, iv) -> {mark: (bend, force)}, iv -> [cpu]
    for s in seeds:
        for iv in ivs:
            d = os.path.join(out, "s%s_%s" % (s, iv))
            try:
                rows = read_curve(os.path.join(d, "bending.csv"))
                summ = read_summary(os.path.join(d, "summary.ini"))
            except OSError:
                continue
            if summ.get("result.status", "completed") != "completed":
                skipped.append("s%s_%s (%s)" % (s, iv, summ.get("result.status")))
                continue
            a0 = rows[0]["bending_angle"]
            got = {}
            for x in marks:
                a = value_at(rows, x * 1e-3, "bending_angle")
                f = value_at(rows, x * 1e-3, "piston_force")
                if a is not None:
                    got[x] = (a - a0, f)
            data[(s, iv)] = got
            c = summ.get("timing.cpu") or summ.get("timing.wall")
            if c:
                cpu.setdefault(iv, []).append(float(c))
    lines = ["# %s (%s)" % (arg("--title", "Variants against the grain noise"),
                            os.path.basename(out.rstrip("/"))),
             "",
             "Beds (seeds) with every variant: %d of %d. Bend b = angle(x) - angle(0) [deg]; "
             "mean +- standard error over the beds; differences paired by bed against the "
             "reference variant (%s)." % (
                 sum(all((s, iv) in data for iv in ivs) for s in seeds), len(seeds), finest),
             "",
             "Left out (not completed): %s." % (", ".join(skipped) or "none"),
             "",
             "| variant | x [mm] | beds | mean bend [deg] | mean force [N] | bend - reference [deg] (paired) | in SE | force - reference [N] | median CPU [s] |",
             "|---|---|---|---|---|---|---|---|---|"]
    for iv in ivs:
        for x in marks:
            b = [data[(s, iv)][x][0] for s in seeds if (s, iv) in data and x in data[(s, iv)]]
            f = [data[(s, iv)][x][1] for s in seeds if (s, iv) in data and x in data[(s, iv)]]
            db, df = [], []
            for s in seeds:
                p, q = data.get((s, iv), {}).get(x), data.get((s, finest), {}).get(x)
                if p and q:
                    db.append(p[0] - q[0])
                    df.append(p[1] - q[1])
            mb, sb = mean_se(b)
            mf, _ = mean_se(f)
            md, sd = mean_se(db)
            mdf, sdf = mean_se(df)
            z = md / sd if sd and sd == sd and sd > 0 else float("nan")
            c = statistics.median(cpu[iv]) if cpu.get(iv) else float("nan")
            same = iv == finest
            lines.append("| %s | %g | %d | %.3f +- %.3f | %.2f | %s | %s | %s | %.0f |" % (
                iv + (" (reference)" if same else ""), x, len(b), mb, sb, mf,
                "-" if same else "%+.3f +- %.3f" % (md, sd),
                "-" if same else "%.1f" % z,
                "-" if same else "%+.2f +- %.2f" % (mdf, sdf), c))
    # the mean curves with their standard errors
    last = max(marks)
    xs = [0.25 * k for k in range(1, int(round(last / 0.25)) + 1)]
    name = arg("--name", "paired_stats.md")
    labels = arg("--labels", ",".join(ivs)).split(",")
    series, most = [], 0
    for k, iv in enumerate(ivs):
        fn = "%s_%d.dat" % (name, k)
        with open(os.path.join(out, fn), "w") as f:
            for x in xs:
                b = []
                for s in seeds:
                    if (s, iv) not in data:
                        continue
                    rows = read_curve(os.path.join(out, "s%s_%s" % (s, iv), "bending.csv"))
                    a = value_at(rows, x * 1e-3, "bending_angle")
                    if a is not None:
                        b.append(a - rows[0]["bending_angle"])
                m, se = mean_se(b)
                most = max(most, len(b))
                if b:
                    f.write("%g %.6g %.6g %d\n" % (x + 0.02 * (k - 1), m, se if se == se else 0,
                                                   len(b)))
        series.append("'%s' using 1:2:3 with yerrorlines lw 2 title '%s'" % (fn, labels[k]))
    g = ["set terminal pngcairo size 900,600", "set output '%s.png'" % name, "set grid",
         "set key top left",
         "set title '%s: mean bend over up to %d beds, +- one standard error'" % (
             arg("--title", "Variants"), most), "set xrange [0:%g]" % (last + 0.1),
         "set xlabel 'piston displacement [mm]'",
         "set ylabel 'bend angle(x) - angle(0) [deg]'", "plot " + ", ".join(series)]
    try:
        subprocess.run(["gnuplot"], input="\n".join(g) + "\n", text=True, cwd=out, check=True)
    except (OSError, subprocess.CalledProcessError) as e:
        print("gnuplot failed: %s" % e, file=sys.stderr)
    text = "\n".join(lines) + "\n"
    open(os.path.join(out, name), "w").write(text)
    print(text)

if __name__ == "__main__":
    main()
