#!/usr/bin/env python3
"""The README's case key reference is the output of `softact keys` (one source: the tables)."""
import subprocess, sys

exe, readme = sys.argv[1], sys.argv[2]
keys = subprocess.run([exe, "keys"], capture_output=True, text=True, check=True).stdout
text = open(readme).read()
missing = [l for l in keys.splitlines() if l.startswith("| `") and l not in text]
for l in missing:
    print("README lacks (regenerate with `softact keys`):", l)
sys.exit(1 if missing else 0)
