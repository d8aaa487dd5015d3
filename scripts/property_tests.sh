#!/usr/bin/env bash
# The long tier of the property tests (tests/property): CASES random cases of
# SEED, in batches of BATCH cases run JOBS at a time (one thread each), with a
# progress line per batch. Prints every failing case with the command that
# reproduces it and a summary; exits 1 if any case failed.
#
#   scripts/property_tests.sh [CASES=100000] [SEED=1]
#   JOBS=2 BATCH=500 ITERATIONS=3 BUILD=build scripts/property_tests.sh 20000 7
# FIRST=N starts at case N (to resume a run that was stopped; batches keep
# their numbering, so the logs of both runs line up). VOXEL_FAITHFUL=1 runs only
# the label cases among them, read voxel-faithful (property_runner --voxel-faithful).
# CHECK_EVERY=N meshes each case whole with crossings looked for every N
# iterations (property_runner --check-crossings-every; give ITERATIONS=8 or so,
# so that windows open). WHOLE=1 meshes each case whole as `voronoimesh mesh`
# does, its default pipeline (remesh, collapses, polish, floor), checked after
# every iteration (property_runner --whole; give ITERATIONS=8 or so, so that
# polish runs).
set -euo pipefail
# Read whole before it runs (the braces, closed by the last line, with exit in
# them): bash reads a script as it goes, and editing this file during an
# 18-minute run broke its summary line.
{
cases=${1:-100000}
seed=${2:-1}
jobs=${JOBS:-2}
batch=${BATCH:-500}
iterations=${ITERATIONS:-3}
first_case=${FIRST:-0}
variant=${VOXEL_FAITHFUL:+--voxel-faithful}
windows=${CHECK_EVERY:+--check-crossings-every $CHECK_EVERY}
whole=${WHOLE:+--whole}
root=$(cd "$(dirname "$0")/.." && pwd)
runner=${BUILD:-$root/build}/tests/property_runner
[[ -x $runner ]] || { echo "property_tests.sh: $runner not built (cmake --build build)" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/vm-property-XXXXXX")
trap 'rm -rf "$work"' EXIT

batches=$(( (cases + batch - 1) / batch ))
first_batch=$(( first_case / batch ))
(( first_case % batch == 0 )) || { echo "property_tests.sh: FIRST=$first_case is not a multiple of BATCH=$batch" >&2; exit 2; }
echo "property tests: $cases cases of seed $seed from case $first_case, $batches batches of $batch, $jobs at a time, $iterations iterations${variant:+ (only label cases, read voxel-faithful)}${windows:+ (meshed whole, crossings checked every $CHECK_EVERY iterations)}${whole:+ (meshed whole with the default pipeline, checked after every iteration)}"
start=$(date +%s)
# Each batch writes its own log; a batch's exit status only says whether a case failed.
seq $first_batch $((batches - 1)) | xargs -P "$jobs" -I{} bash -c '
  first=$(( {} * '"$batch"' )); count=$(( '"$cases"' - first < '"$batch"' ? '"$cases"' - first : '"$batch"' ))
  "'"$runner"'" --seed '"$seed"' --first $first --count $count --iterations '"$iterations"' '"$variant"' '"$windows"' '"$whole"' > "'"$work"'/batch{}.log" 2>&1 || true
  done_batches=$(ls "'"$work"'" | wc -l)
  echo "batch {} ($first..$((first + count - 1))): $(tail -n 1 "'"$work"'/batch{}.log")  [$done_batches/'"$batches"' batches, $(( $(date +%s) - '"$start"' ))s]"
'
failures=$(cat "$work"/batch*.log | grep -c '^FAIL' || true)
checked=$(cat "$work"/batch*.log | sed -n 's/^checked \([0-9]*\) cases.*/\1/p' | paste -sd+ | bc)
if [[ $failures -gt 0 ]]; then
  echo "failing cases (reproduce with $runner ... --verbose):"
  cat "$work"/batch*.log | grep -A1 '^FAIL' | grep -v '^--$' | sed "s|property_runner|$runner|"
fi
# A batch that crashed has no summary line: its cases count as not checked.
summaries=$(cat "$work"/batch*.log | grep -c '^checked' || true)
again=""
if [[ -n $windows ]]; then
  sum_of() { cat "$work"/batch*.log | sed -n "s/^checked .* \([0-9]*\) windows run again in \([0-9]*\) cases$/\\$1/p" | paste -sd+ | bc; }
  again=", $(sum_of 1) windows run again in $(sum_of 2) cases"
fi
echo "last run: $checked ${variant:+label }cases checked of $((cases - first_case)) (from case $first_case), $failures failures$again, $((batches - first_batch - summaries)) batches crashed (seed $seed, $(( $(date +%s) - start )) s)"
[[ $failures -eq 0 && $summaries -eq $((batches - first_batch)) && ( -n $variant || $checked -eq $((cases - first_case)) ) ]]
exit
}
