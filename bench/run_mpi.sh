#!/usr/bin/env bash
# Distributed create on 1, 2 and 4 ranks (one thread each): one Markdown row
# per run from bench_mpi (see its header for the columns); with ITERATIONS,
# then that many iterations of the default pipeline over the ranks, a second
# table. Needs a build configured with -DVM_MPI=ON (scripts/build.sh --mpi).
# Usage: bench/run_mpi.sh [SCENE.json [GRID [BUILD_DIR [ITERATIONS]]]]
#   default: examples/four_spheres.json at 256^3, build/, create only
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-examples/four_spheres.json}
grid=${2:-256}
build=${3:-build}
iterations=${4:-0}
rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
for ranks in 1 2 4; do
  mpirun --oversubscribe ${OMPI_ALLOW_RUN_AS_ROOT:+--allow-run-as-root} -np "$ranks" \
    "$build/bench/bench_mpi" "$scene" "$grid" 1 "$iterations" >>"$rows"
done
echo "| scene | grid | ranks | triangles | seconds | work s max/min | peak MB per rank (max) | MPI % (max) | interface tets max/mean |"
echo "|---|---|---|---|---|---|---|---|---|"
awk -F'|' 'NF == 11' "$rows"
if [ "$iterations" -gt 0 ]; then
  echo
  echo "| scene | grid | ranks | triangles | seconds ($iterations iterations) | work s max/min | CPU s (max) | peak MB per rank (max) | MPI % (max) | MB sent per rank per iteration (max) | collectives per iteration | window / own triangles (max) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F'|' 'NF == 14' "$rows"
fi
