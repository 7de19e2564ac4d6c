#!/usr/bin/env python3
"""When the steps collapse at the edge of the model's domain, the diagnosis fits the model that
ran: a Zener run with an enormous load (b2 = 1e300) must not be told about the polymer chain's
pole or advised to raise lambda_max (a PC key it does not have), but about its own domain and
the load key; the PC model keeps its pole diagnosis."""
import os, subprocess, sys, tempfile

exe = sys.argv[1]
CASES = [  # (label, case, words required, words forbidden)
    ("zener const", "[hmsa]\nmodel = zener\nb2 = 1e300\nt_end = 1\n",
     ["Zener", "lambda > 0", "b2"], ["PC pole", "lambda_max"]),
    ("zener sq", "[hmsa]\nmodel = zener\nloading = sq\nb_a = 1e150\nt_end = 1\n",
     ["Zener", "b_a"], ["PC pole", "lambda_max"]),
    ("pc const", "[hmsa]\nmodel = pc\nb2 = 1e300\nt_end = 1\n",
     ["PC pole", "lambda_max"], ["Zener"]),
]
fails = []
with tempfile.TemporaryDirectory() as tmp:
    for label, text, want, refuse in CASES:
        case = os.path.join(tmp, "c.ini")
        with open(case, "w") as f:
            f.write("[run]\nplots = false\n" + text)
        r = subprocess.run([exe, "run", case, "--out", os.path.join(tmp, "out"), "--quiet"],
                           capture_output=True, text=True, timeout=60)
        if r.returncode != 2:
            fails.append(f"{label}: exit {r.returncode}, expected 2 (numerical failure)")
        msg = r.stderr
        for w in want:
            if w not in msg:
                fails.append(f"{label}: the diagnosis lacks '{w}': {msg.strip()[:400]}")
        for w in refuse:
            if w in msg:
                fails.append(f"{label}: the diagnosis mentions '{w}': {msg.strip()[:400]}")
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
