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
# ldd's output is kept, not piped into `grep -q`: grep stops at the first match,
# ldd then dies of SIGPIPE and pipefail would report the match as a failure.
libraries=$(ldd "$plugin")
if grep -q "not found" <<<"$libraries"; then
  echo "FAIL: the installed plugin misses libraries:"; grep "not found" <<<"$libraries"; exit 1
fi
grep -q "$work/prefix/.*libvoronoimesh" <<<"$libraries" ||
  { echo "FAIL: the installed plugin does not load the installed libvoronoimesh"; echo "$libraries"; exit 1; }
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
