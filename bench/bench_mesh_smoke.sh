#!/usr/bin/env bash
# Smoke test of bench_mesh, so the driver run_table.sh relies on does not rot:
# on a tiny grid, each row has as many columns as the header and the rows for
# 1 and 2 threads end with the same mesh hash.
# Usage: bench_mesh_smoke.sh BENCH_MESH SCENE.json
set -euo pipefail
bench=$1 scene=$2
columns() { awk -F'|' '{ print NF }' <<<"$1"; }
header=$("$bench" --header | head -1)
one=$("$bench" "$scene" 12 1)
two=$("$bench" "$scene" 12 2)
for row in "$one" "$two"; do
  if [ "$(columns "$row")" != "$(columns "$header")" ]; then
    echo "row and header differ in columns:"; echo "$header"; echo "$row"; exit 1
  fi
done
hash() { awk -F'|' '{ gsub(/ /, "", $(NF-1)); print $(NF-1) }' <<<"$1"; }
if [ "$(hash "$one")" != "$(hash "$two")" ]; then
  echo "1 and 2 threads give different meshes:"; echo "$one"; echo "$two"; exit 1
fi
echo "$one"
