#!/bin/sh
# CHOLMOD must run on OpenBLAS: the libblas.so.3 that the softact binary loads resolves to it.
exe=$1
lib=$(ldd "$exe" | awk '/libblas\.so/ {print $3; exit}')
[ -n "$lib" ] || { echo "FAIL: $exe does not load libblas.so.3 (no CHOLMOD linked?)"; exit 1; }
real=$(readlink -f "$lib")
case "$real" in
  *openblas*) exit 0 ;;
  *) echo "FAIL: libblas.so.3 resolves to $real, not OpenBLAS (run scripts/setup.sh)"; exit 1 ;;
esac
