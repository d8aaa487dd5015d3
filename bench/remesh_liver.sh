#!/usr/bin/env bash
# The remesh pass on CGAL's liver (bench/race.sh fetches it): for each grid and
# pipeline, one `voronoimesh mesh` run (2 threads, 20 iterations) measured with
# `voronoimesh stats`, and the same options meshed closed by bench/label_agreement
# for the share of voxel centres inside their own label. Prints a Markdown table.
# Usage: bench/remesh_liver.sh   (after scripts/build.sh and bench/race.sh --quick;
#        BUILD=DIR, OUT=DIR (where liver.inr.gz is, default out/race))
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
out=${OUT:-out/race}
vm=$build/tools/voronoimesh/voronoimesh
agreement=$build/bench/label_agreement
liver=$out/liver.inr.gz
[ -s "$liver" ] || { echo "remesh_liver.sh: $liver missing: run bench/race.sh --quick first" >&2; exit 2; }
cmake --build "$build" -j"$(nproc)" --target voronoimesh_cli label_agreement >&2
paper=smooth,project,clamp,flip
echo "| voxels per cell | pipeline | whole run s | triangles | min q | mean q | min angle | voxel centres in their label % (closed mesh) | interior % |"
echo "|---|---|---|---|---|---|---|---|---|"
for case in "1 $paper" "1 remesh:size=1,$paper" "1 remesh:size=1.2,$paper" "1 remesh:size=1.4,$paper" \
  "2 $paper" "2 remesh:size=1,$paper" "2 remesh:size=1.2,$paper"; do
  read -r vpc pipeline <<<"$case"
  start=$EPOCHREALTIME
  "$vm" mesh -q "$liver" --threads 2 --voxels-per-cell "$vpc" --pipeline "$pipeline" -o "$out/remesh.ply"
  end=$EPOCHREALTIME
  row=$("$agreement" "$liver" --voxels-per-cell "$vpc" --pipeline "$pipeline")
  "$vm" stats --json "$out/remesh.ply" | python3 -c '
import json, sys
s = json.load(sys.stdin)
cells = [c.strip() for c in sys.argv[4].split("|")]
print("| {} | {} | {:.1f} | {} | {:.3f} | {:.3f} | {:.1f} | {} | {} |".format(
    sys.argv[1], sys.argv[2], float(sys.argv[5]) - float(sys.argv[3]), s["triangles"], s["min_quality"], s["mean_quality"],
    s["min_angle_deg"], cells[7], cells[8]))' "$vpc" "$pipeline" "$start" "$row" "$end"
done
