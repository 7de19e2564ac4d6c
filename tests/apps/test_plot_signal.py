#!/usr/bin/env python3
"""A second signal while gnuplot renders a figure ends the gnuplot child too: softact kills and
reaps it and removes the temporary PNG it was writing, so nothing appears in the results folder
after softact has exited (before, the orphaned child wrote .NAME.png.tmp.* later).
A stand-in gnuplot on PATH answers the terminal probe, marks that it runs, then takes 2 s to
write its output, so the signals surely arrive while it works."""
import os, signal, stat, subprocess, sys, tempfile, time

exe = sys.argv[1]
FAKE = r"""#!/bin/sh
# stand-in gnuplot: `-e "set terminal"` probe, else `-e "sa_output='NAME'" SCRIPT`
if [ "$2" = "set terminal" ]; then echo "pngcairo png"; exit 0; fi
out=$(printf '%s' "$2" | sed "s/^sa_output='\(.*\)'\$/\1/")
: > "$out"
touch "$SA_FAKE_MARK"
sleep 2
echo "late bytes" > "$out"
"""
CASE = "[hmsa]\nanalysis = statics\nS = 0, 2.5\nb2 = 3, 0.16\n"

fails = []
with tempfile.TemporaryDirectory() as tmp:
    bindir = os.path.join(tmp, "bin")
    os.mkdir(bindir)
    gp = os.path.join(bindir, "gnuplot")
    with open(gp, "w") as f:
        f.write(FAKE)
    os.chmod(gp, os.stat(gp).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    case, out, mark = os.path.join(tmp, "s.ini"), os.path.join(tmp, "out"), os.path.join(tmp, "mark")
    with open(case, "w") as f:
        f.write(CASE)
    env = dict(os.environ, PATH=bindir + ":" + os.environ.get("PATH", "/usr/bin:/bin"),
               SA_FAKE_MARK=mark)
    p = subprocess.Popen([exe, "run", case, "--out", out, "--quiet"], env=env,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    t0 = time.time()
    while not os.path.exists(mark) and p.poll() is None and time.time() - t0 < 60:
        time.sleep(0.01)
    if p.poll() is not None:
        fails.append(f"the run ended (rc={p.returncode}) before gnuplot started")
    else:
        p.send_signal(signal.SIGTERM)
        time.sleep(0.1)
        p.send_signal(signal.SIGTERM)
        try:
            _, err = p.communicate(timeout=10)
            if p.returncode != 3:
                fails.append(f"exit {p.returncode} after two signals, expected 3; {err[-300:]}")
        except subprocess.TimeoutExpired:
            p.kill()
            p.communicate()
            fails.append("did not stop within 10 s of the second signal")
        time.sleep(2.5)  # the stand-in would have written by now
        temps = [n for n in os.listdir(out) if ".tmp." in n]
        if temps:
            fails.append(f"temporaries in the results folder after softact exited: {temps}")
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
