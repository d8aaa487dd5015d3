#!/usr/bin/env bash
# Configures and builds voronoimesh (Release) into ./build; with --mpi also the
# distributed create (voronoimesh_mpi, `mesh --mpi`, its tests; needs
# scripts/setup.sh --mpi).
# Usage: scripts/build.sh [--mpi]
set -euo pipefail
cd "$(dirname "$0")/.."
mpi=OFF
case "${1:-}" in
  --mpi) mpi=ON ;;
  "") ;;
  *) echo "usage: scripts/build.sh [--mpi]" >&2; exit 2 ;;
esac
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DVM_MPI=$mpi >/dev/null
cmake --build build -j"$(nproc)"
