#!/usr/bin/env bash
# Prints a SHA-256 for every output of a fixed set of runs: the examples through
# `mesh` in every output format, create alone, --close, the other lattice, no
# snapping, the unguarded and converging runs, smooth and flip of a created mesh,
# a label volume, a point cloud, the plugin passes, `mesh --mpi` (whole and in
# pieces, with MPI builds) and the mesh hashes of bench_mesh's quick cases. Two
# builds that print the same lines made the same files byte for byte: the check
# that a change which should not alter results (a refactoring) did not.
#
# Usage: scripts/output_hashes.sh BUILD_DIR [WORK_DIR]   (after scripts/build.sh)
#   diff <(scripts/output_hashes.sh build-before) <(scripts/output_hashes.sh build)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "$1" && pwd)
work=${2:-$(mktemp -d)}
mkdir -p "$work"
cd "$work"
vm=$build/tools/voronoimesh/voronoimesh
ex=$here/examples
run() { "$vm" "$@" -q; }

run mesh -o demo.ply --history demo.svg
run mesh -o demo_iter0.ply --iterations 0 --history demo.csv
run mesh -o demo_json.ply --iterations 3 --history demo.json
for scene in four_spheres split_sphere voronoi7 voronoi30; do run mesh "$ex/$scene.json" -o "$scene.ply"; done
for format in obj stl msh vtu vtp mesh; do run mesh "$ex/voronoi7.json" --grid 24 -o "voronoi7_24.$format"; done
run mesh "$ex/four_spheres.json" --grid 32 --ascii -o ascii.ply --per-phase per_phase
run create "$ex/four_spheres.json" -o created.ply
run create "$ex/four_spheres.json" --close -o created_closed.ply
run mesh "$ex/four_spheres.json" --close -o closed.msh
run mesh "$ex/four_spheres.json" --lattice cube6 --grid 32 -o cube6.ply
run mesh "$ex/voronoi7.json" --snap 0 --grid 32 -o nosnap.ply
run mesh "$ex/voronoi7.json" --no-crossing-guard -o unguarded.ply
run mesh "$ex/four_spheres.json" --stop-when-converged --iterations 60 -o converged.ply
run mesh "$ex/four_spheres.json" --pipeline smooth,project,clamp,flip:collapse_below=0.2,stats --iterations 5 -o stats.ply
run smooth created.ply --field "$ex/four_spheres.json" -o smoothed.ply
run smooth created_closed.ply --field "$ex/four_spheres.json" --iterations 5 -o smoothed_closed.ply
run flip created.ply -o flipped.ply
run mesh "$ex/voronoi7.json" --grid 32 --pipeline relax,project,clamp,flip -o relax.ply
run mesh "$ex/voronoi7.json" --grid 32 --pipeline cvt,project,clamp,flip -o cvt.ply
"$build/bench/make_label_volume" grains 40 12 grains.nrrd >/dev/null
run mesh grains.nrrd --voxels-per-cell 1.4 -o grains_volume.ply
run mesh grains.nrrd --signed-distance --iterations 5 -o grains_signed.vtu
python3 "$here/bench/make_grains.py" 10 grains10.xyz >/dev/null
run mesh grains10.xyz --grid 32 -o grains_cloud.ply
python3 "$here/scripts/make_point_cloud.py" --count 4000 cloud.ply >/dev/null
run mesh cloud.ply --grid 24 --iterations 5 -o cloud_mesh.ply
# Every build lists --mpi; only MPI builds (VM_MPI=ON) make the MPI library.
if compgen -G "$build/lib/libvoronoimesh_mpi.*" >/dev/null && command -v mpirun >/dev/null; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  mpirun -np 2 --oversubscribe "$vm" mesh "$ex/four_spheres.json" --mpi -q -o mpi.ply
  mpirun -np 2 --oversubscribe "$vm" mesh "$ex/four_spheres.json" --mpi -q --grid 32 -o mpi_pieces.pvtu
fi
find . -type f ! -name '*.nrrd' ! -name '*.xyz' ! -name 'cloud.ply' ! -name bench.txt | sort | xargs sha256sum

# bench_mesh's quick cases (bench/run_table.sh --quick): the last column hashes the mesh.
bench=$build/bench/bench_mesh
{
  "$bench" "$ex/voronoi7.json" 44 2
  "$bench" "$ex/voronoi7.json" 44 2 --no-guard
  "$bench" "$ex/four_spheres.json" 64 2
  "$bench" grains10.xyz 32 2
  "$build/bench/make_label_volume" grains 48 20 grains48_20.nrrd >/dev/null
  "$bench" grains48_20.nrrd 0 2 --voxels-per-cell 1.4
} >bench.txt
awk -F'|' '{ gsub(/ /, "", $2); gsub(/ /, "", $3); gsub(/ /, "", $(NF-1)); print "bench " $2 " " $3 " " $(NF-1) }' bench.txt
