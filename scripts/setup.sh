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
if [ -z "$missing" ]; then
  echo "setup: all packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
echo "setup: installing:$missing"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
echo "setup: done"
