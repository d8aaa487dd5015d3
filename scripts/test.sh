#!/usr/bin/env bash
# Quick start 2: set up, build, and run every test.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --test-readers
scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
