#!/usr/bin/env bash
# Meshes per second on a sequence (issue 20, the paper's use: an evolving interface
# meshed step after step): STEPS scenes of two spheres of one phase approaching and
# merging while a sphere of another phase passes through them, at grid GRID; meshed once
# as a sequence in one process (voronoimesh mesh 'step_%03d.json' -o 'step_%03d.vtu') and
# once as STEPS separate runs. Prints a markdown table: total and per-step wall time, the
# slowest step against its lone run, and peak memory (the sequence's against the largest
# lone run's).
# Usage: bench/sequence.sh [STEPS [GRID]]   (after scripts/build.sh; default 100 steps, grid 48)
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-100}
grid=${2:-48}
vm=$PWD/build/tools/voronoimesh/voronoimesh
work=out/sequence
rm -rf "$work" && mkdir -p "$work/scenes" "$work/one" "$work/lone"
python3 - "$steps" "$grid" "$work/scenes" <<'PY'
import sys
steps, grid, folder = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
for s in range(steps):
    t = s / max(steps - 1, 1)
    gap = 0.32 * (1 - t)  # the two spheres of phase "pair" meet halfway and merge
    a, b = 0.5 - gap, 0.5 + gap
    pair = (f"max(0.16 - sqrt((x - {a:.5f})^2 + (y - 0.5)^2 + (z - 0.5)^2), "
            f"0.16 - sqrt((x - {b:.5f})^2 + (y - 0.5)^2 + (z - 0.5)^2))")
    c = 0.15 + 0.7 * t  # the passer crosses the box
    with open(f"{folder}/step_{s:03d}.json", "w") as f:
        f.write('{"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": %d, "phases": ['
                '{"name": "outside", "kind": "constant", "value": 0}, '
                '{"name": "pair", "kind": "expr", "expr": "%s"}, '
                '{"name": "passer", "kind": "sphere", "center": [0.5, %.5f, 0.55], "radius": 0.2}]}\n'
                % (grid, pair, c))
PY
seconds_of() { sed -n 's/^step [0-9]* done in \([0-9.]*\) s$/\1/p'; }
# One process.
/usr/bin/time -f "%e %M" -o "$work/one.time" "$vm" mesh "$work/scenes/step_%03d.json" -o "$work/one/step_%03d.vtu" \
  2>"$work/one.log"
seconds_of <"$work/one.log" >"$work/one.steps"
# Separate runs.
: >"$work/lone.steps"
: >"$work/lone.times"
for f in "$work"/scenes/step_*.json; do
  name=$(basename "$f" .json)
  /usr/bin/time -f "%e %M" -o "$work/lone.time" "$vm" mesh "$f" -o "$work/lone/$name.vtu" -q
  cat "$work/lone.time" >>"$work/lone.times"
done
# The lone runs' own step times (create + improve + write inside the process) come from a
# second pass through the sequence command on one step each, so both sides time the same thing.
for f in "$work"/scenes/step_*.json; do
  "$vm" mesh "$f" "$f" -o "$work/lone/again_%d.vtu" 2>&1 | seconds_of | head -1 >>"$work/lone.steps"
done
python3 - "$work" "$steps" "$grid" <<'PY'
import sys
work, steps, grid = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
one_wall, one_kb = (float(v) for v in open(f"{work}/one.time").read().split())
one = [float(v) for v in open(f"{work}/one.steps").read().split()]
lone = [float(v) for v in open(f"{work}/lone.steps").read().split()]
lone_runs = [tuple(float(v) for v in line.split()) for line in open(f"{work}/lone.times")]
lone_wall = sum(w for w, _ in lone_runs)
lone_peak = max(kb for _, kb in lone_runs)
ratios = [o / l for o, l in zip(one, lone)]
worst = max(range(len(ratios)), key=lambda i: ratios[i])
print("| steps | grid | one process s | meshes/s | separate runs s | meshes/s | slowest step vs its lone run | "
      "peak MiB one process | peak MiB largest lone run | ratio |")
print("|---|---|---|---|---|---|---|---|---|---|")
print(f"| {steps} | {grid} | {one_wall:.2f} | {steps / one_wall:.1f} | {lone_wall:.2f} | {steps / lone_wall:.1f} | "
      f"{ratios[worst]:.2f}x (step {worst}: {one[worst]:.3f} s vs {lone[worst]:.3f} s) | {one_kb / 1024:.0f} | "
      f"{lone_peak / 1024:.0f} | {one_kb / lone_peak:.3f} |")
PY
