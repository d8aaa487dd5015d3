#!/usr/bin/env bash
# Fills the improvement benchmark table of README.md: the seven-phase scene (about
# 16,600 triangles at grid 44, like the paper's Fig. 8) for 50 iterations with 1
# and 2 threads (with and without the crossing guard), then about 10x and 60x the
# triangles for linear scaling.
# Usage: bench/run_improve.sh   (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
bench=build/bench/bench_improve
echo "| scene | grid | threads | triangles | 50 it. s | ms/it. | µs/it. per node | smooth ms | project ms | clamp+commit ms | flip ms | min q | mean q |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for threads in 1 2; do "$bench" examples/voronoi7.json 44 "$threads" 50; done
for threads in 1 2; do "$bench" examples/voronoi7.json 44 "$threads" 50 unguarded | sed 's/| voronoi7 |/| voronoi7, no guard |/'; done
for grid in 140 340; do "$bench" examples/voronoi7.json "$grid" 2 50; done
