"""Shared by the coupled-run tests: the short run that is their fixture, summary.ini's keys,
the bed's force balance, and runs resumed from a checkpoint."""
import math, os, shutil, subprocess, sys


def short_run_args(exe, case, out):
    """The fixture run (test_coupled_run.py) into folder out: 5 preload + 3 stroke steps, a
    checkpoint after step 6 (one stroke step before the end), which every user resumes.
    softening 1000 (the scene uses 100): the pour at the 3.2x larger time step keeps it near
    3 min; the machinery and the checks are the same. One process (the scene's default is two
    MPI ranks: test_coupled_run_mpi.py runs those) and one FEM thread: on an AMD Zen machine
    (OpenBLAS' Zen kernels, 2026-12-07) two FEM threads do not repeat a run bit for bit (the
    resumed run differed by 1e-5 from the first resumed step on; with one thread it is
    identical), which is not what these tests are about: the checkpoint's contents."""
    return [exe, "run", case, "--out", out, "--quiet", "--set", "dem.mpi_ranks=1",
            "--set", "run.threads=1", "--set", "grains.softening=1000",
            "--set", "grains.diameter=3e-3", "--set", "piston.stroke=7.5e-4",
            "--set", "coupling.vtk_every=0", "--set", "run.plots=false",
            "--set", "coupling.checkpoint_every=6", "--set", "coupling.checkpoint_poured=true"]


def fixture_args(argv):
    """(exe, case, folder of the fixture run) from a test's command line; exits when the fixture
    test coupled_run_short has not made the run."""
    exe, case, folder = argv[1], argv[2], argv[3]
    if not os.path.exists(os.path.join(folder, "checkpoint")):
        sys.exit(f"no fixture run in {folder} (test coupled_run_short makes it)")
    return exe, case, folder


def bed_weight(summary, d=3e-3, density=2500):
    """The bed's weight [N] from summary.ini's grain count."""
    return int(summary["grains"]) * math.pi * d ** 3 / 6 * density * 9.81


def balance_fails(rows, W, label):
    """Rows whose forces on the walls do not carry the bed weight W (to 10 % of the load)."""
    out = []
    for row in rows:
        Fp, Fw, Fb = (float(row[k]) for k in ("piston_force", "wall_force_z", "barrel_force_z"))
        err = abs(Fp + Fw + Fb + W) / (abs(Fp) + W)  # forces on the walls carry -W
        if err > 0.10:
            out.append(f"{label}force balance misses by {err:.3f} at s = {row['piston_displacement']}")
    return out


def read_summary(folder):
    """summary.ini's keys (sections flattened), values without their comments."""
    keys = {}
    for line in open(os.path.join(folder, "summary.ini")):
        line = line.split(";")[0].strip()
        if "=" in line:
            k, v = [x.strip() for x in line.split("=", 1)]
            keys[k] = v
    return keys


def resumed_run(out, args, tmp, label, keys, timeout=1500):
    """A copy of the run in out (made with args; its rows dropped) resumed from its checkpoint
    with the extra key=value settings: (folder, completed process)."""
    d = os.path.join(tmp, label)
    shutil.copytree(out, d)
    os.remove(os.path.join(d, "bending.csv"))
    sets = sum([["--set", kv] for kv in ["coupling.resume=true"] + keys], [])
    r = subprocess.run([a if a != out else d for a in args] + sets, capture_output=True,
                       text=True, timeout=timeout)
    return d, r


def resume_differs(args, out, tmp, timeout, keys=()):
    """Resume a copy of the results folder `out` of the run made with `args` (+ keys) from its
    checkpoint and return what differs from the run that went on: [] when bending.csv is the
    same, bit for bit."""
    out2, r = resumed_run(out, args, tmp, "resumed", list(keys), timeout)
    if r.returncode != 0:
        return [f"resumed run failed: {r.returncode} {r.stderr[-1500:]}"]
    a = open(os.path.join(out, "bending.csv")).read().splitlines()
    b = open(os.path.join(out2, "bending.csv")).read().splitlines()
    if a != b:
        return ["resumed run differs from the run that went on:\n" +
                "\n".join(f"  {x}\n  {y}" for x, y in zip(a, b) if x != y)]
    return []
