#!/usr/bin/env bash
# Smoke test of pass_times, so the tool the closing notes cite does not rot: on
# a tiny grid it takes the pipeline voronoimesh mesh takes for a scene (remesh
# first), prints one row per iteration and a row of sums, each with as many
# columns as the header, and answers a bad option or value with its usage and exit 2.
# Usage: pass_times_smoke.sh PASS_TIMES SCENE.json
set -euo pipefail
tool=$1 scene=$2
out=$("$tool" "$scene" --grid 12 --iterations 2 --threads 2)
echo "$out"
grep -q "iterations of remesh:" <<<"$out" || { echo "not the scenes' default pipeline"; exit 1; }
header=$(grep '^| iteration' <<<"$out")
columns() { awk -F'|' '{ print NF }' <<<"$1"; }
rows=$(grep -cE '^\| [0-9]+ \|' <<<"$out")
[ "$rows" = 2 ] || { echo "expected 2 iteration rows, got $rows"; exit 1; }
while read -r row; do
  [ "$(columns "$row")" = "$(columns "$header")" ] || { echo "row and header differ in columns: $row"; exit 1; }
done < <(grep -E '^\| ([0-9]+|all) \|' <<<"$out")
set +e
"$tool" "$scene" --no-such-option 2>/dev/null
status=$?
set -e
[ "$status" = 2 ] || { echo "a bad option exited $status, not 2"; exit 1; }
set +e
"$tool" "$scene" --voxels-per-cell abc 2>/dev/null
status=$?
set -e
[ "$status" = 2 ] || { echo "--voxels-per-cell abc exited $status, not 2"; exit 1; }
