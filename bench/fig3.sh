#!/usr/bin/env bash
# The paper's Fig. 3 comparison on the four-sphere scene: six tetrahedra per cell
# versus the BCC lattice, each with and without vertex snapping (0.2 h).
# Prints a Markdown table. Usage: bench/fig3.sh [GRID]   (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
grid=${1:-64}
vm=${BUILD:-build}/tools/voronoimesh/voronoimesh
out=${OUT:-out}
mkdir -p "$out"
echo "| lattice | snap | vertices | triangles | q < 0.1 (slivers) | q < 0.5 | min q | mean q | min angle | max angle |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for lattice in cube6 bcc; do
  for snap in 0 0.2; do
    "$vm" create -q examples/four_spheres.json --grid "$grid" --lattice "$lattice" --snap "$snap" -o "$out/fig3.ply"
    "$vm" stats --json "$out/fig3.ply" | python3 -c '
import json, sys
s = json.load(sys.stdin)
print("| {} | {} h | {} | {} | {} | {} | {:.3f} | {:.3f} | {:.2f} | {:.1f} |".format(
    sys.argv[1], sys.argv[2], s["vertices"], s["triangles"], s["slivers"], s["below_half"],
    s["min_quality"], s["mean_quality"], s["min_angle_deg"], s["max_angle_deg"]))' "$lattice" "$snap"
  done
done
