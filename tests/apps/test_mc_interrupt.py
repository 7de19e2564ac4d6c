#!/usr/bin/env python3
"""Interrupting the Mohr-Coulomb scene: SIGTERM during the geostatic stage stops it with exit
status 3, no temporary file is left, and summary.ini says `status = interrupted` (it said
`failed`, as if a stage had broken). CI mesh as in test_mc_bending; the signal goes 3 s after
the results folder appears (the geostatic stage then runs for several more seconds)."""
import os, signal, subprocess, sys, tempfile, time

exe, case = sys.argv[1], sys.argv[2]
BASE = ["mesh.order=1", "mesh.rings=0", "mesh.h=6e-3", "mc_bending.fill_h=4e-3",
        "mc_bending.stroke=1e-3", "mc_bending.n_steps=20", "mc_bending.vtk_every=0",
        "run.threads=1", "run.plots=0"]
fails = []
with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "run")
    args = [exe, "run", case, "--out", out, "--quiet"] + sum([["--set", s] for s in BASE], [])
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    t0 = time.time()
    while not os.path.isdir(out) and p.poll() is None and time.time() - t0 < 60:
        time.sleep(0.05)
    time.sleep(3)
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=120)
    if p.returncode != 3:
        fails.append(f"exit status {p.returncode} (3 expected): {err[-600:]}")
    if os.path.isdir(out):
        temps = [f for f in os.listdir(out) if ".tmp." in f]
        if temps:
            fails.append(f"temporary files left: {temps}")
        summ = os.path.join(out, "summary.ini")
        status = [l.split("=", 1)[1].split(";")[0].strip() for l in open(summ)
                  if l.startswith("status")] if os.path.exists(summ) else []
        if status != ["interrupted"]:
            fails.append(f"summary.ini status {status} (interrupted expected)")
    else:
        fails.append("no results folder")
for f in fails:
    print(f)
sys.exit(1 if fails else 0)
