#!/usr/bin/env python3
"""The short FEM-DEM run with LIGGGHTS on two MPI ranks ([dem] mpi_ranks = 2: softact starts
itself under mpirun; rank 0 runs the FEM, the coupling and the output, rank 1 half of the bore).
It starts from the fixture run's checkpoint after step 6 (test_coupled_run.py, ctest fixture
`dem_short_run`, one rank; argv[3], read only): LIGGGHTS' restart of one rank's grains read back
and redistributed over two, the last two stroke steps on two ranks, a checkpoint after step 7
written by rank 0 from both ranks' grains. References independent of the coupling code, as in
test_coupled_run.py:
 - force balance of the bed (conservation of momentum): the forces on piston, wall and barrel,
   summed over the triangles of both ranks, carry the bed weight to 10 % of the load;
 - the weight from summary.ini's grain count (the grains of both ranks): no grain lost in the
   redistribution;
 - largest overlap below 5 % of d, packing in 0.45..0.64, the piston force grows with the
   displacement;
 - summary.ini says mpi_ranks = 2 and the log names the two ranks.
And a resume from the two-rank checkpoint ends with the same bending.csv, bit for bit; bad
input found after the relaunch exits 1 with its message, leaving nothing; more ranks than cores
are refused before mpirun starts."""
import csv, os, subprocess, sys, tempfile
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coupled_run_util import (balance_fails, bed_weight, fixture_args, read_summary,
                              resume_differs, resumed_run, short_run_args)

exe, case, fixture = fixture_args(sys.argv)
n_fixture = int(read_summary(fixture)["grains"])
MPI = ["dem.mpi_ranks=2", "coupling.checkpoint_every=7"]
fails = []
with tempfile.TemporaryDirectory() as tmp:
    out, r = resumed_run(fixture, short_run_args(exe, case, fixture), tmp, "run", MPI, 1200)
    if r.returncode != 0:
        print("coupled MPI run failed:", r.returncode, r.stderr[-3000:])
        sys.exit(1)
    # the run as made: the fixture's arguments in its own folder, on two ranks, resumed
    args = short_run_args(exe, case, out) + sum([["--set", kv] for kv in
                                                 ["coupling.resume=true"] + MPI], [])
    rows = list(csv.DictReader(open(os.path.join(out, "bending.csv")).readlines()[1:]))
    summ = read_summary(out)
    log = open(os.path.join(out, "softact.log")).read()
    if summ.get("status") != "completed":
        fails.append(f"status {summ.get('status')}")
    if summ.get("mpi_ranks") != "2" or "LIGGGHTS on 2 MPI ranks" not in log:
        fails.append(f"not on two ranks: mpi_ranks = {summ.get('mpi_ranks')}")
    if int(summ["grains"]) != n_fixture:
        fails.append(f"{summ['grains']} grains on two ranks, {n_fixture} in the checkpoint")
    fails += balance_fails(rows, bed_weight(summ), "")
    for row in rows:
        if float(row["max_overlap"]) >= 0.05:
            fails.append(f"overlap {row['max_overlap']}")
        if not 0.45 <= float(row["packing_fraction"]) <= 0.64:
            fails.append(f"packing fraction {row['packing_fraction']}")
    if len(rows) != 4 or float(rows[-1]["piston_force"]) <= float(rows[-2]["piston_force"]):
        fails.append("piston force does not grow with the displacement: "
                     + ", ".join(r["piston_force"] for r in rows))
    if "checkpoint after coupling step 7 " not in log:
        fails.append("no two-rank checkpoint after step 7 in softact.log")
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
