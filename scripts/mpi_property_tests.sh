#!/usr/bin/env bash
# The MPI tier of the property tests (tests/mpi/mpi_property_runner.cpp): CASES
# random cases of SEED created and improved over RANKS ranks and in one
# process, in batches of BATCH cases one after the other (each batch takes
# RANKS processes, one thread each), with a progress line per batch. Prints
# every case whose distributed mesh is not the one-process mesh, with the
# command that reproduces it, and a summary; exits 1 if any case failed or a
# batch crashed or outran TIMEOUT seconds (ranks that disagree can hang).
#
#   scripts/mpi_property_tests.sh [CASES=200] [SEED=1]
#   RANKS=3 BATCH=50 ITERATIONS=10 PIPELINE=smooth,project,clamp,flip TIMEOUT=900 BUILD=build \
#     scripts/mpi_property_tests.sh 400 104
# Needs the MPI build (scripts/setup.sh --mpi, scripts/build.sh --mpi). On 2
# cores, 200 cases at 10 iterations on 3 ranks take about 4 minutes.
set -euo pipefail
# Read whole before it runs (see scripts/property_tests.sh).
{
cases=${1:-200}
seed=${2:-1}
ranks=${RANKS:-3}
batch=${BATCH:-50}
iterations=${ITERATIONS:-10}
pipeline=${PIPELINE:-smooth,project,clamp,flip}
limit=${TIMEOUT:-900}
root=$(cd "$(dirname "$0")/.." && pwd)
runner=${BUILD:-$root/build}/tests/mpi_property_runner
[[ -x $runner ]] || { echo "mpi_property_tests.sh: $runner not built (scripts/build.sh --mpi)" >&2; exit 2; }
mpirun=$(command -v mpirun || command -v mpiexec) ||
  { echo "mpi_property_tests.sh: no mpirun (scripts/setup.sh --mpi)" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/vm-mpi-property-XXXXXX")
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 # CI runs as root

batches=$(( (cases + batch - 1) / batch ))
echo "MPI property tests: $cases cases of seed $seed on $ranks ranks, $iterations iterations of $pipeline," \
  "$batches batches of $batch"
start=$(date +%s)
crashed=0
for ((b = 0; b < batches; ++b)); do
  first=$((b * batch)); count=$((cases - first < batch ? cases - first : batch))
  log=$work/batch$b.log
  timeout "$limit" "$mpirun" -np "$ranks" --oversubscribe "$runner" --seed "$seed" --first "$first" --count "$count" \
    --iterations "$iterations" --pipeline "$pipeline" >"$log" 2>&1 || true
  summary=$(grep '^checked' "$log" || true)
  if [[ -z $summary ]]; then
    crashed=$((crashed + 1))
    summary="no summary: crashed or outran ${limit} s (the first lines of its log above)"
    head -n 3 "$log" | sed 's/^/    /'
  fi
  grep -A1 '^FAIL' "$log" | grep -v '^--$' | sed "s|mpi_property_runner|$runner|" || true
  echo "batch $b ($first..$((first + count - 1))): $summary  [$((b + 1))/$batches batches, $(( $(date +%s) - start ))s]"
done
summary_line='^checked \([0-9]*\) cases, \([0-9]*\) failed, \([0-9]*\) skipped.*'
sum_of() { cat "$work"/batch*.log | sed -n "s/$summary_line/\\$1/p" | paste -sd+ | bc; }
checked=$(sum_of 1) failures=$(sum_of 2) skipped=$(sum_of 3)
checked=${checked:-0} failures=${failures:-0} skipped=${skipped:-0}
echo "last run: $checked cases checked of $cases ($skipped skipped: fewer slabs than ranks, or no mesh)," \
  "$failures failures, $crashed batches crashed (seed $seed, $ranks ranks, $(( $(date +%s) - start )) s)"
[[ $failures -eq 0 && $crashed -eq 0 ]]
exit
}
