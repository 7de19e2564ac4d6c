"""Shared by the coupled-run tests: summary.ini's keys, and a run resumed from its checkpoint
compared with the run that went on."""
import os, shutil, subprocess


def read_summary(folder):
    """summary.ini's keys (sections flattened), values without their comments."""
    keys = {}
    for line in open(os.path.join(folder, "summary.ini")):
        line = line.split(";")[0].strip()
        if "=" in line:
            k, v = [x.strip() for x in line.split("=", 1)]
            keys[k] = v
    return keys


def resume_differs(args, out, tmp, timeout):
    """Copy the results folder `out` of the run made with `args`, resume it from its checkpoint
    (coupling.resume) and return what differs from the run that went on: [] when bending.csv is
    the same, bit for bit."""
    out2 = os.path.join(tmp, "resumed")
    shutil.copytree(out, out2)
    os.remove(os.path.join(out2, "bending.csv"))
    args2 = [a if a != out else out2 for a in args] + ["--set", "coupling.resume=true"]
    r = subprocess.run(args2, capture_output=True, text=True, timeout=timeout)
    if r.returncode != 0:
        return [f"resumed run failed: {r.returncode} {r.stderr[-1500:]}"]
    a = open(os.path.join(out, "bending.csv")).read().splitlines()
    b = open(os.path.join(out2, "bending.csv")).read().splitlines()
    if a != b:
        return ["resumed run differs from the run that went on:\n" +
                "\n".join(f"  {x}\n  {y}" for x, y in zip(a, b) if x != y)]
    return []
