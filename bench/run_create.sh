#!/usr/bin/env bash
# Fills the create benchmark table of README.md: four spheres and 30 seeds at
# 64^3, 128^3 and 256^3 with 1 and 2 threads, and 30 vs 300 seeds for memory.
# Usage: bench/run_create.sh   (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
bench=build/bench/bench_create
mkdir -p out
[ -f out/voronoi300.json ] || python3 scripts/make_voronoi_scene.py 300 300 64 out/voronoi300.json
echo "| scene | grid | threads | tets visited | tets cut | triangles | create ms | of which check ms | ns/tet | sampling s | peak RSS MiB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for scene in examples/four_spheres.json examples/voronoi30.json; do
  for grid in 64 128 256; do
    for threads in 1 2; do
      "$bench" "$scene" "$grid" "$threads"
    done
  done
done
for grid in 128 256; do
  "$bench" out/voronoi300.json "$grid" 2
done
