#!/usr/bin/env bash
# The worst triangles where junctions crowd (issue 18's scenes): 12 random
# Voronoi seed scenes (17, 20, 25 and 30 cells, seeds 2-4, grid 48; made by
# scripts/make_voronoi_scene.py) and 6 random scenes of four overlapping balls
# (grid 48), meshed with `voronoimesh mesh` at its defaults. Prints a Markdown
# table (with, for the seeds, the best min q exact junctions allow) and the mean
# min q of each kind. The scenes are made anew each run and are the same every
# time (fixed seeds).
# Usage: bench/junction_scenes.sh   (after scripts/build.sh; BUILD=DIR, OUT=DIR;
#        VM=PATH to measure another voronoimesh, e.g. an older build)
set -euo pipefail
cd "$(dirname "$0")/.."
vm=${VM:-${BUILD:-build}/tools/voronoimesh/voronoimesh}
out=${OUT:-out}/junction_scenes
mkdir -p "$out"

for cells in 17 20 25 30; do
  for seed in 2 3 4; do python3 scripts/make_voronoi_scene.py "$cells" "$seed" 48 "$out/seeds${cells}_$seed.json"; done
done
python3 - "$out" <<'PY'
import json, random, sys
for seed in range(6):
    r = random.Random(100 + seed)
    phases = [{"name": "outside", "kind": "constant", "value": 0}]
    for i in range(4):
        centre = [round(r.uniform(0.3, 0.7), 4) for _ in range(3)]
        phases.append({"name": f"ball{i}", "kind": "sphere", "center": centre, "radius": round(r.uniform(0.15, 0.3), 4)})
    scene = {"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": 48, "phases": phases}
    with open(f"{sys.argv[1]}/balls_{seed}.json", "w") as f:
        json.dump(scene, f)
PY

# "exact bound": the most min q can be with exact junctions (the smallest
# corner of a surface at a quadruple point; scripts/corner_bound.py).
# "farthest node": the largest offset of a surface / triple-curve / quadruple-point
# node from its closed-form interface, in grid spacings h (`stats --field`);
# "nowhere": the curve / point nodes whose phases meet nowhere near them (a
# junction finer than the grid), left out of the farthest.
# "smallest corner": the smallest corner a surface of the mesh makes at a
# junction point (`stats`), which bounds the min angle while the mesh's
# junctions stay where they are: a min angle equal to it is all that scene's
# junctions, as meshed, allow.
echo "| scene | triangles | min q | mean q | min angle | smallest corner | exact bound | farthest node (h): surface / curve / point | nowhere: curve / point |"
echo "|---|---|---|---|---|---|---|---|---|"
for scene in "$out"/seeds*.json "$out"/balls_*.json; do
  name=$(basename "$scene" .json)
  "$vm" mesh -q "$scene" -o "$out/$name.ply"
  bound=$(python3 scripts/corner_bound.py "$scene" | sed -n 's/.*min q <= //p')
  "$vm" stats --json --field "$scene" "$out/$name.ply" | python3 -c '
import json, sys
s = json.load(sys.stdin)
far = " / ".join("{:.3f}".format(s["offsets"][c]["max_h"]) for c in ("surface", "triple_curve", "quadruple_point"))
nowhere = " / ".join(str(s["offsets"][c]["unresolved"]) for c in ("triple_curve", "quadruple_point"))
print("| {} | {} | {:.3f} | {:.3f} | {:.1f} | {:.1f} | {} | {} | {} |".format(
    sys.argv[1], s["triangles"], s["min_quality"], s["mean_quality"], s["min_angle_deg"], s["smallest_corner_deg"],
    sys.argv[2], far, nowhere))' "$name" "${bound:-none}"
done | tee "$out/table.md"
python3 - "$out/table.md" <<'PY'
import sys
rows = [line.split("|")[1:-1] for line in open(sys.argv[1])]
for kind in ("seeds", "balls"):
    mine = [r for r in rows if r[0].strip().startswith(kind)]
    q = [float(r[2]) for r in mine]
    # Scenes whose worst angle is their junctions' smallest corner: remeshing cannot do better there.
    bound = sum(1 for r in mine if float(r[4]) >= float(r[5]) - 0.5)
    print(f"{kind}: mean min q {sum(q) / len(q):.3f} over {len(q)} scenes, lowest {min(q):.3f}; "
          f"min angle within 0.5 deg of the smallest corner in {bound}")
PY
