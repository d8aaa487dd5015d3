#!/usr/bin/env bash
# Builds the project with sanitizers and runs the test suite under them:
#   asan  AddressSanitizer + LeakSanitizer + UndefinedBehaviorSanitizer, every test (build-asan/)
#   tsan  ThreadSanitizer, every test but install (build-tsan/; see below): each parallel pass runs on TBB's
#         threads in the create, improve, sample, guard, flip and determinism tests.
#         Debian's libtbb is not instrumented; the library's parallel calls tell TSan
#         what TBB guarantees instead (libvoronoimesh/src/core/tbb_sanitizer.hpp).
#   all   both, ASan first
# Both builds have VM_MPI=ON, so the distributed create (voronoimesh_mpi) and its tests
# under mpirun run instrumented too (scripts/setup.sh --mpi installs OpenMPI).
# Any finding aborts the test that triggers it, so a clean run is a green ctest.
# Usage: scripts/test_sanitizers.sh [asan (default)|tsan|all] [extra ctest arguments, e.g. -R Improve]
set -euo pipefail
cd "$(dirname "$0")/.."
variant=${1:-asan}
shift || true
jobs=$(nproc)

# run VARIANT SANITIZERS: configure, build and test one sanitizer build.
run() {
  local dir=build-$1 sanitizers=$2
  shift 2
  echo "== $dir: -fsanitize=$sanitizers"
  # RelWithDebInfo: optimised enough for the suite to finish, with line numbers in reports.
  # The benchmarks are left out: they test speed, which sanitizers distort.
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVM_SANITIZE="$sanitizers" \
    -DVM_MPI=ON -DVORONOIMESH_BUILD_BENCH=OFF >/dev/null
  cmake --build "$dir" -j"$jobs"
  ctest --test-dir "$dir" --output-on-failure -j"$jobs" --timeout 1200 "$@"
}

# Findings abort (halt_on_error) with whole stacks. The install test links uninstrumented
# consumer programs against the instrumented library, so the ASan runtime is not the
# first library they load; that is harmless there (verify_asan_link_order=0).
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:verify_asan_link_order=0:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1

# Under ThreadSanitizer the install test's consumers (uninstrumented programs
# linked against the instrumented library) deadlock as they exit: libp11-kit's
# destructor (HDF5 -> curl -> gnutls -> p11-kit) waits in freelocale() on
# glibc's locale lock, with no other thread running (gdb, 2026-12-02). Nothing
# of ours is on that stack, and each consumer would hang until the timeout, so
# the tsan build leaves that test out.
tsan_skip=(-E '^install$')

case "$variant" in
  asan) run asan address,undefined "$@" ;;
  tsan) run tsan thread "${tsan_skip[@]}" "$@" ;;
  all) run asan address,undefined "$@" && run tsan thread "${tsan_skip[@]}" "$@" ;;
  *) echo "usage: scripts/test_sanitizers.sh [asan|tsan|all] [ctest arguments]" >&2; exit 2 ;;
esac
