#!/usr/bin/env python3
"""Table of bad case files: each must exit with status 1, name the file:line and the key (or
section) at fault, say what was expected, and leave no results folder content behind."""
import os, subprocess, sys, tempfile

exe = sys.argv[1]
HMSA = "[hmsa]\nmodel = zener\n"

# (name, case text, --set options, strings the message must contain)
TABLE = [
    ("unknown_key", HMSA + "etta = 5\n", [], [":3:", "etta", "did you mean 'eta'"]),
    ("section_typo", "[hmsaa]\nmodel = zener\n", [], [":1:", "unknown section [hmsaa]", "did you mean [hmsa]"]),
    ("not_a_number", HMSA + "eta = abc\n", [], [":3:", "eta", "expected a real number"]),
    ("out_of_range", HMSA + "eta = -5\n", [], [":3:", "eta", "expected a real number in"]),
    ("bad_choice", "[hmsa]\nmodel = maxwell\n", [], [":2:", "model", "expected one of"]),
    ("duplicate_key", HMSA + "eta = 5\neta = 10\n", [], [":4:", "eta", "given twice"]),
    ("key_before_section", "eta = 5\n" + HMSA, [], [":1:", "eta", "before any [section]"]),
    ("syntax_error", HMSA + "this line has no equals sign\n", [], [":3:", "syntax error"]),
    ("empty_file", "", [], [":1:", "empty case file"]),
    ("comments_only", "; nothing here\n# nor here\n", [], ["empty case file"]),
    ("binary_garbage", None, [], [":1:", "control byte"]),
    ("no_scene", "[run]\ntitle = x\n", [], ["no scene section found"]),
    ("bad_set_value", HMSA, ["hmsa.eta=oops"], ["--set", "eta", "expected a real number"]),
    ("bad_set_syntax", HMSA, ["hmsa_eta"], ["--set", "section.key=value"]),
    ("bad_run_key", "[run]\nvtk_format = xml\n" + HMSA, [], [":2:", "vtk_format", "expected one of binary|ascii"]),
    ("two_scenes", HMSA + "[mesh]\n", [], ["describes one scene"]),
    ("missing_mesh_file", "[mesh]\ngeo = no_such_mesh.geo\n", [], [":2:", "geo", "no_such_mesh.geo", "not found"]),
    ("bad_mesh_size", "[mesh]\nh = 0\n", [], [":2:", "h", "expected a real number in"]),
    # FEM-DEM scene: refused before LIGGGHTS starts
    ("dem_unsafe_time_step", "[grains]\n[dem]\ndt_fraction = 0.5\n", [], [":3:", "dt_fraction", "expected a real number in"]),
    ("dem_beads_larger_than_bore", "[grains]\ndiameter = 6e-3\n", [], ["diameter", "smaller than the bore radius"]),
    ("dem_stroke_longer_than_barrel", "[grains]\n[piston]\nstroke = 0.035\n", [], ["stroke", "longer than the barrel"]),
    ("dem_rest_window_rigid_contact", "[grains]\nwall_contact = grain\n[coupling]\nwall_every_rest = 10\n", [], ["wall_every_rest = 10", "wall_contact", "allowed: 1"]),
    ("dem_negative_friction", "[grains]\nfriction_wall = -0.1\n", [], [":2:", "friction_wall", "expected a real number in"]),
]

def write_case(path, text, name):
    if text is None:  # binary garbage with NUL bytes and control characters
        data = bytes((i * 97 + 13) % 256 for i in range(600))
        with open(path, "wb") as f:
            f.write(data)
    else:
        with open(path, "w") as f:
            f.write(text)

fails = []
with tempfile.TemporaryDirectory() as tmp:
    for name, text, sets, needles in TABLE:
        case = os.path.join(tmp, f"{name}.ini")
        write_case(case, text, name)
        out = os.path.join(tmp, "out_" + name)
        args = [exe, "run", case, "--out", out, "--quiet"]
        for s in sets:
            args += ["--set", s]
        r = subprocess.run(args, capture_output=True, text=True, errors="replace", timeout=60)
        msg = r.stderr
        if r.returncode != 1:
            fails.append(f"{name}: exit {r.returncode}, expected 1; stderr: {msg[:400]}")
        for n in needles:
            if n not in msg:
                fails.append(f"{name}: message lacks {n!r}: {msg[:400]}")
        if text is not None and ":" in needles[0] and needles[0].startswith(":") and case not in msg:
            fails.append(f"{name}: message does not name the file {case}: {msg[:300]}")
        if os.path.exists(out) and os.listdir(out):
            fails.append(f"{name}: results folder has content: {os.listdir(out)}")
        # check must fail the same way
        r2 = subprocess.run([exe, "check", case] + sum([["--set", s] for s in sets], []),
                            capture_output=True, text=True, errors="replace", timeout=60)
        if r2.returncode != 1:
            fails.append(f"{name}: check exit {r2.returncode}, expected 1")
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
