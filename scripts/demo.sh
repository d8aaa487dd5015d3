#!/usr/bin/env bash
# Quick start 1: set up, build, and mesh the built-in demo scene (the paper's four
# overlapping spheres), then print the mesh statistics.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
mkdir -p out
build/tools/voronoimesh/voronoimesh create -o out/demo.ply
build/tools/voronoimesh/voronoimesh stats out/demo.ply
