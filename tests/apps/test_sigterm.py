#!/usr/bin/env python3
"""Interrupting a run: SIGTERM (and SIGINT) stop a long run cleanly with exit status 3, keep
what was computed as complete files, and never leave a temporary or truncated file; a second
signal stops at once, still leaving no temporary. Uses a long HMSA time history.
Delays count from a sign of life (the results folder appears), not from the start: on a loaded
machine start-up alone can take longer than a fixed delay; early_sigterm signals at once then."""
import csv, glob, os, signal, subprocess, sys, tempfile, time

exe = sys.argv[1]
CASE = """[hmsa]
model = zener
loading = sq
omega = 2.1
t_end = 1e5
dt_out = 0.1
"""

def check_outputs(out, label, fails):
    temps = [f for f in os.listdir(out) if ".tmp." in f]
    if temps:
        fails.append(f"{label}: temporary files left: {temps}")
    for path in glob.glob(os.path.join(out, "*.csv")):
        with open(path) as f:
            text = f.read()
        if text and not text.endswith("\n"):
            fails.append(f"{label}: {path} does not end with a newline (truncated)")
        rows = [r for r in csv.reader(l for l in text.splitlines() if not l.startswith("#"))]
        widths = {len(r) for r in rows}
        if len(widths) > 1:
            fails.append(f"{label}: {path} has ragged rows {widths}")
        for r in rows[1:]:
            try:
                [float(x) for x in r]
            except ValueError:
                fails.append(f"{label}: {path} has a non-number row {r[:4]}")
                break

fails = []
with tempfile.TemporaryDirectory() as tmp:
    case = os.path.join(tmp, "long.ini")
    with open(case, "w") as f:
        f.write(CASE)
    for label, signals, delay in [("sigterm", [signal.SIGTERM], 2.0), ("sigint", [signal.SIGINT], 1.0),
                                  ("early_sigterm", [signal.SIGTERM], 0.0),
                                  ("double_signal", [signal.SIGTERM, signal.SIGTERM], 1.0)]:
        out = os.path.join(tmp, label)
        p = subprocess.Popen([exe, "run", case, "--out", out, "--quiet"], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
        t0 = time.time()
        while not os.path.isdir(out) and p.poll() is None and time.time() - t0 < 60:
            time.sleep(0.005)
        time.sleep(delay)
        if p.poll() is not None:
            fails.append(f"{label}: run ended before the signal (rc={p.returncode}); make the case longer")
            continue
        for s in signals:
            p.send_signal(s)
            time.sleep(0.05)
        try:
            _, err = p.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            p.kill()
            fails.append(f"{label}: did not stop within 60 s of the signal")
            continue
        if p.returncode != 3:
            fails.append(f"{label}: exit {p.returncode}, expected 3; stderr: {err[-400:]}")
        if os.path.isdir(out):
            check_outputs(out, label, fails)
            if len(signals) == 1 and not os.path.exists(os.path.join(out, "softact.log")):
                fails.append(f"{label}: the log of the interrupted run is missing")
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
