#!/usr/bin/env bash
# Configures and builds voronoimesh (Release) into ./build; with --mpi also the
# distributed create (voronoimesh_mpi, `mesh --mpi`, its tests; needs
# scripts/setup.sh --mpi); with --paraview also the ParaView plugin and its test
# (needs scripts/setup.sh --paraview).
# Usage: scripts/build.sh [--mpi] [--paraview]
set -euo pipefail
cd "$(dirname "$0")/.."
mpi=OFF paraview=OFF
for arg in "$@"; do
  case "$arg" in
    --mpi) mpi=ON ;;
    --paraview) paraview=ON ;;
    *) echo "usage: scripts/build.sh [--mpi] [--paraview]" >&2; exit 2 ;;
  esac
done
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DVM_MPI=$mpi -DVORONOIMESH_PARAVIEW=$paraview >/dev/null
cmake --build build -j"$(nproc)"
