#!/usr/bin/env bash
# Quick start 1: set up, build, and run the main job on the built-in demo scene
# (the paper's four overlapping spheres): create the initial mesh, improve it for
# 20 iterations, write it with a picture of the quality history, print its stats.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
mkdir -p out
build/tools/voronoimesh/voronoimesh mesh -o out/demo.ply --history out/demo_history.svg
build/tools/voronoimesh/voronoimesh stats out/demo.ply
echo "wrote out/demo.ply (open it in ParaView or MeshLab) and out/demo_history.svg (open it in a browser)"
