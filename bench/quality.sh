#!/usr/bin/env bash
# Quality of the initial mesh and after 20 iterations of the paper's pipeline on
# the four-sphere and 30-seed scenes at grid 64. Prints a Markdown table.
# Usage: bench/quality.sh   (after scripts/build.sh; BUILD=DIR and OUT=DIR as for fig3.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
vm=${BUILD:-build}/tools/voronoimesh/voronoimesh
out=${OUT:-out}
mkdir -p "$out"
echo "| scene | mesh | triangles | min q | 1% q | mean q | q < 0.5 | min angle | max angle |"
echo "|---|---|---|---|---|---|---|---|---|"
for scene in four_spheres voronoi30; do
  "$vm" create -q "examples/$scene.json" --grid 64 -o "$out/q_$scene.ply"
  "$vm" mesh -q "examples/$scene.json" --grid 64 --iterations 20 -o "$out/q_${scene}_20.ply"
  for which in initial "20 iterations"; do
    file="$out/q_$scene.ply"
    [ "$which" = initial ] || file="$out/q_${scene}_20.ply"
    "$vm" stats --json "$file" | python3 -c '
import json, sys
s = json.load(sys.stdin)
print("| {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.2f}% | {:.1f} | {:.1f} |".format(
    sys.argv[1], sys.argv[2], s["triangles"], s["min_quality"], s["quality_p01"], s["mean_quality"],
    100.0 * s["below_half"] / s["triangles"], s["min_angle_deg"], s["max_angle_deg"]))' "$scene" "$which"
  done
done
