#!/bin/sh
# Install exactly the Debian packages softact needs that are missing (idempotent).
# Runs apt-get update only when something must be installed. Needs root (or sudo).
set -eu
PKGS="build-essential cmake pkg-config git
libsuitesparse-dev libmetis-dev libopenblas-dev
libsundials-dev libinih-dev
libgmsh-dev gmsh
libliggghts-dev libopenmpi-dev
gnuplot-nox python3 python3-vtk9"
missing=""
for p in $PKGS; do
  st=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  case "$st" in *" installed") ;; *) missing="$missing $p" ;; esac
done
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
if [ -n "$missing" ]; then
  echo "setup: installing:$missing"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
# CHOLMOD's speed comes from the BLAS it finds at run time: make sure that is OpenBLAS.
arch=$(gcc -print-multiarch 2>/dev/null || echo x86_64-linux-gnu)
blas=$(readlink -f "/usr/lib/$arch/libblas.so.3" 2>/dev/null || true)
case "$blas" in
  *openblas*) ;;
  *) alt=$(ls /usr/lib/"$arch"/openblas-*/libblas.so.3 2>/dev/null | head -n 1)
     [ -n "$alt" ] && $SUDO update-alternatives --set "libblas.so.3-$arch" "$alt" >/dev/null &&
       echo "setup: libblas.so.3 now points to OpenBLAS ($alt)" ;;
esac
[ -n "$missing" ] && echo "setup: done" || echo "setup: all packages present"
