#!/usr/bin/env python3
"""A signal stops a long HMSA run within about a second wherever it arrives, with exit status 3,
the results computed so far kept and no temporary left:
  settling   Zener step load, long t_end: the history is written quickly, then the settling-time
             pass re-integrates on a 0.002 grid (tens of seconds; it never polled: ~33 s);
  erk        stiff Maxwell branch under method = erk: millions of explicit steps per 1000 rows
             (the history polled every 1000 rows: 800 rows never reached the next poll).
The signal is sent after a sign of life (a file of the run appears), not after a fixed delay."""
import os, signal, subprocess, sys, tempfile, time

exe = sys.argv[1]
LIMIT = 3.0  # s from the signal to the exit; the polls answer in milliseconds (loaded machine)
CASES = [
    ("settling", "[run]\nplots = false\n[hmsa]\nmodel = zener\nloading = const\nb2 = 0.16\n"
                 "t_end = 1e5\ndt_out = 1e3\n", "history.csv", 0.2),
    ("erk", "[run]\nplots = false\n[hmsa]\nmodel = zener\neta = 1e-4\nb2 = 0.16\nt_end = 40\n"
            "dt_out = 0.05\nmethod = erk\n", "case.ini", 0.5),
]

fails = []
with tempfile.TemporaryDirectory() as tmp:
    for label, text, sign, delay in CASES:
        case, out = os.path.join(tmp, label + ".ini"), os.path.join(tmp, label)
        with open(case, "w") as f:
            f.write(text)
        p = subprocess.Popen([exe, "run", case, "--out", out, "--quiet"], stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
        t0 = time.time()
        while not os.path.exists(os.path.join(out, sign)) and p.poll() is None and time.time() - t0 < 60:
            time.sleep(0.01)
        if p.poll() is not None:
            fails.append(f"{label}: run ended (rc={p.returncode}) before it could be interrupted")
            continue
        time.sleep(delay)
        p.send_signal(signal.SIGTERM)
        ts = time.time()
        try:
            _, err = p.communicate(timeout=LIMIT)
        except subprocess.TimeoutExpired:
            p.kill()
            p.communicate()
            fails.append(f"{label}: still running {LIMIT} s after SIGTERM")
            continue
        dt = time.time() - ts
        if p.returncode != 3:
            fails.append(f"{label}: exit {p.returncode} after SIGTERM, expected 3; {err[-300:]}")
        names = os.listdir(out)
        temps = [n for n in names if ".tmp." in n]
        if temps:
            fails.append(f"{label}: temporaries left: {temps}")
        for keep in ("softact.log", "summary.ini", "history.csv"):
            if keep not in names:
                fails.append(f"{label}: {keep} of the interrupted run is missing ({dt:.2f} s)")
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
