#!/bin/sh
# Installs the Debian 12 packages Sable needs, only those that are missing.
# Runs apt-get directly as root, through sudo otherwise. Does nothing when all are present.
set -eu
PKGS="build-essential pkg-config bc petsc-dev libopenmpi-dev openmpi-bin libccd-dev libhdf5-openmpi-dev python3-numpy python3-h5py python3-matplotlib paraview python3-paraview xvfb xauth clang-format procps"
missing=""
for p in $PKGS; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
[ -z "$missing" ] && exit 0
echo "install-deps: installing$missing"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
