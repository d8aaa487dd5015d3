#!/usr/bin/env bash
# The long tier of the property tests (tests/property): CASES random cases of
# SEED, in batches of BATCH cases run JOBS at a time (one thread each), with a
# progress line per batch. Prints every failing case with the command that
# reproduces it and a summary; exits 1 if any case failed.
#
#   scripts/property_tests.sh [CASES=100000] [SEED=1]
#   JOBS=2 BATCH=500 ITERATIONS=3 BUILD=build scripts/property_tests.sh 20000 7
set -euo pipefail
cases=${1:-100000}
seed=${2:-1}
jobs=${JOBS:-2}
batch=${BATCH:-500}
iterations=${ITERATIONS:-3}
root=$(cd "$(dirname "$0")/.." && pwd)
runner=${BUILD:-$root/build}/tests/property_runner
[[ -x $runner ]] || { echo "property_tests.sh: $runner not built (cmake --build build)" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/vm-property-XXXXXX")
trap 'rm -rf "$work"' EXIT

batches=$(( (cases + batch - 1) / batch ))
echo "property tests: $cases cases of seed $seed, $batches batches of $batch, $jobs at a time, $iterations iterations"
start=$(date +%s)
# Each batch writes its own log; a batch's exit status only says whether a case failed.
seq 0 $((batches - 1)) | xargs -P "$jobs" -I{} bash -c '
  first=$(( {} * '"$batch"' )); count=$(( '"$cases"' - first < '"$batch"' ? '"$cases"' - first : '"$batch"' ))
  "'"$runner"'" --seed '"$seed"' --first $first --count $count --iterations '"$iterations"' > "'"$work"'/batch{}.log" 2>&1 || true
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
echo "last run: $checked of $cases cases checked, $failures failures (seed $seed, $(( $(date +%s) - start )) s)"
[[ $failures -eq 0 && $checked -eq $cases ]]
