#!/usr/bin/env python3
"""The short FEM-DEM run with LIGGGHTS on two MPI ranks ([dem] mpi_ranks = 2: softact starts
itself under mpirun; rank 0 runs the FEM, the coupling and the output, rank 1 half of the bore).
References independent of the coupling code, as in test_coupled_run.py:
 - force balance of the bed (conservation of momentum): the forces on piston, wall and barrel,
   summed over the triangles of both ranks, carry the bed weight to 10 % of the load;
 - the weight from summary.ini's grain count (the grains of both ranks);
 - no grain lost, largest overlap below 5 % of d, packing of a poured bed in 0.45..0.64, the
   piston force grows with the displacement;
 - summary.ini says mpi_ranks = 2 and the log names the two ranks.
And a resume from the mid-run checkpoint (LIGGGHTS' restart written by rank 0 from both
ranks' grains, read back and redistributed) ends with the same bending.csv, bit for bit; and
bad input found after the relaunch exits 1 with its message, leaving nothing; more ranks than
cores are refused before mpirun starts."""
import csv, math, os, subprocess, sys, tempfile
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coupled_run_util import read_summary, resume_differs


exe, case = sys.argv[1], sys.argv[2]
with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "run")
    # 5 preload + 2 stroke steps; a checkpoint after step 6 (one stroke step); the same cheap
    # bed as test_coupled_run.py (3 mm beads, softening 1000)
    # one FEM thread: two do not repeat a run bit for bit on an AMD Zen machine
    # (test_coupled_run.py)
    args = [exe, "run", case, "--out", out, "--set", "dem.mpi_ranks=2", "--set", "run.threads=1",
            "--set", "grains.softening=1000", "--set", "grains.diameter=3e-3",
            "--set", "piston.stroke=5e-4", "--set", "coupling.vtk_every=0",
            "--set", "run.plots=false", "--set", "coupling.checkpoint_every=6"]
    r = subprocess.run(args, capture_output=True, text=True, timeout=1200)
    if r.returncode != 0:
        print("coupled MPI run failed:", r.returncode, r.stderr[-3000:])
        sys.exit(1)
    rows = list(csv.DictReader(open(os.path.join(out, "bending.csv")).readlines()[1:]))
    summ = read_summary(out)
    fails = []
    if summ.get("status") != "completed":
        fails.append(f"status {summ.get('status')}")
    if summ.get("mpi_ranks") != "2" or "LIGGGHTS on 2 MPI ranks" not in r.stderr:
        fails.append(f"not on two ranks: mpi_ranks = {summ.get('mpi_ranks')}")
    n = int(summ["grains"])
    W = n * math.pi * 3e-3 ** 3 / 6 * 2500 * 9.81
    for row in rows:
        Fp, Fw, Fb = (float(row[k]) for k in ("piston_force", "wall_force_z", "barrel_force_z"))
        err = abs(Fp + Fw + Fb + W) / (abs(Fp) + W)
        if err > 0.10:
            fails.append(f"force balance misses by {err:.3f} at s = {row['piston_displacement']}")
        if float(row["max_overlap"]) >= 0.05:
            fails.append(f"overlap {row['max_overlap']}")
        if not 0.45 <= float(row["packing_fraction"]) <= 0.64:
            fails.append(f"packing fraction {row['packing_fraction']}")
    if len(rows) != 3 or float(rows[-1]["piston_force"]) <= float(rows[0]["piston_force"]):
        fails.append("piston force does not grow with the displacement: "
                     + ", ".join(r["piston_force"] for r in rows))
    fails += resume_differs(args, out, tmp, 1200)
    # bad input found on rank 0 after the relaunch (a resume with no earlier run): the named
    # error, exit 1 (rank 0's status, passed on by mpirun), nothing made
    none = os.path.join(tmp, "none")
    r = subprocess.run([exe, "run", case, "--out", none, "--set", "dem.mpi_ranks=2",
                        "--set", "coupling.resume=true"], capture_output=True, text=True,
                       timeout=300)
    if r.returncode != 1 or "no earlier run to continue" not in r.stderr or os.path.exists(none):
        fails.append(f"bad input under mpirun: exit {r.returncode}, stderr {r.stderr[-800:]}")
    # more ranks than cores: refused before mpirun starts, naming the key and the range
    many = os.path.join(tmp, "many")
    r = subprocess.run([exe, "run", case, "--out", many, "--set",
                        f"dem.mpi_ranks={os.cpu_count() + 1}"], capture_output=True, text=True,
                       timeout=120)
    if r.returncode != 1 or "mpi_ranks" not in r.stderr or "allowed: 1.." not in r.stderr \
            or os.path.exists(many):
        fails.append(f"too many ranks: exit {r.returncode}, stderr {r.stderr[-400:]}")
    for f in fails:
        print(f)
    sys.exit(1 if fails else 0)
