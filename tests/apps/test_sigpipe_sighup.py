#!/usr/bin/env python3
"""SIGHUP and SIGPIPE end a run like SIGINT/SIGTERM: exit status 3, the results computed so far
and the log kept, no temporary left (before, both killed the process and left
.softact.log.tmp.* and .summary.ini.tmp.*). SIGPIPE is produced the way users meet it: stderr
piped into a reader that quits after the first line (`softact run ... 2>&1 | head -1`); the
later writes to the closed pipe must neither kill nor hang the run. A closed stderr (2>&-) does
not stop a run at all."""
import os, signal, subprocess, sys, tempfile, time

exe = sys.argv[1]
# a few variants, each logging a line when done: stderr is written during the whole run
VARIANTS = ("[run]\nplots = false\n[hmsa]\nmodel = zener\nloading = sq\nomega = 2.1\n"
            "eta = 5, 10, 20, 50, 100, 200, 400, 800\nt_end = 2000\ndt_out = 0.1\n")
LONG = "[run]\nplots = false\n[hmsa]\nmodel = zener\nloading = sq\nomega = 2.1\nt_end = 1e5\ndt_out = 0.1\n"
STATICS = "[run]\nplots = false\n[hmsa]\nanalysis = statics\nS = 0, 2.5\nb2 = 3, 0.16\n"


def check_out(label, out, fails, need=("softact.log", "summary.ini")):
    names = os.listdir(out) if os.path.isdir(out) else []
    temps = [n for n in names if ".tmp." in n]
    if temps:
        fails.append(f"{label}: temporaries left: {temps}")
    for n in need:
        if n not in names:
            fails.append(f"{label}: {n} missing (have {sorted(names)})")


fails = []
with tempfile.TemporaryDirectory() as tmp:
    def case(name, text):
        path = os.path.join(tmp, name + ".ini")
        with open(path, "w") as f:
            f.write(text)
        return path

    # SIGHUP: the terminal went away
    out = os.path.join(tmp, "hup")
    p = subprocess.Popen([exe, "run", case("long", LONG), "--out", out, "--quiet"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    t0 = time.time()
    while not os.path.exists(os.path.join(out, "case.ini")) and p.poll() is None and time.time() - t0 < 60:
        time.sleep(0.01)
    time.sleep(0.3)
    p.send_signal(signal.SIGHUP)
    try:
        _, err = p.communicate(timeout=30)
        if p.returncode != 3:
            fails.append(f"sighup: exit {p.returncode}, expected 3; {err[-300:]}")
        check_out("sighup", out, fails)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        fails.append("sighup: did not stop within 30 s")

    # SIGPIPE: stderr into a reader that closes after the first line
    out = os.path.join(tmp, "pipe")
    p = subprocess.Popen([exe, "run", case("variants", VARIANTS), "--out", out],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    p.stderr.readline()
    p.stderr.close()  # the reader quits, like `head -1`
    try:
        p.wait(timeout=60)
        if p.returncode != 3:
            fails.append(f"sigpipe: exit {p.returncode}, expected 3 (interrupted by SIGPIPE)")
        check_out("sigpipe", out, fails)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
        fails.append("sigpipe: the run hung after its stderr reader went away")

    # stderr closed from the start: writes fail with EBADF, the run completes
    out = os.path.join(tmp, "closed")
    r = subprocess.run([exe, "run", case("statics", STATICS), "--out", out],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       preexec_fn=lambda: os.close(2), timeout=60)
    if r.returncode != 0:
        fails.append(f"closed stderr: exit {r.returncode}, expected 0")
    check_out("closed stderr", out, fails)
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
