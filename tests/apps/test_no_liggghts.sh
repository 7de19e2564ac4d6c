#!/bin/sh
# A scene without particles never loads LIGGGHTS or MPI: softact does not link them (the FEM-DEM
# scene dlopen()s its plugin), and running the HMSA statics scene loads neither (the dynamic
# loader's own record of every object it opens, LD_DEBUG=files, is the reference).
set -u
exe=$1
case_file=$2
if ldd "$exe" | grep -E -i 'liggghts|libmpi' >/dev/null; then
  echo "softact links LIGGGHTS or MPI:"; ldd "$exe" | grep -E -i 'liggghts|libmpi'; exit 1
fi
out=$(mktemp -d)
LD_DEBUG=files "$exe" run "$case_file" --out "$out/r" --quiet 2>"$out/ld.txt" >/dev/null
rc=$?
if [ $rc -ne 0 ]; then echo "the HMSA scene failed ($rc)"; tail -5 "$out/ld.txt"; rm -rf "$out"; exit 1; fi
if grep -E -i 'file=.*(liggghts|libmpi)' "$out/ld.txt" >/dev/null; then
  echo "a particle-free scene loaded:"; grep -E -i 'file=.*(liggghts|libmpi)' "$out/ld.txt" | head -3
  rm -rf "$out"; exit 1
fi
rm -rf "$out"
exit 0
