#!/usr/bin/env bash
# The ParaView plugin in pvpython on CGAL's liver against the CLI on the same file
# (issue 20): the same triangles, and both times (bench/paraview_liver.py).
# Needs a build with the plugin (scripts/setup.sh --paraview; scripts/build.sh --paraview).
# Usage: [BUILD=build] [OUT=out/race] bench/paraview_liver.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build} OUT=${OUT:-out/race}
liver=$(bench/get_liver.sh "$OUT")
plugin=$BUILD/lib/paraview-5.11/plugins/VoronoiMesh/VoronoiMesh.so
[ -f "$plugin" ] || { echo "paraview_liver.sh: no $plugin: build with scripts/build.sh --paraview" >&2; exit 2; }
DISPLAY= pvpython bench/paraview_liver.py "$liver" "$plugin" "$BUILD/tools/voronoimesh/voronoimesh" "$OUT/paraview"
