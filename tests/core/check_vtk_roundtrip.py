#!/usr/bin/env python3
"""Reads softact's legacy VTK files back with VTK's own readers and compares with what the
writer was given (manifest.json, expected values as exact hex floats).

usage: check_vtk_roundtrip.py WRITER_EXE WORKDIR [-v]

Checks, for every file: dataset type; point coordinates; cell types and connectivity (grid)
or one vertex per point (POLYDATA); each array's name, location, number of components,
number of tuples, storage type (double) and values; no extra arrays. Also checks that the
.vtk.series index is valid JSON in ParaView's layout listing the files with their times.

Tolerance: BINARY stores the float64 bytes, so values must be bit-identical. ASCII stores
%.17g, which round-trips every double exactly through a correctly rounded reader (17
significant digits suffice for IEEE binary64), so exact equality is expected there too; the
check allows |a - b| <= 1e-15 |b| (a few ulp) so that a reader with a slightly inexact
decimal parser is not mistaken for a writer bug, and -v reports how many were bit-exact.
Silent on success; exit 77 (ctest SKIP) if this python has no vtk module."""
import json
import math
import os
import shutil
import subprocess
import sys

try:
    from vtkmodules.vtkIOLegacy import vtkGenericDataObjectReader
    from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkUnstructuredGrid
except ImportError:
    print("SKIP: %s has no vtk module (Debian: python3-vtk9)" % sys.executable)
    sys.exit(77)

RTOL_ASCII = 1e-15
failures = []
stats = {"ascii": [0, 0], "binary": [0, 0]}  # [bit-exact, total]


def fail(msg):
    failures.append(msg)


def same(a, b, enc):
    """Binary: bit-identical; ASCII: |a-b| <= RTOL |b| (exact expected, see module doc)."""
    st = stats[enc]
    st[1] += 1
    if a == b and math.copysign(1.0, a) == math.copysign(1.0, b):
        st[0] += 1
        return True
    if enc == "binary":
        return False
    return abs(a - b) <= RTOL_ASCII * abs(b)


def read(path):
    errors = []
    r = vtkGenericDataObjectReader()
    r.SetFileName(path)
    r.ReadAllScalarsOn()
    r.ReadAllVectorsOn()
    r.ReadAllTensorsOn()
    r.ReadAllFieldsOn()
    r.AddObserver("ErrorEvent", lambda obj, ev: errors.append(ev))
    r.AddObserver("WarningEvent", lambda obj, ev: errors.append(ev))
    r.Update()
    if errors:
        fail("%s: VTK reader reported %s" % (path, errors))
    return r.GetOutput()


def check_array(tag, arr, spec, ntuples, enc):
    if arr is None:
        fail("%s: array %s missing" % (tag, spec["name"]))
        return
    if arr.GetNumberOfComponents() != spec["ncomp"]:
        fail("%s: %s has %d components, expected %d"
             % (tag, spec["name"], arr.GetNumberOfComponents(), spec["ncomp"]))
        return
    if arr.GetNumberOfTuples() != ntuples:
        fail("%s: %s has %d tuples, expected %d"
             % (tag, spec["name"], arr.GetNumberOfTuples(), ntuples))
        return
    if arr.GetDataTypeAsString() != "double":
        fail("%s: %s is stored as %s" % (tag, spec["name"], arr.GetDataTypeAsString()))
    want = [float.fromhex(h) for h in spec["values"]]
    nc = spec["ncomp"]
    for k, w in enumerate(want):
        got = arr.GetComponent(k // nc, k % nc)
        if not same(got, w, enc):
            fail("%s: %s[%d][%d] = %r, expected %r" % (tag, spec["name"], k // nc, k % nc, got, w))
            return


def check_data(tag, attrs, specs, ntuples, enc):
    names = sorted(attrs.GetArrayName(i) for i in range(attrs.GetNumberOfArrays()))
    if names != sorted(s["name"] for s in specs):
        fail("%s: arrays %s, expected %s" % (tag, names, sorted(s["name"] for s in specs)))
    for s in specs:
        check_array(tag, attrs.GetArray(s["name"]), s, ntuples, enc)


def check_dataset(work, ds):
    path = os.path.join(work, ds["file"])
    enc = ds["encoding"]
    out = read(path)
    grid = ds["kind"] == "grid"
    want_type = vtkUnstructuredGrid if grid else vtkPolyData
    if not isinstance(out, want_type):
        fail("%s: reader produced %s, expected %s" % (path, type(out).__name__, want_type.__name__))
        return
    xyz = [float.fromhex(h) for h in ds["points"]]
    npts = len(xyz) // 3
    if out.GetNumberOfPoints() != npts:
        fail("%s: %d points, expected %d" % (path, out.GetNumberOfPoints(), npts))
        return
    if out.GetPoints().GetData().GetDataTypeAsString() != "double":
        fail("%s: coordinates stored as %s" % (path, out.GetPoints().GetData().GetDataTypeAsString()))
    for i in range(npts):
        p = out.GetPoint(i)
        for c in range(3):
            if not same(p[c], xyz[3 * i + c], enc):
                fail("%s: point %d coordinate %d = %r, expected %r" % (path, i, c, p[c], xyz[3 * i + c]))
                return
    if grid:
        types, offs, conn = ds["cell_types"], ds["cell_offsets"], ds["conn"]
    else:
        types, offs, conn = [1] * npts, list(range(npts + 1)), list(range(npts))
    ncells = len(types)
    if out.GetNumberOfCells() != ncells:
        fail("%s: %d cells, expected %d" % (path, out.GetNumberOfCells(), ncells))
        return
    if not grid and out.GetNumberOfVerts() != npts:
        fail("%s: %d vertex cells, expected %d" % (path, out.GetNumberOfVerts(), npts))
    for c in range(ncells):
        if out.GetCellType(c) != types[c]:
            fail("%s: cell %d has type %d, expected %d" % (path, c, out.GetCellType(c), types[c]))
        ids = out.GetCell(c).GetPointIds()
        got = [ids.GetId(j) for j in range(ids.GetNumberOfIds())]
        if got != conn[offs[c]:offs[c + 1]]:
            fail("%s: cell %d nodes %s, expected %s" % (path, c, got, conn[offs[c]:offs[c + 1]]))
    check_data(path + " POINT_DATA", out.GetPointData(), ds["point_data"], npts, enc)
    check_data(path + " CELL_DATA", out.GetCellData(), ds["cell_data"], ncells, enc)


def check_series(work, spec):
    path = os.path.join(work, spec["file"])
    try:
        with open(path) as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        fail("%s: not valid JSON: %s" % (path, e))
        return
    if doc.get("file-series-version") != "1.0":
        fail("%s: file-series-version is %r" % (path, doc.get("file-series-version")))
    files = doc.get("files")
    want = [(e["name"], float.fromhex(e["time"])) for e in spec["entries"]]
    got = [(e.get("name"), e.get("time")) for e in files] if isinstance(files, list) else None
    if got != want:
        fail("%s: files %s, expected %s" % (path, got, want))
    for name, _ in want:
        if name.endswith(".vtk") and name.startswith("grid") and not os.path.exists(os.path.join(work, name)):
            fail("%s: listed file %s does not exist" % (path, name))


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    exe, work = sys.argv[1], sys.argv[2]
    verbose = "-v" in sys.argv[3:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    run = subprocess.run([exe, work], capture_output=True, text=True)
    if run.returncode != 0:
        print("writer failed (status %d):\n%s%s" % (run.returncode, run.stdout, run.stderr))
        return 1
    with open(os.path.join(work, "manifest.json")) as f:
        manifest = json.load(f)
    for ds in manifest["datasets"]:
        check_dataset(work, ds)
    check_series(work, manifest["series"])
    leftovers = [n for n in os.listdir(work) if ".tmp." in n]
    if leftovers:
        fail("temporaries left behind: %s" % leftovers)
    if len(manifest["datasets"]) != 4:
        fail("manifest lists %d datasets, expected 4" % len(manifest["datasets"]))
    for msg in failures[:20]:
        print(msg)
    if verbose or failures:
        for enc, (exact, total) in stats.items():
            print("%s: %d of %d values bit-exact" % (enc, exact, total))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
