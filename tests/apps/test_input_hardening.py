#!/usr/bin/env python3
"""Input hardening of the case-file reader and the command line (issue 16). Each check names the
defect it guards; a failure prints what differed. Usage: test_input_hardening.py SOFTACT."""
import os, subprocess, sys, tempfile

exe = sys.argv[1]
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

    # --- an error found from a default used to name no file or line ("default: dt_out exceeds t_end")
    c = case("t_end_below_default", HMSA + "t_end = 0.005\n")
    expect("error_from_default", run(["check", c]), 1, [c + ":3:", "t_end = 0.005", "default dt_out = 0.01"])
    r = run(["check", case("statics", STATICS), "--set", "hmsa.t_end=0.005"])
    expect("error_from_default_set", r, 1, ["--set", "t_end = 0.005", "default dt_out"])

for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
