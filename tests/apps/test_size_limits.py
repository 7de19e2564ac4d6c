#!/usr/bin/env python3
"""Products of case keys that size an array or a loop are checked by `softact check` (and so
before `softact run` creates anything), each key alone inside its range: the error names the
keys and the limit. Before, [hmsa_sweep] measure_periods x samples_per_period = 65536 x 65536
wrapped an int to 0 (exit 0, every amplitude 0) and 30000 x 100000 crashed leaving temporaries."""
import os, subprocess, sys, tempfile

exe = sys.argv[1]
help_text = subprocess.run([exe, "--help"], capture_output=True, text=True).stdout
SWEEP = ("[hmsa]\nanalysis = sweep\nloading = sq\nsigma = -1\n[hmsa_sweep]\nn_omega = 5\n"
         "continuation = false\nrefine = false\n")
# (label, scene section that must be built, case text, words the message must contain)
CASES = [
    ("sweep 65536 x 65536", "[hmsa]", SWEEP + "measure_periods = 65536\nsamples_per_period = 65536\n",
     ["measure_periods", "samples_per_period", "at most"]),
    ("sweep 30000 x 100000", "[hmsa]", SWEEP + "measure_periods = 30000\nsamples_per_period = 100000\n",
     ["measure_periods", "samples_per_period", "at most"]),
    ("sweep transient_tau", "[hmsa]", SWEEP + "transient_tau = 1e300\n",
     ["transient_tau", "omega_max", "at most"]),
    ("settling grid", "[hmsa]", "[hmsa]\nmodel = zener\nt_end = 1e300\ndt_out = 1e299\n",
     ["t_end", "at most"]),
    ("footing mesh", "[footing]", "[footing]\ncells = 200\ndomain_width = 100\n[fill]\ncohesion = 10e3\n",
     ["cells", "domain_width", "at most"]),
    ("coupling steps", "[grains]", "[grains]\n[coupling]\ninterval = 1e-300\n",
     ["stroke", "interval", "at most"]),
    ("grains", "[grains]", "[grains]\ndiameter = 1e-4\n", ["diameter", "grains", "at most"]),
]

fails = []
with tempfile.TemporaryDirectory() as tmp:
    for label, scene, text, words in CASES:
        if scene not in help_text:
            continue  # module not built
        case = os.path.join(tmp, "c.ini")
        with open(case, "w") as f:
            f.write(text)
        # run too for the sweeps of the issue (it must refuse before creating anything)
        for cmd in ("check", "run") if label.startswith("sweep 3") else ("check",):
            out = os.path.join(tmp, "out")
            try:
                r = subprocess.run([exe, cmd, case, "--out", out] if cmd == "run" else [exe, cmd, case],
                                   capture_output=True, text=True, timeout=60)
            except subprocess.TimeoutExpired:
                fails.append(f"{label}: softact {cmd} ran for a minute instead of refusing the case")
                continue
            if r.returncode != 1:
                fails.append(f"{label}: softact {cmd} exit {r.returncode}, expected 1 (bad input)")
            missing = [w for w in words if w not in r.stderr]
            if missing:
                fails.append(f"{label}: softact {cmd} message lacks {missing}: {r.stderr.strip()[:300]}")
            if cmd == "run" and os.path.exists(out):
                fails.append(f"{label}: softact run left {sorted(os.listdir(out))}")
                subprocess.run(["rm", "-rf", out])
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
