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
# The same run again (meshes do not depend on the run) for ParaView, whose PLY reader
# drops the phases (docs/formats.md, "Which viewer shows what").
build/tools/voronoimesh/voronoimesh mesh -q -o out/demo.vtu
build/tools/voronoimesh/voronoimesh stats out/demo.ply
echo "wrote out/demo.vtu (ParaView: colour by phase1 or junction_order), out/demo.ply (voronoimesh stats/smooth,"
echo "meshio; MeshLab and Blender show its geometry) and out/demo_history.svg (open it in a browser)"
