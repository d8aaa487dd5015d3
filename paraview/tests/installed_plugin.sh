#!/usr/bin/env bash
# The installed plugin: `cmake --install` puts VoronoiMesh.so under
# lib/paraview-5.11/plugins/VoronoiMesh/, every library it needs resolves from
# there (libvoronoimesh beside the prefix's other libraries), and pvpython finds it
# through PV_PLUGIN_PATH alone and meshes a small label image with it.
# Usage: installed_plugin.sh BUILD_DIR WORK_DIR PVPYTHON
set -euo pipefail
build=$1 work=$2 pvpython=$3
rm -rf "$work" && mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
plugin=$(find "$work/prefix" -path "*/paraview-5.11/plugins/VoronoiMesh/VoronoiMesh.so")
[ -n "$plugin" ] || { echo "FAIL: no paraview-5.11/plugins/VoronoiMesh/VoronoiMesh.so under the prefix"; exit 1; }
if ldd "$plugin" | grep -q "not found"; then
  echo "FAIL: the installed plugin misses libraries:"; ldd "$plugin" | grep "not found"; exit 1
fi
ldd "$plugin" | grep -q "$work/prefix/.*libvoronoimesh" ||
  { echo "FAIL: the installed plugin does not load the installed libvoronoimesh"; ldd "$plugin"; exit 1; }
cat >"$work/run.py" <<'PY'
from paraview.simple import Wavelet, PointDatatoCellData, Calculator, servermanager
import paraview.simple as pv
w = Wavelet(WholeExtent=[0, 15, 0, 15, 0, 15])
labels = Calculator(Input=w, ResultArrayName="labels", Function="1 + (RTData > 150)", ResultArrayType="Int")
f = pv.VoronoiMesh(Input=labels, Iterations=3)
f.Labels = ["POINTS", "labels"]
n = servermanager.Fetch(f).GetNumberOfCells()
assert n > 50, n
print(f"installed plugin: {n} triangles")
PY
PV_PLUGIN_PATH=$(dirname "$plugin") DISPLAY= "$pvpython" "$work/run.py"
