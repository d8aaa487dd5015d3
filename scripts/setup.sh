#!/usr/bin/env bash
# Installs everything voronoimesh needs to build, from Debian 12 packages; with
# --test-readers also the independent readers the tests check every output format
# with (meshio, VTK, Gmsh, TetGen; h5py and Pillow to write DREAM.3D and TIFF files: large, and only the
# tests need them) and doxygen,
# which the api_docs test builds the API reference with; with
# --mpi also OpenMPI, for the distributed build (scripts/build.sh --mpi); with
# --paraview ParaView's development files and pvpython, for the ParaView plugin
# (scripts/build.sh --paraview; about 850 MB), and OpenMPI's development files:
# ParaView's VTK links MPI's C library, which paraview-dev does not bring.
# ParaView's python3-paraview conflicts with python3-vtk9 (one removes the
# other): where ParaView is (or is to be) installed, the VTK tests use its VTK
# and python3-vtk9 is not installed.
# Safe to run again: apt-get skips what is already there. Needs root (or sudo).
# Usage: scripts/setup.sh [--test-readers] [--mpi] [--paraview]
set -euo pipefail
packages=(
  cmake g++ make pkg-config
  libopenmesh-dev libeigen3-dev libtbb-dev libcli11-dev libgtest-dev
  libmuparser-dev nlohmann-json3-dev libbenchmark-dev
  libteem-dev libnanoflann-dev
  zlib1g-dev libbz2-dev libnifti2-dev libhdf5-dev libtiff-dev
  pybind11-dev python3-dev python3-numpy python3-pytest
)
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep "install ok installed" >/dev/null; }
readers=0 paraview=0
for arg in "$@"; do
  case "$arg" in
    --test-readers) readers=1; packages+=(python3-meshio python3-h5py python3-pil gmsh tetgen doxygen) ;;
    --mpi) packages+=(libopenmpi-dev openmpi-bin) ;;
    --paraview) paraview=1; packages+=(paraview-dev paraview python3-paraview libopenmpi-dev) ;;
    *) echo "usage: scripts/setup.sh [--test-readers] [--mpi] [--paraview]" >&2; exit 2 ;;
  esac
done
if [ $readers = 1 ] && [ $paraview = 0 ] && ! installed python3-paraview; then
  packages+=(python3-vtk9)
fi
missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
