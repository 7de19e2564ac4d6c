#!/usr/bin/env python3
"""--help, --version, keys and argument errors: documented exit codes (0 ok, 1 bad input)."""
import subprocess, sys

exe = sys.argv[1]
fails = []

def run(*args):
    return subprocess.run([exe, *args], capture_output=True, text=True, timeout=60)

r = run("--help")
if r.returncode != 0 or "usage: softact run" not in r.stdout or "exit status" not in r.stdout:
    fails.append(f"--help: rc={r.returncode} out={r.stdout[:200]!r}")
r = run("--version")
if r.returncode != 0 or not r.stdout.startswith("softact "):
    fails.append(f"--version: rc={r.returncode} out={r.stdout!r}")
r = run("keys")
if r.returncode != 0 or "| key | type | unit | default | range | meaning |" not in r.stdout:
    fails.append(f"keys: rc={r.returncode}")
for args, needle in [((), "usage"), (("frobnicate", "x.ini"), "unknown command"),
                     (("run",), "needs a case file"), (("run", "x.ini", "--bogus"), "unknown option"),
                     (("run", "/nonexistent/x.ini"), "cannot open case file"),
                     (("check", "x.ini", "--set"), "--set needs a value")]:
    r = run(*args)
    if r.returncode != 1 or needle not in (r.stderr + r.stdout):
        fails.append(f"{args}: expected exit 1 and '{needle}', got rc={r.returncode} err={r.stderr[:300]!r}")
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
