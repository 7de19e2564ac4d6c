#!/usr/bin/env python3
"""Table of bench/dem/dem_step_study.sh: each variant's bending angle and piston force at the
given piston displacements, its difference from the finest time step (same bed), the round-off
pair's difference (the bed's chaos alone) and the variant's CPU time.
  python3 bench/dem/dem_step_table.py OUT [x_mm ...]"""
import csv
import os
import sys

out = sys.argv[1]
xs = [float(a) for a in sys.argv[2:]] or [1.0, 2.0, 3.0]
VARIANTS = ["dt_0.2", "dt_0.2_threads2", "dt_0.1", "dt_0.05"]


def rows(v):
    path = os.path.join(out, v, "bending.csv")
    if not os.path.exists(path):
        return None
    lines = [l for l in open(path) if not l.startswith("#")]
    return {round(float(r["piston_displacement"]) * 1e3, 3): r for r in csv.DictReader(lines)}


def cpu(v):
    path = os.path.join(out, v, "summary.ini")
    if not os.path.exists(path):
        return float("nan")
    for l in open(path):
        if l.startswith("cpu"):
            return float(l.split("=", 1)[1].split(";")[0])
    return float("nan")


data = {v: rows(v) for v in VARIANTS}
finest = next((v for v in reversed(VARIANTS) if data[v]), None)
print("| variant | x [mm] | angle [deg] | force [N] | angle - finest [deg] | force - finest [N] | CPU [s] |")
print("|---|---|---|---|---|---|---|")
for v in VARIANTS:
    if not data[v]:
        continue
    for x in xs:
        r, f = data[v].get(round(x, 3)), data[finest].get(round(x, 3))
        if not r:
            continue
        a, F = float(r["bending_angle"]), float(r["piston_force"])
        da = a - float(f["bending_angle"]) if f else float("nan")
        dF = F - float(f["piston_force"]) if f else float("nan")
        print(f"| {v} | {x:.2f} | {a:.4f} | {F:.2f} | {da:+.4f} | {dF:+.2f} | {cpu(v):.0f} |")
if data["dt_0.2"] and data["dt_0.2_threads2"]:
    print("\nround-off pair (one FEM thread against two, same time step): angle / force differences")
    for x in xs:
        a, b = data["dt_0.2"].get(round(x, 3)), data["dt_0.2_threads2"].get(round(x, 3))
        if a and b:
            print(f"  x = {x:.2f} mm: {float(b['bending_angle']) - float(a['bending_angle']):+.4f} deg, "
                  f"{float(b['piston_force']) - float(a['piston_force']):+.2f} N")
