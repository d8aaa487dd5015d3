#!/usr/bin/env bash
# The worst triangle of `voronoimesh mesh` at its defaults on 60 small random
# label volumes (issue 18's label targets): ellipsoids in 32^3 (4 labels), 48^3
# (6) and 64^3 (8), and grain maps in 32^3 (8 grains) and 64^3 (16), seeds 1-12
# each, made by bench/make_label_volume. Prints a Markdown table (min q, mean q,
# iterations, what meets at the worst triangle's corners, and whether its
# smallest angle is a junction's corner), then how many are below q 0.3 and the
# mean min q. The volumes are the same every run (fixed seeds).
# Usage: bench/label_survey.sh [extra mesh options, e.g. --snap 0.3]
#        (after scripts/build.sh; BUILD=DIR, OUT=DIR; VM=PATH for another voronoimesh)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
vm=${VM:-$build/tools/voronoimesh/voronoimesh}
out=${OUT:-out}/label_survey
mkdir -p "$out"
echo "| volume | triangles | min q | mean q | iterations | worst triangle's corners | at a junction's corner |"
echo "|---|---|---|---|---|---|---|"
for kind in e32 e48 e64 g32 g64; do
  for seed in $(seq 1 12); do
    name=${kind}_$seed
    case $kind in
      e32) "$build/bench/make_label_volume" ellipsoids 32 4 "$out/$name.nrrd" "$seed" > /dev/null ;;
      e48) "$build/bench/make_label_volume" ellipsoids 48 6 "$out/$name.nrrd" "$seed" > /dev/null ;;
      e64) "$build/bench/make_label_volume" ellipsoids 64 8 "$out/$name.nrrd" "$seed" > /dev/null ;;
      g32) "$build/bench/make_label_volume" grains 32 8 "$out/$name.nrrd" "$seed" > /dev/null ;;
      g64) "$build/bench/make_label_volume" grains 64 16 "$out/$name.nrrd" "$seed" > /dev/null ;;
    esac
    # The mesher's own message when it fails (a bad option, say), not a silent stop.
    log=$("$vm" mesh "$out/$name.nrrd" -o "$out/$name.ply" --threads 2 "$@" 2>&1) || {
      status=$?
      echo "label_survey.sh: $name: $log" >&2
      exit "$status"
    }
    iterations=$(grep -o 'improve: [0-9]* iterations' <<< "$log" | awk '{print $2}')
    stats=$("$vm" stats "$out/$name.ply" --worst 1)
    triangles=$(awk '/^triangles/ {print $2}' <<< "$stats")
    read -r min mean < <(awk '/^quality min/ {print $3, $7}' <<< "$stats")
    corners=$(grep -A3 '^triangle' <<< "$stats" | tail -3 | sed -E 's/.*\): //; s/ of .*//; s/, on a box.*//' |
      sort | uniq -c | awk '{n=$1; $1=""; printf "%s%d%s", (NR>1 ? ", " : ""), n, $0}')
    # Whether its smallest angle is its surface's whole corner at a junction
    # point (`stats` says so): no triangulation beats it while the junctions stay put.
    bound=$(grep -q 'whole corner' <<< "$stats" && echo yes || echo no)
    echo "| $name | $triangles | $min | $mean | $iterations | $corners | $bound |"
  done
done | tee "$out/table.md"
awk -F'|' '{n++; q = $4 + 0; s += q; if (q < 0.3) { below++; if ($8 ~ /yes/) bound++ } } END {
  printf "%d volumes: %d below min q 0.3 (%d of them at a junction'"'"'s corner), mean min q %.3f\n",
    n, below, bound, s / n }' "$out/table.md"
