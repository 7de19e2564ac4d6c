"""Readers shared by the bench/dem scripts: summary.ini (section.key -> string) and bending.csv
(list of dicts of floats; line 1 is the units line)."""
import csv

def read_summary(path):
    out, sec = {}, ""
    for line in open(path):
        line = line.split(";")[0].strip()
        if line.startswith("["):
            sec = line.strip("[]") + "."
        elif "=" in line:
            k, v = [x.strip() for x in line.split("=", 1)]
            out[sec + k] = v
    return out

def read_curve(path):
    lines = open(path).readlines()[1:]
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(lines)]

def value_at(rows, s, key, tol=0.02e-3):
    """The value of key in the row nearest displacement s [m], None if none lies within tol."""
    best = min(rows, key=lambda r: abs(r["piston_displacement"] - s)) if rows else None
    if not best or abs(best["piston_displacement"] - s) > tol:
        return None
    return best[key]
