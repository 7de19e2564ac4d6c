#!/usr/bin/env python3
"""Input hardening of the case-file reader and the command line (issue 16), and what a run does
to an existing results folder. Each check names the defect it guards; a failure prints what
differed. Usage: test_input_hardening.py SOFTACT [DEM_CASE] (DEM_CASE: the FEM-DEM scene, for the
resume checks; left out when the DEM module is not built)."""
import os, subprocess, sys, tempfile

exe = sys.argv[1]
dem_case = sys.argv[2] if len(sys.argv) > 2 else None
fails = []


def run(args, timeout=60, **kw):
    return subprocess.run([exe] + args, capture_output=True, text=True, errors="replace",
                          timeout=timeout, **kw)


def expect(name, r, status, needles=(), stdout_has=(), stdout_lacks=()):
    if r.returncode != status:
        fails.append(f"{name}: exit {r.returncode}, expected {status}; stderr: {r.stderr[-400:]}")
    for n in needles:
        if n not in r.stderr:
            fails.append(f"{name}: message lacks {n!r}: {r.stderr[-400:]}")
    for n in stdout_has:
        if n not in r.stdout:
            fails.append(f"{name}: output lacks {n!r}")
    for n in stdout_lacks:
        if n in r.stdout:
            fails.append(f"{name}: output has {n!r}")


def write(path, text, mode="w"):
    with open(path, mode) as f:
        f.write(text)
    return path


HMSA = "[hmsa]\nmodel = zener\n"
STATICS = HMSA + "analysis = statics\n"  # < 1 s

with tempfile.TemporaryDirectory() as tmp:
    def case(name, text, mode="w"):
        return write(os.path.join(tmp, name + ".ini"), text, mode)

    # --- 2: a long line is never split. The tail of a comment split at inih's 200-byte buffer
    # used to be parsed as a line of its own (here it set t_end = 7) and shifted line numbers.
    c = case("long_comment", HMSA + "; " + "x" * 197 + "t_end = 7\netta = 5\n")
    expect("long_comment", run(["check", c]), 1, [c + ":4:", "etta"])
    c = case("long_comment_ok", HMSA + "; " + "x" * 197 + "t_end = 7\n")
    expect("long_comment_ok", run(["check", c]), 0, stdout_has=["t_end = 100 "])
    c = case("long_inline_comment", "[hmsa]\nmodel = pc ; " + "y" * 300 + "\n")
    expect("long_inline_comment", run(["check", c]), 0, stdout_has=["model = pc "])
    c = case("long_value", "[run]\ntitle = " + "z" * 300 + "\n" + HMSA)
    expect("long_value", run(["check", c]), 1, [c + ":2:", "line too long"])

    # --- 7: a UTF-8 byte-order mark used to hide the first section ("empty case file")
    c = case("bom", b"\xef\xbb\xbf" + STATICS.encode(), mode="wb")
    expect("bom", run(["check", c]), 0, stdout_has=["analysis = statics"])

    # --- a repeated section used to be merged silently
    c = case("duplicate_section", HMSA + "[run]\ntitle = x\n[hmsa]\neta = 5\n")
    expect("duplicate_section", run(["check", c]), 1, [c + ":5:", "section [hmsa] given twice", "line 1"])

    # --- empty list items used to be dropped silently
    for name, v in [("empty_item_middle", "5,,10"), ("empty_item_end", "5,"), ("empty_item_start", ",5")]:
        c = case(name, HMSA + f"eta = {v}\n")
        expect(name, run(["check", c]), 1, [c + ":3:", "eta", "empty"])

    # --- a folder given as the case file used to say "empty case file"; a FIFO used to hang
    expect("directory_case", run(["check", tmp]), 1, ["is a directory"])
    fifo = os.path.join(tmp, "fifo.ini")
    os.mkfifo(fifo)
    try:
        expect("fifo_case", run(["check", fifo], timeout=20), 1, ["not a regular file"])
    except subprocess.TimeoutExpired:
        fails.append("fifo_case: softact check on a FIFO hangs")

    # --- 10: a control character in a --set value used to go raw into case.ini (a new section)
    c = case("statics", STATICS)
    for name, value in [("set_newline", "run.title=x\n[injected]"), ("set_carriage_return", "run.title=x\ry"),
                        ("set_escape", "run.title=x\x1b[2J")]:
        out = os.path.join(tmp, "out_" + name)
        expect(name, run(["check", c, "--set", value]), 1, ["--set", "control character"],
               stdout_lacks=["[injected]"])
        expect(name + "_run", run(["run", c, "--out", out, "--quiet", "--set", value]), 1, ["control character"])
        if os.path.exists(out):
            fails.append(f"{name}: the refused run made its results folder")

    # --- --set "hmsa.model = pc" used to keep the blanks in the key ("unknown key 'model '")
    expect("set_blanks", run(["check", c, "--set", " hmsa . model =  pc "]), 0, stdout_has=["model = pc "])

    # --- a list given by --set longer than 1023 characters used to be cut silently (64 values
    # set, 43 kept): every value is kept, and the resolved case lists all of them
    r = run(["check", case("statics_list", STATICS), "--set", "hmsa.S=" + ",".join(["-1.23456789012346e-300"] * 64)])
    expect("long_set_list", r, 0)
    line = [l for l in r.stdout.splitlines() if l.startswith("S ")]
    if not line or line[0].split(";")[0].count("e-300") != 64:
        fails.append(f"long_set_list: resolved S does not hold the 64 values: {line[:1]}")

    # --- an error found from a default used to name no file or line ("default: dt_out exceeds t_end")
    c = case("t_end_below_default", HMSA + "t_end = 0.005\n")
    expect("error_from_default", run(["check", c]), 1, [c + ":3:", "t_end = 0.005", "default dt_out = 0.01"])
    r = run(["check", case("statics", STATICS), "--set", "hmsa.t_end=0.005"])
    expect("error_from_default_set", r, 1, ["--set", "t_end = 0.005", "default dt_out"])

    # --- check and keys used to exit 0 when their output could not be written
    if os.path.exists("/dev/full"):
        c = case("statics", STATICS)
        for name, args in [("keys_full", ["keys"]), ("check_full", ["check", c])]:
            with open("/dev/full", "w") as full:
                r = subprocess.run([exe] + args, stdout=full, stderr=subprocess.PIPE, text=True, timeout=60)
            if r.returncode == 0:
                fails.append(f"{name}: exit 0 although standard output could not be written")
            elif "standard output" not in r.stderr:
                fails.append(f"{name}: message does not say what failed: {r.stderr[-300:]}")

    # --- 8: an over-long --out used to be cut to 511 characters and that tree created
    deep = os.path.join(tmp, "deep")
    long_out = os.path.join(deep, *(["d" * 50] * 12))  # ~620 characters
    c = case("statics", STATICS)
    expect("long_out", run(["run", c, "--out", long_out, "--quiet"]), 1, ["too long"])
    if os.path.exists(deep):
        fails.append("long_out: folders were created for a refused --out")
    mid_out = os.path.join(deep, *(["e" * 50] * 8))  # ~420: fits 511 but leaves no room for names
    expect("long_out_400", run(["run", c, "--out", mid_out, "--quiet"]), 1, ["too long"])
    if os.path.exists(deep):
        fails.append("long_out_400: folders were created for a refused --out")

    # --- 6: existing results folders. A run never mixes its files with another run's and never
    # touches a folder that is not a softact run.
    out = os.path.join(tmp, "results", "r")

    def listing(d):
        return sorted(os.listdir(d)) if os.path.isdir(d) else None

    def leftovers():
        return [f for f in os.listdir(os.path.dirname(out)) if f != "r"]

    expect("first_run", run(["run", c, "--out", out, "--quiet", "--set", "run.plots=false"]), 0)
    first = {f: open(os.path.join(out, f), "rb").read() for f in listing(out)}
    # bad input found only at run time (a .geo syntax error): the earlier run stays as it was
    geo = write(os.path.join(tmp, "bad.geo"), "Point(1) = {0, 0, 0;\nnot gmsh at all\n")
    fem = case("bad_geo", "[mesh]\ngeo = bad.geo\n")
    expect("runtime_bad_input", run(["run", fem, "--out", out, "--quiet"], timeout=120), 1, ["bad.geo"])
    now = {f: open(os.path.join(out, f), "rb").read() for f in listing(out)} if os.path.isdir(out) else {}
    if now != first:
        fails.append(f"runtime_bad_input: the earlier run changed: {sorted(first)} -> {sorted(now)}")
    if leftovers():
        fails.append(f"runtime_bad_input: left {leftovers()} beside the results folder")
    # a new run replaces the earlier one as a whole: no stale file survives
    write(os.path.join(out, "centerline_0012.csv"), "stale\n")
    hist = case("history", HMSA + "t_end = 2\n")
    expect("second_run", run(["run", hist, "--out", out, "--quiet", "--set", "run.plots=false"]), 0)
    names = listing(out) or []
    for stale in ["centerline_0012.csv", "statics.csv", "equilibria.csv"]:
        if stale in names:
            fails.append(f"second_run: {stale} of the earlier run is still in the folder: {names}")
    if "history.csv" not in names or "history" not in open(os.path.join(out, "case.ini")).read():
        fails.append(f"second_run: the folder does not hold the new run: {names}")
    if leftovers():
        fails.append(f"second_run: left {leftovers()} beside the results folder")
    # a folder with other content is refused and untouched
    mine = os.path.join(tmp, "mine")
    os.mkdir(mine)
    write(os.path.join(mine, "notes.txt"), "my notes\n")
    expect("foreign_folder", run(["run", c, "--out", mine, "--quiet"]), 1, ["not a softact run"])
    if listing(mine) != ["notes.txt"] or open(os.path.join(mine, "notes.txt")).read() != "my notes\n":
        fails.append(f"foreign_folder: the folder changed: {listing(mine)}")
    expect("file_as_out", run(["run", c, "--out", os.path.join(mine, "notes.txt"), "--quiet"]), 1,
           ["not a folder"])
    # an empty folder is used as it is; bad input leaves it empty again
    empty = os.path.join(tmp, "empty")
    os.mkdir(empty)
    expect("empty_folder_bad", run(["run", fem, "--out", empty, "--quiet"], timeout=120), 1)
    if listing(empty) != []:
        fails.append(f"empty_folder_bad: left {listing(empty)}")
    expect("empty_folder", run(["run", c, "--out", empty, "--quiet", "--set", "run.plots=false"]), 0)
    if "case.ini" not in (listing(empty) or []):
        fails.append(f"empty_folder: no results in the empty folder: {listing(empty)}")
    # folders made for a run that fails on bad input are removed again, parents included
    made = os.path.join(tmp, "made")
    expect("made_bad", run(["run", fem, "--out", os.path.join(made, "a", "b"), "--quiet"], timeout=120), 1)
    if os.path.exists(made):
        fails.append("made_bad: the folders made for the run are left")

    # --- resume (FEM-DEM): continues its own folder, must find an earlier run there, and a
    # refused resume leaves the folder's case.ini as it was
    if dem_case:
        r = run(["run", dem_case, "--out", os.path.join(tmp, "none"), "--quiet", "--set", "coupling.resume=true"])
        expect("resume_missing", r, 1, ["no earlier run to continue"])
        if os.path.exists(os.path.join(tmp, "none")):
            fails.append("resume_missing: the refused resume made its folder")
        before = listing(out)
        ini = open(os.path.join(out, "case.ini"), "rb").read()
        coarse = ["--set", "mesh.h=0.008", "--set", "mesh.order=1"]  # the refusal comes after the FEM set-up
        r = run(["run", dem_case, "--out", out, "--quiet", "--set", "coupling.resume=true"] + coarse, timeout=600)
        expect("resume_refused", r, 1, ["no checkpoint"])
        if listing(out) != before or open(os.path.join(out, "case.ini"), "rb").read() != ini:
            fails.append(f"resume_refused: the folder changed: {before} -> {listing(out)}")

for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
