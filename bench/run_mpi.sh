#!/usr/bin/env bash
# Distributed create on 1, 2 and 4 ranks (one thread each), create only: one
# Markdown row per run from bench_mpi (see its header for the columns).
# Needs a build configured with -DVM_MPI=ON (scripts/build.sh --mpi).
# Usage: bench/run_mpi.sh [SCENE.json [GRID [BUILD_DIR]]]
#   default: examples/four_spheres.json at 256^3, build/
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-examples/four_spheres.json}
grid=${2:-256}
build=${3:-build}
echo "| scene | grid | ranks | triangles | seconds | work s max/min | peak MB per rank (max) | MPI % (max) | interface tets max/mean |"
echo "|---|---|---|---|---|---|---|---|---|"
for ranks in 1 2 4; do
  mpirun --oversubscribe ${OMPI_ALLOW_RUN_AS_ROOT:+--allow-run-as-root} -np "$ranks" \
    "$build/bench/bench_mpi" "$scene" "$grid" 1
done
