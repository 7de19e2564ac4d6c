#!/usr/bin/env python3
"""A short FEM-DEM run (3 mm beads, 0.75 mm stroke, default actuator mesh; every coupling step
iterated, as in the scene) passes every run check and reports consistent numbers. Its results
folder (argv[3], kept in the build tree) is the ctest fixture `dem_short_run`: the resumed runs
of test_coupled_resume.py and the two-rank run of test_coupled_run_mpi.py start from its
checkpoint after step 6 instead of pouring beds of their own. References independent of the
coupling code:
 - force balance of the bed (conservation of momentum, quasi-static): piston + walls + barrel
   forces carry the bed weight, |error| <= 10 % of the load (piston force + weight). At the
   start the load is only the bed weight (0.15 N for 3 mm beads) and the settled bed's residual
   motion (rms speed < 2 mm/s) changes its momentum by ~0.01 N per coupling step (measured 7 %
   at s = 0 and 0.1 mm, then 0.1-2 % once the piston loads the bed), hence 10 %, the run's own
   [dem] balance_tol;
 - the weight: grains x (pi d^3 / 6) x density x g from summary.ini's grain count;
 - the piston force grows with the piston displacement (the bed is compressed);
 - no grain lost (count unchanged), largest overlap below 5 % of the diameter, packing fraction
   of a poured monodisperse bed between 0.45 and 0.64 (random loose to random close packing)."""
import csv, os, shutil, subprocess, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coupled_run_util import balance_fails, bed_weight, read_summary, short_run_args


exe, case, out = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(out, ignore_errors=True)
args = short_run_args(exe, case, out)
r = subprocess.run(args, capture_output=True, text=True, timeout=1500)
if r.returncode != 0:
    print("coupled run failed:", r.returncode, r.stderr[-2000:])
    sys.exit(1)
rows = list(csv.DictReader(open(os.path.join(out, "bending.csv")).readlines()[1:]))
summ = read_summary(out)
fails = []
if summ.get("status") != "completed":
    fails.append(f"status {summ.get('status')}")
# the wall's side of a bead contact: the silicone's small-strain Young's modulus from the
# case's Yeoh law (mu0 = 2 c10, K = kappa_ratio mu0: E = 9 K mu0 / (3 K + mu0))
mu0 = 2 * 0.11e6
E_sil = 9 * 500 * mu0 * mu0 / (3 * 500 * mu0 + mu0)
if abs(float(summ.get("silicone_contact_young", 0)) / E_sil - 1) > 1e-5:
    fails.append(f"silicone contact modulus {summ.get('silicone_contact_young')} Pa, "
                 f"expected {E_sil:.6g}")
if float(rows[-1]["max_indentation"]) <= 0:
    fails.append("the loaded bed does not indent the silicone wall")
W = bed_weight(summ)
fails += balance_fails(rows, W, "")
for row in rows:
    if float(row["max_overlap"]) >= 0.05:
        fails.append(f"overlap {row['max_overlap']}")
    # the beads indent the silicone wall (the scene's wall_contact = silicone), less than
    # the run check's limit ([dem] max_indentation 0.4 of d)
    if not 0 <= float(row["max_indentation"]) <= 0.4:
        fails.append(f"indentation {row['max_indentation']}")
    phi = float(row["packing_fraction"])
    if not 0.45 <= phi <= 0.64:
        fails.append(f"packing fraction {phi}")
if len(rows) < 3 or float(rows[-1]["piston_force"]) <= float(rows[1]["piston_force"]):
    fails.append("piston force does not grow with the displacement: "
                 + ", ".join(r["piston_force"] for r in rows))
if abs(float(rows[-1]["piston_displacement"]) - 7.5e-4) > 1e-9:
    fails.append("stroke not reached")
# checkpoint_poured: the poured bed was checkpointed before the preload (the step-6
# checkpoint replaced it; the fixture's users start from that one)
if "checkpoint after coupling step 0 " not in open(os.path.join(out, "softact.log")).read():
    fails.append("checkpoint_poured: no checkpoint of the poured bed in softact.log")
# the scene iterates every step (rollback of DEM and FEM, IQN-ILS): 8 steps, each with at
# least one pass and none left unconverged; test_coupled_resume.py resumes the iterated path
if int(summ.get("iterated_steps", 0)) != 8 or int(summ.get("unconverged_steps", 1)) != 0:
    fails.append(f"iterated steps {summ.get('iterated_steps')} (8 expected), "
                 f"{summ.get('unconverged_steps')} unconverged")
if os.path.exists(os.path.join(out, "checkpoint", "step.ckpt")):
    fails.append("the step checkpoint was left behind")
for f in fails:
    print(f)
sys.exit(1 if fails else 0)
