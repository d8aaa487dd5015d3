#!/usr/bin/env bash
# Fills the label-volume benchmark table of README.md: 256^3 label volumes with
# 5 labels (ellipsoids in a background) and 500 labels (Voronoi grains), meshed
# by the whole main job (read, phase functions, create, 20 iterations, write),
# with wall time and peak memory from /usr/bin/time, for 1 and 2 threads.
# Usage: bench/run_labels.sh [SIZE]   (after scripts/build.sh; default SIZE 256)
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-256}
vm=build/tools/voronoimesh/voronoimesh
mkdir -p out
build/bench/make_label_volume ellipsoids "$size" 5 "out/ellipsoids$size.nrrd"
build/bench/make_label_volume grains "$size" 500 "out/grains$size.nrrd"
echo "| volume | labels | threads | triangles | total s | create s | improve s | peak MiB | min q | mean q |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for name in ellipsoids grains; do
  labels=5 && [ "$name" = grains ] && labels=500
  for threads in 1 2; do
    /usr/bin/time -f "%e %M" -o out/time.txt "$vm" mesh "out/$name$size.nrrd" --threads "$threads" \
      -o "out/$name$size.ply" 2>out/log.txt
    read -r seconds kib <out/time.txt
    triangles=$(grep -oE "[0-9]+ triangles" out/log.txt | head -1 | cut -d' ' -f1)
    create=$(grep -oE "create [0-9.]+ s" out/log.txt | head -1 | cut -d' ' -f2)
    improve=$(grep -oE "iterations of .* in [0-9.]+ s" out/log.txt | grep -oE "[0-9.]+ s$" | cut -d' ' -f1)
    quality=$(grep -oE "min q [0-9.]+ -> [0-9.]+, mean q [0-9.]+ -> [0-9.]+" out/log.txt)
    min_q=$(echo "$quality" | awk '{print $5}' | tr -d ,)
    mean_q=$(echo "$quality" | awk '{print $10}')
    echo "| $name ${size}^3 | $labels | $threads | $triangles | $seconds | $create | $improve | $((kib / 1024)) | $min_q | $mean_q |"
  done
done
