#!/usr/bin/env bash
# bench/race.sh: voronoimesh against CGAL 5.5 Mesh_3's labelled-image mesher on
# the same label volumes, side by side, measured the same way for both.
#
# Usage: bench/race.sh [--quick]
#   BUILD=build       an existing Release build dir of voronoimesh (scripts/build.sh);
#                     its voronoimesh and make_label_volume targets are (re)built here
#   OUT=out/race      cache and outputs: liver.inr.gz, grains96.{nrrd,inr}, every mesh,
#                     logs, and race.md (the tables below)
#   CGAL_BUILD=build-cgal   where bench/cgal (cgal_label_mesher) is built
#   REPS=3            runs per case (--quick: 1)
#
# Cases (each run alternately with the others, REPS times; the wall time is the
# median, peak memory the largest, both from /usr/bin/time):
#   liver (CGAL's liver.inr.gz, 438x353x165, labels 0/84/85/127/255, from
#   Debian's libcgal-demo): voronoimesh mesh default and --voxels-per-cell 2;
#   CGAL facet size 2 voxels, distance 0.5, angle 30;
#   grains96 (make_label_volume grains 96 60): voronoimesh default and
#   --voxels-per-cell 1.4; CGAL on the same voxels converted to INR, same criteria;
#   and (not with --quick) CGAL built with Sequential_tag, one thread.
# --quick: only the liver with voronoimesh's defaults and CGAL, once.
#
# voronoimesh runs with --threads 2; CGAL with TBB's default thread count (every
# core) and Parallel_tag (bench/cgal/CMakeLists.txt). Sizes in voxels are of the
# smallest spacing for both (liver: 0.617 mm; its slices are 1.333 mm apart).
# Quality and validity come from `voronoimesh stats` on each tool's PLY (the
# last run's); for a mesh it rejects, `voronoimesh flip` prints the total count of
# problems and bench/cgal/edge_census.py counts them by kind over the whole mesh
# (stats lists only the first 20).
#
# Benchmark only: CGAL is never a dependency of the library or its build.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

quick=0
case "${1:-}" in
--quick) quick=1 ;;
"") ;;
*) echo "usage: bench/race.sh [--quick]" >&2 && exit 2 ;;
esac
BUILD=${BUILD:-build}
OUT=${OUT:-out/race}
CGAL_BUILD=${CGAL_BUILD:-build-cgal}
REPS=${REPS:-3}
[ "$quick" = 1 ] && REPS=1
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

# ---- packages (only what is missing) ------------------------------------------
need=()
for pkg in libcgal-dev libtbb-dev cmake g++ python3 time; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg")
done
if [ ${#need[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" = 0 ] || sudo=sudo
  echo "installing ${need[*]}" >&2
  $sudo apt-get update -qq && $sudo apt-get install -y -qq "${need[@]}" >&2
fi

# ---- the liver: data/images/liver.inr.gz of libcgal-demo ------------------------
liver=$(bench/get_liver.sh "$OUT")

# ---- builds -------------------------------------------------------------------
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >&2
fi
grep -q '^CMAKE_BUILD_TYPE:STRING=Release$' "$BUILD/CMakeCache.txt" ||
  echo "race.sh: warning: $BUILD is not a Release build" >&2
cmake --build "$BUILD" -j"$(nproc)" --target voronoimesh_cli make_label_volume >&2
vm=$root/$BUILD/tools/voronoimesh/voronoimesh
cmake -S bench/cgal -B "$CGAL_BUILD" -DCMAKE_BUILD_TYPE=Release >&2
cmake --build "$CGAL_BUILD" -j"$(nproc)" >&2
cgal=$root/$CGAL_BUILD/cgal_label_mesher
if [ "$quick" = 0 ]; then
  cmake -S bench/cgal -B "$CGAL_BUILD-seq" -DCMAKE_BUILD_TYPE=Release -DRACE_CGAL_PARALLEL=OFF >&2
  cmake --build "$CGAL_BUILD-seq" -j"$(nproc)" >&2
  cgal_seq=$root/$CGAL_BUILD-seq/cgal_label_mesher
fi

# ---- the polycrystal ------------------------------------------------------------
grains=$OUT/grains96.nrrd
if [ "$quick" = 0 ]; then
  [ -s "$grains" ] || "$root/$BUILD/bench/make_label_volume" grains 96 60 "$grains"
  python3 bench/cgal/nrrd_to_inr.py "$grains" "$OUT/grains96.inr"
fi

# ---- the cases: name|tool|case|options|threads|command (OUTPUT stands for the mesh) ----
cases=(
  "vm_liver_default|voronoimesh|liver|default (cubic cells for its flat voxels, remesh:size=1.4, then the paper's passes)|2|$vm mesh $liver -o OUTPUT --threads 2"
  "cgal_liver|CGAL 5.5 Mesh_3|liver|facet size 2, distance 0.5 voxels, angle 30|TBTHREADS|$cgal $liver OUTPUT --facet-size 2 --facet-distance 0.5 --facet-angle 30"
)
if [ "$quick" = 0 ]; then
  cases+=(
    "vm_liver_paper|voronoimesh|liver|--pipeline smooth,project,clamp,flip (the paper's, on the default grid)|2|$vm mesh $liver -o OUTPUT --threads 2 --pipeline smooth,project,clamp,flip"
    "vm_liver_vpc2|voronoimesh|liver|--voxels-per-cell 2|2|$vm mesh $liver -o OUTPUT --threads 2 --voxels-per-cell 2"
    "cgalseq_liver|CGAL 5.5 Mesh_3, Sequential_tag|liver|facet size 2, distance 0.5 voxels, angle 30|1|$cgal_seq $liver OUTPUT --facet-size 2 --facet-distance 0.5 --facet-angle 30"
    "vm_grains96_default|voronoimesh|grains96|default|2|$vm mesh $grains -o OUTPUT --threads 2"
    "vm_grains96_vpc1.4|voronoimesh|grains96|--voxels-per-cell 1.4|2|$vm mesh $grains -o OUTPUT --threads 2 --voxels-per-cell 1.4"
    "cgal_grains96|CGAL 5.5 Mesh_3|grains96|facet size 2, distance 0.5 voxels, angle 30|TBTHREADS|$cgal $OUT/grains96.inr OUTPUT --facet-size 2 --facet-distance 0.5 --facet-angle 30"
    "cgalseq_grains96|CGAL 5.5 Mesh_3, Sequential_tag|grains96|facet size 2, distance 0.5 voxels, angle 30|1|$cgal_seq $OUT/grains96.inr OUTPUT --facet-size 2 --facet-distance 0.5 --facet-angle 30"
  )
fi

command_of() { local c=${1##*|}; echo "${c//OUTPUT/$OUT/$2.ply}"; }

# Alternate: round r runs every case once, so slow drifts of the machine (heat,
# other load) spread over all of them; and each round takes them in another
# order (a stride through the list coprime with its length: 1, then the next),
# so a case follows another case each round. In one fixed order the default
# liver run always came after CGAL's sequential grains run; reading the volume
# then took 0.75-0.8 s, and 0.28 s right after another voronoimesh run.
gcd() { local a=$1 b=$2; while ((b)); do local t=$((a % b)); a=$b; b=$t; done; echo "$a"; }
stride=0
for ((r = 1; r <= REPS; ++r)); do
  n=${#cases[@]}
  stride=$((stride + 1))
  while (($(gcd "$stride" "$n") != 1)); do stride=$((stride + 1)); done
  for ((i = 0; i < n; ++i)); do
    c=${cases[(i * stride + r - 1) % n]}
    name=${c%%|*}
    echo "run $r/$REPS: $name" >&2
    # shellcheck disable=SC2046 # the command is split into words on purpose
    /usr/bin/time -f "%e %M" -o "$OUT/$name.time.$r" $(command_of "$c" "$name") >"$OUT/$name.log.$r" 2>&1 ||
      { echo "race.sh: $name failed, see $OUT/$name.log.$r" >&2 && exit 1; }
  done
done

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
json_field() { grep -oE "\"$2\": [0-9.eE+-]+" "$1" | head -1 | awk '{print $2}'; }
# Triangles whose smallest angle is below 30 degrees (CGAL's facet_angle bound),
# from voronoimesh stats --json's bins of 10 degrees.
below_30() { python3 -c 'import json, sys; print(sum(json.load(open(sys.argv[1]))["smallest_angles"][:3]))' "$1"; }

# "valid, N triple curves" or "INVALID: N problems (kinds)" from voronoimesh's own checks.
validity() {
  local mesh=$1 stats=$2
  if "$vm" stats "$mesh" >"$stats"; then
    echo "valid, $(awk '/^triple curves/ {print $3}' "$stats") triple curves closed and shared"
    return
  fi
  # flip refuses an invalid mesh and says how many problems validate found in all.
  local total census
  # (flip exits 4 on such a mesh: under pipefail that is not the pipeline's failure.)
  total=$({ "$vm" flip "$mesh" -o "$OUT/refused.ply" 2>&1 || true; } | grep -oE '\(([0-9]+) problems\)' | grep -oE '[0-9]+' || true)
  [ -n "$total" ] || total="?"
  rm -f "$OUT/refused.ply"
  census=$(python3 bench/cgal/edge_census.py "$mesh")
  echo "$census" >"${stats%.txt}.census.json"
  printf 'INVALID: %s problems; edges: %s open (holes), %s non-manifold, %s of %s junction edges broken; %s triple curves' \
    "$total" "$(json_field <(echo "$census") open)" "$(json_field <(echo "$census") non_manifold)" \
    "$(json_field <(echo "$census") broken_junction)" "$(json_field <(echo "$census") junction_edges)" \
    "$(awk '/^triple curves/ {print $3}' "$stats")"
}

table=$OUT/race.md
{
  echo "| tool | case | options | threads | wall s (median of $REPS) | peak MiB | triangles | min q | mean q | min angle | smallest angle < 30 | folds | junctions / validity (voronoimesh stats) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for c in "${cases[@]}"; do
    IFS='|' read -r name tool case_ options threads _ <<<"$c"
    wall=$(for ((r = 1; r <= REPS; ++r)); do awk '{print $1}' "$OUT/$name.time.$r"; done | median)
    peak=$(for ((r = 1; r <= REPS; ++r)); do awk '{print $2}' "$OUT/$name.time.$r"; done | sort -g | tail -1)
    mesh=$OUT/$name.ply
    "$vm" stats --json "$mesh" >"$OUT/$name.stats.json" || true # exit 4 for an invalid mesh; the numbers are there
    s=$OUT/$name.stats.json
    if [ "$threads" = TBTHREADS ]; then
      threads="$(json_field "$OUT/$name.log.$REPS" threads) (TBB default, Parallel_tag)"
    fi
    printf '| %s | %s | %s | %s | %.2f | %d | %s | %.3f | %.3f | %.1f | %s | %s | %s |\n' "$tool" "$case_" "$options" \
      "$threads" "$wall" "$((peak / 1024))" "$(json_field "$s" triangles)" "$(json_field "$s" min_quality)" \
      "$(json_field "$s" mean_quality)" "$(json_field "$s" min_angle_deg)" "$(below_30 "$s")" "$(json_field "$s" folds)" \
      "$(validity "$mesh" "$OUT/$name.stats.txt")"
  done

  echo
  echo "Where the time goes (median of $REPS, seconds). CGAL: its JSON line; voronoimesh: its progress lines."
  echo
  echo "| tool | case | options | read + phase functions / read | sampling + create / make_mesh_3 | improve / facet extraction | whole process |"
  echo "|---|---|---|---|---|---|---|"
  for c in "${cases[@]}"; do
    IFS='|' read -r name tool case_ options _ _ <<<"$c"
    wall=$(for ((r = 1; r <= REPS; ++r)); do awk '{print $1}' "$OUT/$name.time.$r"; done | median)
    if [[ $name == cgal* ]]; then
      a=$(for ((r = 1; r <= REPS; ++r)); do json_field "$OUT/$name.log.$r" read_s; done | median)
      b=$(for ((r = 1; r <= REPS; ++r)); do json_field "$OUT/$name.log.$r" make_mesh_3_s; done | median)
      d=$(for ((r = 1; r <= REPS; ++r)); do json_field "$OUT/$name.log.$r" extract_s; done | median)
    else
      a=$(for ((r = 1; r <= REPS; ++r)); do grep -oE "read and phase functions [0-9.]+ s" "$OUT/$name.log.$r" | grep -oE "[0-9.]+"; done | median)
      b=$(for ((r = 1; r <= REPS; ++r)); do grep -oE "sampling [0-9.]+ s, create [0-9.]+ s" "$OUT/$name.log.$r" | awk '{print $2 + $5}'; done | median)
      d=$(for ((r = 1; r <= REPS; ++r)); do grep -oE "iterations of .* in [0-9.]+ s" "$OUT/$name.log.$r" | grep -oE "[0-9.]+ s$" | cut -d' ' -f1; done | median)
    fi
    echo "| $tool | $case_ | $options | $a | $b | $d | $wall |"
  done

  # Untimed: where CGAL's surface (restricted Delaunay facets) and its cell
  # labels disagree (cgal_label_mesher --diagnose, a run of its own, so a
  # different mesh than the timed ones when parallel).
  echo
  for c in "${cases[@]}"; do
    name=${c%%|*}
    [[ $name == cgal_* ]] || continue
    $(command_of "$c" "$name.diagnose") --diagnose >"$OUT/$name.diagnose.log" 2>&1
    echo "- $name (a separate run with --diagnose): $(json_field "$OUT/$name.diagnose.log" triangles) triangles," \
      "$(json_field "$OUT/$name.diagnose.log" label_changes_off_surface) facets between differently labelled cells" \
      "are not on the surface; $(json_field "$OUT/$name.diagnose.log" triangles_against_0) triangles face label 0 (the outside)"
  done

  echo
  echo "Commands (OUTPUT: $OUT/<name>.ply):"
  echo
  for c in "${cases[@]}"; do echo "    $(command_of "$c" "${c%%|*}")"; done
} | tee "$table"
