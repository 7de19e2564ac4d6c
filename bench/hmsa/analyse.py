#!/usr/bin/env python3
"""analyse.py - tables and figures of the HMSA work-precision study (bench/hmsa/run.sh).

Usage: analyse.py RESULTS_DIR DOCS_DIR
Reads the CSV files run.sh wrote into RESULTS_DIR, computes the errors of the Octave runs
against softact's tight-tolerance reference (the same reference the C runs use), compares
the solvers at equal error (log-log interpolation of time against error inside each curve, no
extrapolation), writes DOCS_DIR/hmsa_benchmark.md and the gnuplot figures DOCS_DIR/img/hmsa_*.png.
Standard library only.
"""
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile


def read_csv(path):
    """Rows (dicts) and the '#' comment lines of a CSV file; ([], []) if it does not exist."""
    if not os.path.exists(path):
        return [], []
    with open(path) as f:
        lines = f.read().splitlines()
    comments = [l[1:].strip() for l in lines if l.startswith("#")]
    body = [l for l in lines if l and not l.startswith("#")]
    return list(csv.DictReader(body)), comments


def fnum(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def cpu_or_wall(r):
    """CPU time of the run if recorded, else its wall time."""
    c = fnum(r.get("cpu"))
    return c if math.isfinite(c) else fnum(r.get("seconds"))


def read_kv(path):
    d = {}
    if os.path.exists(path):
        for line in open(path):
            if "=" in line:
                k, v = line.rstrip("\n").split("=", 1)
                d[k] = v
    return d


def fmt_t(t):
    if not math.isfinite(t):
        return "-"
    if t >= 100:
        return "%.0f" % t
    if t >= 1:
        return "%.2f" % t
    return "%.4f" % t


def fmt_r(r):
    """A tolerance as 1e-08 whatever way the CSV spelt it."""
    v = fnum(r)
    return "%.0e" % v if math.isfinite(v) else str(r)


def fmt_e(e):
    return "%.1e" % e if math.isfinite(e) else "-"


def interp_time(points, err):
    """Time at error err on the curve points [(err, time)], log-log linear between the two
    neighbouring points that bracket err; None outside the curve's range."""
    pts = sorted((e, t) for e, t in points if e > 0 and t > 0 and math.isfinite(e))
    for (e0, t0), (e1, t1) in zip(pts, pts[1:]):
        if e0 <= err <= e1:
            if e1 == e0:
                return min(t0, t1)
            s = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0)))
    return None


def cheapest_at_most(points, err):
    """Smallest time among points with error <= err, or None."""
    ts = [t for e, t in points if math.isfinite(e) and e <= err]
    return min(ts) if ts else None


class Study:
    def __init__(self, res):
        self.res = res
        self.meta = read_kv(os.path.join(res, "meta.txt"))
        self.wall = {}
        wt = os.path.join(res, "walltime.csv")
        if os.path.exists(wt):
            for line in open(wt):
                if "," in line:
                    k, v = line.strip().split(",", 1)
                    self.wall[k] = fnum(v)

    def path(self, name):
        return os.path.join(self.res, name)

    def c_wp(self, names):
        """softact runs of one case: (reference row, comments, {method: [rows]})."""
        ref, comments, by = None, [], {}
        for name in names:
            rows, com = read_csv(self.path(name))
            # the reference is recomputed by every file of a case: keep the first one's lines
            comments += [c for c in com if not comments or not c.startswith(("reference", "ref_check"))]
            for r in rows:
                if r["method"] == "reference":
                    ref = ref or r
                    continue
                r["t"], r["wall"] = cpu_or_wall(r), fnum(r["seconds"])
                r["es"] = fnum(r["err_state"])
                r["ea"] = fnum(r["err_a3"])
                by.setdefault(r["method"], []).append(r)
        return ref, comments, by

    def octave_wp(self, name, ref):
        rows, _ = read_csv(self.path(name))
        y_ref = [fnum(ref[k]) for k in ("lambda", "dlambda", "xi")]
        for r in rows:
            y = [fnum(r[k]) for k in ("lambda", "dlambda", "xi")]
            r["t"], r["wall"] = cpu_or_wall(r), fnum(r["seconds"])
            r["es"] = max(abs(a - b) for a, b in zip(y, y_ref))
            r["ea"] = abs(fnum(r["a3"]) - fnum(ref["a3"]))
        return rows


def wp_table(out, groups):
    out.append("| solver | rtol | CPU time [s] | wall time [s] | steps | rejected | error final state "
               "| error a3 |")
    out.append("|---|---|---|---|---|---|---|---|")
    for label, rows in groups:
        for r in rows:
            steps = r.get("steps", "")
            rej = ""
            if r.get("attempts"):
                rej = str(int(fnum(r["attempts"]) - fnum(r["steps"])))
            if steps in ("NaN", "nan"):
                steps = "-"
            out.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
                label, fmt_r(r["rtol"]), fmt_t(r["t"]), fmt_t(r.get("wall", math.nan)),
                steps or "-", rej or "-", fmt_e(r["es"]), fmt_e(r["ea"])))


def equal_error_table(out, ours, theirs, key, levels, our_label, their_label):
    """Rows: error level, our time, their time, ratio (only where both curves reach it)."""
    out.append("| %s | %s, CPU [s] | %s, CPU [s] | speed-up |" % (
        "error in a3" if key == "ea" else "error in the final state", our_label, their_label))
    out.append("|---|---|---|---|")
    ratios = []
    for lev in levels:
        a = interp_time([(r[key], r["t"]) for r in ours], lev)
        b = interp_time([(r[key], r["t"]) for r in theirs], lev)
        if a and b:
            ratios.append(b / a)
            out.append("| %.0e | %s | %s | %.0fx |" % (lev, fmt_t(a), fmt_t(b), b / a))
        else:
            out.append("| %.0e | %s | %s | - |" % (lev, fmt_t(a) if a else "out of range",
                                                 fmt_t(b) if b else "out of range"))
    return ratios


def gnuplot(script, cwd):
    try:
        subprocess.run(["gnuplot"], input=script.encode(), cwd=cwd, check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        return True
    except (OSError, subprocess.CalledProcessError) as e:
        err = getattr(e, "stderr", None)
        sys.stderr.write("analyse.py: gnuplot failed: %s\n" % (err.decode(errors="replace") if err else e))
        return False


def write_dat(path, rows, cols):
    with open(path, "w") as f:
        for r in rows:
            f.write(" ".join("%.6e" % fnum(r[c]) if isinstance(r[c], str) else "%.6e" % r[c]
                             for c in cols) + "\n")


def wp_plot(res, img, name, title, series):
    """series: [(label, rows, style)] -> two panels: time against error (state, a3)."""
    plots_s, plots_a = [], []
    for i, (label, rows, style) in enumerate(series):
        rows = [r for r in rows if r["es"] > 0 and r["ea"] > 0 and r["t"] > 0]
        if not rows:
            continue
        dat = os.path.join(PLOT_DIR, "plot_%s_%d.dat" % (name, i))
        write_dat(dat, rows, ["es", "ea", "t"])
        plots_s.append("'%s' u 1:3 w %s t '%s'" % (dat, style, label))
        plots_a.append("'%s' u 2:3 w %s t '%s'" % (dat, style, label))
    if not plots_s:
        return None
    png = os.path.join(img, "hmsa_%s.png" % name)
    gp = """set terminal pngcairo size 1300,560 font ',11'
set output '%s'
set multiplot layout 1,2 title '%s'
set logscale xy
set format x '10^{%%L}'
set format y '10^{%%L}'
set grid
set key bottom left
set ylabel 'CPU time per run [s]'
set xlabel 'error of the final state (max norm) vs reference'
plot %s
set xlabel 'error of the amplitude a3 vs reference'
plot %s
unset multiplot
""" % (png, title.replace("_", "\\_"), ", ".join(plots_s), ", ".join(plots_a))
    return png if gnuplot(gp, res) else None


def main():
    if len(sys.argv) != 3:
        sys.stderr.write("usage: analyse.py RESULTS_DIR DOCS_DIR\n")
        return 1
    res, docs = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    img = os.path.join(docs, "img")
    os.makedirs(img, exist_ok=True)
    st = Study(res)
    meta = st.meta
    oct_version = ""
    if os.path.exists(st.path("octave_version.txt")):
        oct_version = open(st.path("octave_version.txt")).read().strip()
    load_c = open(st.path("load_c.txt")).read().strip() if os.path.exists(st.path("load_c.txt")) else "?"
    load_o = (open(st.path("load_octave.txt")).read().strip()
              if os.path.exists(st.path("load_octave.txt")) else "?")

    # Periods per protocol run, from the C files' headers ("..., 140 + 40 periods ...").
    n_tr, n_me = 140, 40
    for name in ("c_wp_nonstiff.csv", "c_sweep.csv"):
        for c in read_csv(st.path(name))[1]:
            m = re.search(r"(\d+) \+ (\d+) periods", c)
            if m:
                n_tr, n_me = int(m.group(1)), int(m.group(2))
    P = n_tr + n_me

    out = []
    out.append("# HMSA integrators: work-precision study against GNU Octave")
    out.append("")
    out.append("Generated by `bench/hmsa/run.sh` (raw numbers in `bench/hmsa/results/`); do not "
               "edit by hand, rerun the script.")
    out.append("")
    out.append("- commit: `%s` (%s files differed from it when the study ran), date %s" % (
        meta.get("commit", "?"), meta.get("dirty_files", "?"), meta.get("date", "?")))
    out.append("- machine: %s, %s cores shared with other jobs (load average before the C runs "
               "%s, before the Octave runs %s)" % (meta.get("cpu", "?"), meta.get("nproc", "?"),
                                                   load_c, load_o))
    out.append("- softact: SUNDIALS %s (Debian), Release build; %s" % (
        meta.get("sundials", "?"), oct_version or "Octave: not run"))
    if meta.get("quick") == "1":
        out.append("- **QUICK=1 smoke run: fewer tolerances and periods; not the study.**")
    out.append("")
    out.append("## Protocol")
    out.append("")
    out.append(
        "Zener model (docs/hmsa_model.md, equations (E1)-(E2)), c = 1, beta = 2, S = 0, `sq` "
        "loading b2 = sgn b_a^2 sin^2(Omega tau), b_a = 0.4, sgn = -1. Start at rest; integrate "
        "%d forcing periods of transient, then %d periods sampled at 128 points per period "
        "from each solver's dense output; a3 = (max lambda3 - min lambda3)/2. One protocol run "
        "is %d forcing periods. Tolerances: rtol as listed, atol = 1e-2 rtol, the same pair "
        "for every solver." % (n_tr, n_me, P))
    out.append("")
    out.append(
        "- softact: `hmsa_bench` (bench/hmsa/hmsa_bench.c) times `hmsa_integrator_create`, "
        "`_reset` and `_advance` of hmsa/hmsa_integrate.c: `erk` = ARKODE ERKStep "
        "Dormand-Prince 5(4) with ARKODE's ImEx Gustafsson step controller (adaptivity method "
        "5, method order in the exponents), fused N_Vector kernels and the error weights "
        "computed in one loop, `dirk` = ARKStep ARK548L2SA DIRK 5(4) with the analytic Jacobian, "
        "dense output from ARKODE's Hermite interpolant (its Lagrange interpolant where the "
        "Maxwell branch is stiff: relaxation rate > 50 x 2 pi/T_ref, here the stiff case), "
        "`bdf` = CVODE BDF with the analytic Jacobian, `auto` = ERK switching to BDF on "
        "stiffness. CPU time (and wall time) of the whole run, median of %s runs." %
        meta.get("reps", "3"))
    out.append(
        "- Octave: the model written again from the specification in Octave "
        "(bench/hmsa/hmsa_rhs.m, hmsa_jac.m), the same protocol (hmsa_protocol.m); `ode45` "
        "(Dormand-Prince, interpreted) and `ode15s` (SUNDIALS IDA, compiled, Jacobian supplied). "
        "`cputime` and tic/toc inside Octave; each Octave run once (minutes); wall time of each "
        "Octave process (start-up included) in the last table.")
    out.append(
        "- Time: the machine is shared with other jobs (2 cores), so wall times depend on the "
        "load; every comparison uses **CPU time of the process** (user + system), which does "
        "not. Wall times are listed beside them.")
    out.append(
        "- Errors: against softact's ERK run at rtol 1e-13 (atol 1e-15) of the same case: "
        "max-norm error of the state (lambda, lambda', xi) at the final time, and the error of "
        "a3. The reference's own error is bounded below by comparing it with the runs at "
        "rtol 1e-12.")
    out.append(
        "- Equal error: each solver's time is interpolated log-log between its two runs that "
        "bracket the error level; no extrapolation ('out of range').")
    out.append("")

    # ---------------------------------------------------------------- non-stiff
    ref_n, com_n, c_n = st.c_wp(["c_wp_nonstiff.csv"])
    ratios_ns = []
    if ref_n:
        o45 = st.octave_wp("octave_wp_nonstiff_ode45.csv", ref_n)
        o15 = st.octave_wp("octave_wp_nonstiff_ode15s.csv", ref_n)
        out.append("## Non-stiff case: eta_bar = 50, Omega = 2.13 (primary resonance)")
        out.append("")
        out.append("Reference a3 = %.12f, final state (%.12f, %.12f, %.12f)." % (
            fnum(ref_n["a3"]), fnum(ref_n["lambda"]), fnum(ref_n["dlambda"]), fnum(ref_n["xi"])))
        for c in com_n:
            if c.startswith("reference") or c.startswith("ref_check"):
                out.append("- %s" % c)
        out.append("")
        out.append("![work-precision, non-stiff](img/hmsa_wp_nonstiff.png)")
        out.append("")
        groups = [("softact " + m, c_n[m]) for m in ("erk", "dirk", "bdf", "auto") if m in c_n]
        groups += [("Octave ode45", o45), ("Octave ode15s", o15)]
        wp_table(out, groups)
        out.append("")
        levels = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9]
        if "erk" in c_n and o45:
            out.append("Equal error, one protocol run, softact ERK against Octave ode45:")
            out.append("")
            ratios_ns = equal_error_table(out, c_n["erk"], o45, "ea", levels, "softact erk",
                                          "Octave ode45")
            out.append("")
            equal_error_table(out, c_n["erk"], o45, "es", levels, "softact erk", "Octave ode45")
            out.append("")
        if "bdf" in c_n and o15:
            out.append("Equal error, softact BDF against Octave ode15s (both implicit, both "
                       "SUNDIALS underneath):")
            out.append("")
            equal_error_table(out, c_n["bdf"], o15, "ea", levels, "softact bdf", "Octave ode15s")
            out.append("")
        # Cross-check of the two implementations of the model.
        tight = [r for r in o45 if fnum(r["rtol"]) <= 1e-10 + 1e-22]
        if tight:
            r = tight[-1]
            out.append(
                "Cross-check of the model: Octave's independent implementation with ode45 at "
                "rtol %s ends %.1e (max norm) from softact's reference state and gives a3 "
                "within %.1e, i.e. within ode45's own error at that tolerance: the C model "
                "(hmsa/hmsa_model.c) and the Octave one (hmsa_rhs.m, written from the "
                "specification) integrate the same equations." % (fmt_r(r["rtol"]), r["es"], r["ea"]))
            out.append("")
        wp_plot(res, img, "wp_nonstiff", "non-stiff: eta_bar = 50, Omega = 2.13, %d periods" % P,
                [("softact " + m, c_n[m], s) for m, s in
                 (("erk", "lp lw 2 pt 7"), ("dirk", "lp lw 2 pt 5"), ("bdf", "lp lw 2 pt 9"))
                 if m in c_n] +
                [("Octave ode45", o45, "lp lw 2 dt 2 pt 6"), ("Octave ode15s", o15, "lp lw 2 dt 2 pt 4")])

    # ---------------------------------------------------------------- stiff
    ref_s, com_s, c_s = st.c_wp(["c_wp_stiff.csv", "c_wp_stiff_erk.csv"])
    if ref_s:
        o15s = st.octave_wp("octave_wp_stiff_ode15s.csv", ref_s)
        o45s, _ = read_csv(st.path("octave_wp_stiff_ode45_2periods.csv"))
        out.append("## Stiff case: eta_bar = 1e-3, Omega = 2.13")
        out.append("")
        out.append(
            "The Maxwell branch relaxes at rate r = 12 beta / eta_bar = 2.4e4 against an "
            "oscillation frequency ~2.4, so explicit steps are bounded by stability (h r <= ~3) "
            "whatever the tolerance.")
        out.append("")
        out.append("Reference a3 = %.12f, final state (%.12f, %.12f, %.12f)." % (
            fnum(ref_s["a3"]), fnum(ref_s["lambda"]), fnum(ref_s["dlambda"]), fnum(ref_s["xi"])))
        for c in com_s:
            if c.startswith("reference") or c.startswith("ref_check") or "failed" in c:
                out.append("- %s" % c)
        out.append("")
        out.append("![work-precision, stiff](img/hmsa_wp_stiff.png)")
        out.append("")
        groups = [("softact " + m, c_s[m]) for m in ("erk", "dirk", "bdf", "auto") if m in c_s]
        groups += [("Octave ode15s", o15s)]
        wp_table(out, groups)
        out.append("")
        if o45s:
            r = o45s[0]
            t2, n2 = cpu_or_wall(r), fnum(r["steps"])
            erk_steps = [fnum(x["steps"]) for x in c_s.get("erk", [])]
            scale = P / 2.0  # the full run over 2 periods; steps are stability-bound
            txt = ("Octave ode45 on the stiff case was run for 2 forcing periods only (1 + 1, "
                   "rtol %s): %s s CPU, %d steps. The step is stability-bound, so %d periods would "
                   "take about %d steps and **~%.0f s (%.0f min) CPU** (linear extrapolation, not "
                   "run)" % (fmt_r(r["rtol"]), fmt_t(t2), n2, P, n2 * scale, t2 * scale,
                             t2 * scale / 60))
            if erk_steps:
                txt += "; softact ERK takes %d steps for the full run" % erk_steps[0]
            out.append(txt + ".")
            if "erk" in c_s:
                t_erk = min(x["t"] for x in c_s["erk"])
                out.append("That is %.0fx softact ERK's %s s on the full run." % (
                    t2 * scale / t_erk, fmt_t(t_erk)))
            out.append("")
        levels = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
        for m in ("bdf", "dirk"):
            if m in c_s and o15s:
                out.append("Equal error, softact %s against Octave ode15s:" % m.upper())
                out.append("")
                equal_error_table(out, c_s[m], o15s, "ea", levels, "softact " + m, "Octave ode15s")
                out.append("")
        wp_plot(res, img, "wp_stiff", "stiff: eta_bar = 1e-3, Omega = 2.13, %d periods" % P,
                [("softact " + m, c_s[m], s) for m, s in
                 (("erk", "lp lw 2 pt 7"), ("dirk", "lp lw 2 pt 5"), ("bdf", "lp lw 2 pt 9"),
                  ("auto", "lp lw 2 pt 11")) if m in c_s] +
                [("Octave ode15s", o15s, "lp lw 2 dt 2 pt 4")])

    # ---------------------------------------------------------------- sweep
    c_sw, com_sw = read_csv(st.path("c_sweep.csv"))
    ref_sw, _ = read_csv(st.path("c_sweep.csv.ref.csv"))
    headline = []
    if c_sw and ref_sw:
        a_ref = {round(fnum(r["omega"]), 9): fnum(r["a3"]) for r in ref_sw}
        for r in c_sw:
            r["t"], r["wall"], r["ea"] = cpu_or_wall(r), fnum(r["seconds"]), fnum(r["err_a3_max"])
        osw = []
        for tol in ("1e-6", "1e-8"):
            rows, com = read_csv(st.path("octave_sweep_ode45_%s.csv" % tol))
            if not rows:
                continue
            tot, tot_wall = math.nan, math.nan
            for c in com:
                if c.startswith("total_seconds="):
                    tot_wall = fnum(c.split("=", 1)[1])
                if c.startswith("total_cpu="):
                    tot = fnum(c.split("=", 1)[1])
            if not math.isfinite(tot):
                tot = tot_wall
            errs = [abs(fnum(r["a3"]) - a_ref.get(round(fnum(r["omega"]), 9), math.nan)) for r in rows]
            osw.append({"rtol": tol, "t": tot, "tw": tot_wall, "ea": max(errs) if errs else math.nan,
                        "wall": st.wall.get("octave_sweep_ode45_%s" % tol, math.nan),
                        "n": len(rows), "rows": rows,
                        "steps": sum(fnum(r["steps"]) for r in rows)})
        out.append("## Frequency sweep: %d frequencies, Omega in [%s], %d periods each from rest"
                   % (len(ref_sw), "%g, %g" % (fnum(ref_sw[0]["omega"]), fnum(ref_sw[-1]["omega"])), P))
        out.append("")
        out.append("eta_bar = 50; the error of a sweep is max over Omega of |a3 - a3_ref|, the "
                   "reference being softact ERK at rtol 1e-13 at every Omega.")
        out.append("")
        out.append("![sweep work-precision](img/hmsa_sweep_wp.png)")
        out.append("")
        out.append("| solver | rtol | CPU time [s] | wall time [s] | steps | max error a3 |")
        out.append("|---|---|---|---|---|---|")
        for r in c_sw:
            out.append("| softact %s | %s | %s | %s | %s | %s |" % (
                r["method"], fmt_r(r["rtol"]), fmt_t(r["t"]), fmt_t(r["wall"]), r["steps"],
                fmt_e(r["ea"])))
        for o in osw:
            out.append("| Octave ode45 | %s | %s | %s (process: %s) | %d | %s |" % (
                o["rtol"], fmt_t(o["t"]), fmt_t(o["tw"]), fmt_t(o["wall"]), o["steps"],
                fmt_e(o["ea"])))
        out.append("")
        erk = [(r["ea"], r["t"]) for r in c_sw if r["method"] == "erk"]
        if osw and erk:
            out.append("**Speed-up of the softact sweep (ERK) over Octave's ode45 sweep at equal "
                       "error:**")
            out.append("")
            out.append("| Octave rtol | Octave CPU [s] | Octave max error | softact ERK CPU at "
                       "that error [s] (interpolated) | speed-up | cheapest softact ERK run with "
                       "error <= Octave's, CPU [s] | speed-up (conservative) | softact ERK at the "
                       "same rtol, CPU [s] | speed-up at equal rtol |")
            out.append("|---|---|---|---|---|---|---|---|---|")
            for o in osw:
                ti = interp_time(erk, o["ea"])
                tc = cheapest_at_most(erk, o["ea"])
                same = [r["t"] for r in c_sw if r["method"] == "erk" and fnum(r["rtol"]) == fnum(o["rtol"])]
                ts = same[0] if same else None
                out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                    o["rtol"], fmt_t(o["t"]), fmt_e(o["ea"]),
                    fmt_t(ti) if ti else "out of range", "%.0fx" % (o["t"] / ti) if ti else "-",
                    fmt_t(tc) if tc else "none", "%.0fx" % (o["t"] / tc) if tc else "-",
                    fmt_t(ts) if ts else "-", "%.0fx" % (o["t"] / ts) if ts else "-"))
                headline.append((o, ti, tc, ts))
            out.append("")
        # plots: sweep work-precision and the a3 curve
        plots = []
        for i, (m, s) in enumerate((("erk", "lp lw 2 pt 7"), ("dirk", "lp lw 2 pt 5"),
                                    ("bdf", "lp lw 2 pt 9"))):
            rows = [r for r in c_sw if r["method"] == m and r["ea"] > 0]
            if rows:
                dat = os.path.join(PLOT_DIR, "plot_sweep_%s.dat" % m)
                write_dat(dat, rows, ["ea", "t"])
                plots.append("'%s' u 1:2 w %s t 'softact %s'" % (dat, s, m))
        if osw:
            dat = os.path.join(PLOT_DIR, "plot_sweep_octave.dat")
            write_dat(dat, osw, ["ea", "t"])
            plots.append("'%s' u 1:2 w lp lw 2 dt 2 pt 6 ps 2 t 'Octave ode45 (rtol 1e-6, 1e-8)'" % dat)
        if plots:
            gnuplot("""set terminal pngcairo size 900,600 font ',11'
set output '%s'
set title 'sweep of %d frequencies x %d periods, eta\\_bar = 50'
set logscale xy
set format x '10^{%%L}'
set format y '10^{%%L}'
set grid
set key bottom left
set xlabel 'max over Omega of |a3 - a3_{ref}|'
set ylabel 'CPU time of the sweep [s]'
plot %s
""" % (os.path.join(img, "hmsa_sweep_wp.png"), len(ref_sw), P, ", ".join(plots)), res)
        dat_ref = os.path.join(PLOT_DIR, "plot_sweep_ref.dat")
        write_dat(dat_ref, ref_sw, ["omega", "a3"])
        curve = ["'%s' u 1:2 w lp lw 2 pt 7 t 'softact reference (erk, rtol 1e-13)'" % dat_ref]
        for o in osw:
            if o["rtol"] == "1e-8":
                dat = os.path.join(PLOT_DIR, "plot_sweep_octave_curve.dat")
                write_dat(dat, o["rows"], ["omega", "a3"])
                curve.append("'%s' u 1:2 w p pt 6 ps 2 t 'Octave ode45, rtol 1e-8'" % dat)
        gnuplot("""set terminal pngcairo size 900,560 font ',11'
set output '%s'
set title 'steady amplitude, eta\\_bar = 50, sgn = -1, b\\_a = 0.4, S = 0'
set grid
set xlabel 'Omega'
set ylabel 'a3 = (max lambda3 - min lambda3)/2'
plot %s
""" % (os.path.join(img, "hmsa_sweep_curve.png"), ", ".join(curve)), res)
        out.append("![sweep amplitude](img/hmsa_sweep_curve.png)")
        out.append("")
        _, com_ref = read_csv(st.path("c_sweep.csv.ref.csv"))
        peaks = [c for c in com_ref if c.startswith("peak")]
        if peaks:
            out.append("Peaks of the reference sweep found by `hmsa_peaks_find` "
                       "(hmsa/hmsa_classify.c) and refined by golden-section search, each "
                       "evaluation a full %d-period run with softact ERK at rtol 1e-10 "
                       "(docs/hmsa_model.md section 8 expects 2.13 for eta_bar = 50, sgn = -1, "
                       "S = 0, with a3 ~ 0.117):" % P)
            out.append("")
            for c in peaks:
                out.append("- %s" % c)
            out.append("")

    # ---------------------------------------------------------------- summary first
    summary = ["## Result", ""]
    for o, ti, tc, ts in headline:
        if not math.isfinite(o["t"]):
            continue
        txt = ("Sweep (%d frequencies x %d periods): Octave's ode45 at rtol %s took %s s CPU "
               "(%s s wall) with max error %s in a3. " % (o["n"], P, o["rtol"], fmt_t(o["t"]),
                                                        fmt_t(o["tw"]), fmt_e(o["ea"])))
        if ti:
            txt += ("softact's ERK reaches that error in %s s CPU: **%.0fx faster at equal "
                    "error**" % (fmt_t(ti), o["t"] / ti))
        else:
            txt += "softact's ERK runs do not bracket that error"
        if tc:
            txt += (" (%.0fx against the cheapest softact run that is at least as accurate)" %
                    (o["t"] / tc))
        if ts:
            e_same = [r["ea"] for r in c_sw if r["method"] == "erk" and fnum(r["rtol"]) == fnum(o["rtol"])]
            txt += ("; at equal tolerance %.0fx (softact's error there %s)" % (
                o["t"] / ts, fmt_e(e_same[0]) if e_same else "?"))
        txt += "."
        summary.append("- " + txt)
    if headline:
        summary.append("- Target of issue 4: >= 300x at equal error on this sweep.")
    summary.append("")
    if ratios_ns:
        summary.append("Single protocol run (one frequency), softact ERK against Octave ode45 at "
                       "equal error in a3: %.0fx to %.0fx over the error levels both reach." % (
                           min(ratios_ns), max(ratios_ns)))
        summary.append("")
    out[out.index("## Protocol"):out.index("## Protocol")] = summary

    # ---------------------------------------------------------------- wall times
    if st.wall:
        out.append("## Octave process wall times (start-up included)")
        out.append("")
        out.append("| run | wall [s] |")
        out.append("|---|---|")
        for k, v in st.wall.items():
            out.append("| %s | %s |" % (k, fmt_t(v)))
        out.append("")
    out.append("## Notes")
    out.append("")
    out.append(
        "- Octave's ode15s (SUNDIALS IDA) stops after 500 steps between two output times; "
        "hmsa_protocol.m therefore asks it for output every quarter period during the transient.")
    out.append(
        "- Octave 7.3 prints `error: ignoring const execution_exception& while preparing to "
        "exit` when it exits; the exit status is 0 and the results are complete.")
    out.append(
        "- The machine is shared; timings of single runs vary by ~10-20 %. softact numbers are "
        "medians of repeated runs, Octave runs once.")
    out.append(
        "- Stiff case: with eta_bar = 1e-3 the Maxwell branch is relaxed and the damping is "
        "tiny (decay rate ~ (omega_u^2 - omega_r^2)/(2 r) = 2.5e-4), so after 140 periods the "
        "free oscillation has not died out and the response is forced + free: its Poincare "
        "section is a closed curve, which `hmsa_poincare_classify` reports as quasi-periodic "
        "(the non-stiff reference is period-1). The errors are still errors of a well-defined "
        "initial-value problem.")
    out.append(
        "- SUNDIALS' per-step overhead (~1 us a step for a 3-equation system: vector operations "
        "through function pointers, error norm, step control) dominates softact's cost; the "
        "right-hand side is a small part of it. Octave's ode45 takes about as many steps and "
        "reaches about the same error at the same tolerance; its ~0.4 ms a step is the "
        "interpreter.")
    out.append(
        "- DIRK accuracy (issue 15): before commit 13579f0 the DIRK's dense output came from "
        "ARKODE's Lagrange interpolant (a degree-5 polynomial through the last six step "
        "values, no derivatives) in every regime. On the non-stiff case its interpolation "
        "error at the output points was 4-20x the DIRK's own step error: final-state error "
        "7.2e-7 at rtol 1e-8 (72 rtol) and 1.3e-7 at rtol 1e-10 (1300 rtol) in the study of "
        "commit 9eca8d1, while outputs landing exactly on a step (tstop) or read from the "
        "Hermite interpolant were 12-22 rtol. The Hermite interpolant is now used unless the "
        "Maxwell branch is stiff, where its interior RHS calls at interpolated states leave xi "
        "off the slow manifold (energy balance 1e3 instead of 1e-6 at eta_bar 1e-5); there the "
        "Lagrange interpolant is kept and its error is not the dominant one (stiff table).")
    out.append(
        "- Where the ERK time goes (perf, non-stiff case, rtol 1e-8, issue 15): N_VLinearCombination "
        "28 %, `sin` of the sq load 9 %, `pow` 6 %, the right-hand side itself 6 %, the "
        "step routine 5 %, the error norm 5 %. All of `pow` is called by ARKODE's step "
        "controller (arkAdaptImExGus: fractional exponents of the error ratios); the "
        "right-hand side (hmsa_model_rhs) has never called `pow` (integer powers are "
        "multiplications since the first commit), so replacing integer `pow` by products "
        "changes nothing measurable there; the few integer `pow` calls left in statics and "
        "diagnostics were replaced anyway.")
    out.append("")
    with open(os.path.join(docs, "hmsa_benchmark.md"), "w") as f:
        f.write("\n".join(out))
    return 0


PLOT_DIR = None

if __name__ == "__main__":
    PLOT_DIR = tempfile.mkdtemp(prefix="hmsa_plot_")
    try:
        rc = main()
    finally:
        shutil.rmtree(PLOT_DIR, ignore_errors=True)
    sys.exit(rc)
