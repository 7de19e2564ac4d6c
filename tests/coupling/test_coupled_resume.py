#!/usr/bin/env python3
"""Runs resumed from the fixture run's checkpoint after step 6 (test_coupled_run.py, ctest
fixture `dem_short_run`; its folder is argv[3], read only: every run here works on a copy):
 - resumed as it was: it ends with the same bending.csv, bit for bit (the checkpoint is written
   at a step boundary; both runs refactorise the FEM and redo the DEM set-up pass after it:
   the resumed run must take the same floating-point path, so any state left out of the
   checkpoint shows);
 - the staggered scheme with Robin springs finishes with every run check and the bed's force
   balance (momentum: the walls carry the bed weight, to 10 % of the load) holding;
 - with an indentation limit no bed meets: the coupling refuses every pass but the last and
   the run check stops the run with its named diagnosis; with an overlap limit no bed meets:
   an overlap up in the rigid barrel stops the run at once (no wall position cures it), one
   next to the wall is refused like the indentation;
 - a step that cannot converge in its passes is halved, then stops the run with a diagnosis,
   keeping the rows before it."""
import csv, os, sys, tempfile
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from coupled_run_util import (balance_fails, bed_weight, fixture_args, read_summary,
                              resume_differs, resumed_run, short_run_args)

exe, case, out = fixture_args(sys.argv)
args = short_run_args(exe, case, out)
W = bed_weight(read_summary(out))
fails = []
with tempfile.TemporaryDirectory() as tmp:
    # resume from the checkpoint in a copy of the results: same rows, bit for bit
    fails += resume_differs(args, out, tmp, 1500)
    # the staggered scheme with Robin springs (iterations = 1) from the same checkpoint: it
    # must finish with every run check and the bed's force balance (momentum) holding
    out3, r = resumed_run(out, args, tmp, "staggered", [
        "coupling.iterations=1", "coupling.interface_stiffness=1",
        "coupling.interface_tangential=1"])
    if r.returncode != 0:
        fails.append(f"staggered run failed: {r.returncode} {r.stderr[-1500:]}")
    else:
        st = read_summary(out3)
        if st.get("status") != "completed" or "iterated_steps" in st:
            fails.append(f"staggered run: status {st.get('status')}, iterated {st.get('iterated_steps')}")
        rows3 = list(csv.DictReader(open(os.path.join(out3, "bending.csv")).readlines()[1:]))
        fails += balance_fails(rows3, W, "staggered: ")
    # a pass whose bead indents the silicone wall beyond [dem] max_indentation (or whose grains
    # overlap beyond max_overlap next to the wall) is never accepted while passes remain (the
    # FEM's wall is tried next); when none are left the run check stops the run with its
    # diagnosis. With a limit below any resting bead's indentation (1e-6 of d: the bed's weight
    # alone indents the silicone by ~1e-2 of d) and 3 passes, exactly two passes are refused (no
    # halving: each half step would be refused alike before the run check)
    mark = "not accepted, the FEM's wall is tried next"
    def refused_passes(out_new):
        # the file logs every level; a resumed run may append to it: count the new lines only
        return (open(os.path.join(out_new, "softact.log")).read().count(mark)
                - open(os.path.join(out, "softact.log")).read().count(mark))
    out4, r = resumed_run(out, args, tmp, "overlap_rule",
                          ["coupling.iterations=3", "dem.max_indentation=1e-6", "coupling.cut_max=0"])
    refused = refused_passes(out4)
    if r.returncode == 0 or refused != 2 or "above [dem] max_indentation" not in r.stderr:
        fails.append(f"indentation rule: exit {r.returncode}, {refused} passes refused (2 "
                     f"expected), stderr tail: {r.stderr[-600:]}")
    # an overlap between two grains up in the rigid barrel is no wall's doing: the run stops at
    # once with the overlap diagnosis, no pass refused (a softening-100 bed at 5 mm spent 15
    # passes and a halving on one); an over-limit overlap next to the wall is refused as above
    out5, r5 = resumed_run(out, args, tmp, "barrel_overlap",
                           ["coupling.iterations=3", "dem.max_overlap=1e-6", "coupling.cut_max=0"])
    refused5 = refused_passes(out5)
    expect5 = 0 if "in the rigid barrel" in r5.stderr else 2
    if r5.returncode == 0 or refused5 != expect5 or "exceeds [dem] max_overlap" not in r5.stderr:
        fails.append(f"overlap rule: exit {r5.returncode}, {refused5} passes refused "
                     f"({expect5} expected), stderr tail: {r5.stderr[-600:]}")
    # a run stopped inside a step reports the last accepted row in summary.ini, not the FEM
    # state of its last, refused pass (the cavity volume once came from that pass)
    st4 = read_summary(out4)
    rows4 = list(csv.DictReader(open(os.path.join(out4, "bending.csv")).readlines()[1:]))
    if rows4 and st4.get("status") == "stopped early":
        v_row, v_sum = float(rows4[-1]["volume_change_rel"]), float(st4["volume_change_rel"])
        if abs(v_sum - v_row) > 1e-5 * abs(v_row) + 1e-12:
            fails.append(f"stopped run: summary volume_change_rel {v_sum} is not the last row's "
                         f"{v_row}")
    else:
        fails.append(f"indentation rule: status {st4.get('status')}, {len(rows4)} rows")
    # a step whose fixed-point residual stays above the guard (10 x iteration_tol) after its last
    # pass is a failed step: the run stops with a diagnosis and keeps the rows before it (it
    # was accepted with a warning, and a stiff bed's angle then jumped, docs/dem.md). Two passes
    # cannot reach 1e-8 of the wall's displacement. Before it stops, the step is halved
    # (cut_max = 1): the whole step fails, then its first half, which may not be halved again.
    out5, r = resumed_run(out, args, tmp, "unconverged",
                          ["coupling.iterations=2", "coupling.iteration_tol=1e-9",
                           "coupling.cut_max=1"])
    st5 = read_summary(out5) if os.path.exists(os.path.join(out5, "summary.ini")) else {}
    rows5 = list(csv.DictReader(open(os.path.join(out5, "bending.csv")).readlines()[1:]))
    if (r.returncode != 2 or "did not converge in 2 passes" not in r.stderr
            or st5.get("status") != "stopped early" or len(rows5) != 2
            or st5.get("halved_steps") != "1"):
        fails.append(f"unconverged step: exit {r.returncode}, status {st5.get('status')}, "
                     f"{len(rows5)} rows (2 expected), halved {st5.get('halved_steps')} (1 "
                     f"expected), stderr tail: {r.stderr[-600:]}")
for f in fails:
    print(f)
sys.exit(1 if fails else 0)
