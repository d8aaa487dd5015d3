#!/usr/bin/env bash
# Prints the label-volume benchmark table of docs/benchmarks.md: the whole main job
# (read, phase functions, create, 20 iterations, write) on
#  - ct:          a CT-like segmentation, 512x512x96 voxels (25.2M), 4 labels
#                 (make_label_volume ct), meshed at --voxels-per-cell 2.4, about
#                 the ~90k triangles CGAL Mesh_3 gives at facet size 2 voxels (issue 6);
#  - grains96:    a 96^3 polycrystal of 60 grains at --voxels-per-cell 1.4 (CGAL: ~108k);
#  - ellipsoids:  SIZE^3 with 5 labels (ellipsoids in a background) on the voxel grid;
#  - grains:      SIZE^3 with 500 Voronoi grains on the voxel grid;
# with wall time and peak memory from /usr/bin/time, for 1 and 2 threads. "input s" is
# reading plus the phase functions, "write s" what remains (writing, final checks).
# Usage: bench/run_labels.sh [SIZE [CASES...]]   (after scripts/build.sh; default SIZE 256,
#        all cases). The same volumes through VTK: bench/vtk_reference.py out/ct.nrrd
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-256}
shift || true
cases=("${@:-ct grains96 ellipsoids grains}")
read -r -a cases <<<"${cases[*]}"
vm=build/tools/voronoimesh/voronoimesh
mkdir -p out
echo "| volume | labels | voxels/cell | threads | triangles | total s | input s | create s | improve s | write s | peak MiB | min q | mean q |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for name in "${cases[@]}"; do
  case $name in
  ct) file=out/ct.nrrd labels=4 per_cell=2.4 && [ -e "$file" ] || build/bench/make_label_volume ct "$file" ;;
  grains96) file=out/grains96.nrrd labels=60 per_cell=1.4 && build/bench/make_label_volume grains 96 60 "$file" ;;
  ellipsoids) file=out/ellipsoids$size.nrrd labels=5 per_cell=1 && build/bench/make_label_volume ellipsoids "$size" 5 "$file" ;;
  grains) file=out/grains$size.nrrd labels=500 per_cell=1 && build/bench/make_label_volume grains "$size" 500 "$file" ;;
  *) echo "unknown case $name" >&2 && exit 2 ;;
  esac
  for threads in 1 2; do
    /usr/bin/time -f "%e %M" -o out/time.txt "$vm" mesh "$file" --voxels-per-cell "$per_cell" --threads "$threads" \
      -o "out/$name.ply" 2>out/log.txt
    read -r seconds kib <out/time.txt
    triangles=$(grep -oE "[0-9]+ triangles" out/log.txt | head -1 | cut -d' ' -f1)
    input=$(grep -oE "read and phase functions [0-9.]+ s" out/log.txt | grep -oE "[0-9.]+")
    create=$(grep -oE "sampling [0-9.]+ s, create [0-9.]+ s" out/log.txt | awk '{printf "%.3f", $2 + $5}')
    improve=$(grep -oE "iterations of .* in [0-9.]+ s" out/log.txt | grep -oE "[0-9.]+ s$" | cut -d' ' -f1)
    write=$(awk -v t="$seconds" -v a="$input" -v b="$create" -v c="$improve" 'BEGIN {printf "%.2f", t - a - b - c}')
    quality=$(grep -oE "min q [0-9.]+ -> [0-9.]+, mean q [0-9.]+ -> [0-9.]+" out/log.txt)
    min_q=$(echo "$quality" | awk '{print $5}' | tr -d ,)
    mean_q=$(echo "$quality" | awk '{print $10}')
    echo "| $name | $labels | $per_cell | $threads | $triangles | $seconds | $input | $create | $improve | $write | $((kib / 1024)) | $min_q | $mean_q |"
  done
done
