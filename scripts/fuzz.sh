#!/usr/bin/env bash
# Fuzzes every reader (fuzz/): builds the libFuzzer targets with clang, ASan and
# UBSan into build-fuzz, then runs each target for SECONDS (default 60), one after
# the other, and prints per target the executions, the coverage libFuzzer reached
# (cov: edges, ft: features) and whether it found a crash, leak, timeout or OOM.
#
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [READER...]
#   readers (targets, default: all): scene nrrd nrrd_detached nrrd_compressed nifti
#   nifti_gz nifti_gzipped metaimage metaimage_detached inr tiff points ply_points ply_mesh
#   (_detached: a header and its data files from one input; nifti_gz: the gzip
#   stream as it is; nifti_gzipped, nrrd_compressed: data the target compresses)
# The corpus of each reader grows across runs in build-fuzz/fuzz_runs/corpus/<reader>;
# a crashing input lands in build-fuzz/fuzz_runs/artifacts/<reader>/ (rerun it with
# build-fuzz/fuzz/fuzz_<reader> FILE) and belongs under tests/data/fuzz/ once fixed.
# Exit status: 1 if any target found a fault.
set -euo pipefail

seconds=${1:-60}
shift || true
readers=("$@")
[ ${#readers[@]} -gt 0 ] || readers=(scene nrrd nrrd_detached nrrd_compressed nifti nifti_gz nifti_gzipped metaimage
  metaimage_detached inr tiff points ply_points ply_mesh)
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz
work=$build/fuzz_runs

CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVORONOIMESH_FUZZ=ON \
  -DVORONOIMESH_BUILD_TESTS=OFF -DVORONOIMESH_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --target fuzz_targets -j2 >/dev/null
rm -rf "$work/seeds"
python3 "$root/fuzz/make_corpus.py" "$work/seeds"

# The dictionary of each reader's format, where it has one.
dictionary() {
  case $1 in
  nrrd* | metaimage* | inr | scene) echo "$root/fuzz/dict/${1%%_*}.dict" ;;
  ply_points | ply_mesh) echo "$root/fuzz/dict/ply.dict" ;;
  esac
}

# Inputs are written to a file per run: in memory, not on disk, where possible.
[ -w /dev/shm ] && export TMPDIR=/dev/shm

printf '%-18s %12s %8s %8s %s\n' reader executions cov ft result
faults=0
for reader in "${readers[@]}"; do
  corpus=$work/corpus/$reader artifacts=$work/artifacts/$reader log=$work/$reader.log
  mkdir -p "$corpus" "$artifacts"
  dict=$(dictionary "$reader")
  # Teem (Debian 12's libteem2, a 1.12 snapshot) leaks its header line buffer, or its zlib
  # stream, on most NRRDs it refuses; each leak check then costs ~0.1 s. Our
  # side holds Teem's Nrrd in a unique_ptr, so NRRD runs without leak checks.
  leaks=1
  case $reader in nrrd*) leaks=0 ;; esac
  # 4 KiB holds every header with a small volume after it; 10 s for one input
  # is a hang; 2 GiB is far beyond what a 4 KiB input may make a reader take.
  status=0
  ASAN_OPTIONS=detect_leaks=$leaks "$build/fuzz/fuzz_$reader" -detect_leaks=$leaks -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$artifacts/" ${dict:+-dict="$dict"} \
    "$corpus" "$work/seeds/$reader" >"$log" 2>&1 || status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cov_line=$(grep -E '^#[0-9]+.*cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  cov=$(sed -E 's/.*cov: ([0-9]+).*/\1/' <<<"$cov_line")
  ft=$(sed -E 's/.*ft: ([0-9]+).*/\1/' <<<"$cov_line")
  if [ "$status" -eq 0 ]; then
    result=clean
  else
    faults=1
    result="FAULT ($(grep -m1 -oE 'ERROR: [A-Za-z]+: [a-z-]+|ERROR: libFuzzer: [a-z-]+|runtime error: .*' "$log" || echo "exit $status")): $(ls -t "$artifacts" | head -1), see $log"
  fi
  printf '%-18s %12s %8s %8s %s\n' "$reader" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$result"
done
exit $faults
