#!/usr/bin/env bash
# Quick start 2: set up, build, and run every test, the distributed (MPI) ones
# and the ParaView plugin's too.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --test-readers --mpi --paraview
scripts/build.sh --mpi --paraview
ctest --test-dir build --output-on-failure -j"$(nproc)"
