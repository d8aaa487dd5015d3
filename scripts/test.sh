#!/usr/bin/env bash
# Quick start 2: set up, build, and run every test, the distributed (MPI) ones too.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --test-readers --mpi
scripts/build.sh --mpi
ctest --test-dir build --output-on-failure -j"$(nproc)"
