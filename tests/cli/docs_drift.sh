#!/usr/bin/env bash
# The tables and the figure the docs quote from deterministic runs must be what a
# fresh run makes: the paper's Fig. 3 table and the quality table of
# docs/benchmarks.md, the demo's quality history (docs/images) and the passes the
# ParaView filter's Pipeline help lists. When one
# drifts, scripts/regenerate_docs.sh makes them anew (and the text around them
# may need a look). Usage: docs_drift.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -uo pipefail
build=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
failed=0
BUILD=$build OUT=$work "$source/bench/fig3.sh" >"$work/fig3.md" &&
  python3 "$source/scripts/doc_tables.py" check "$source/docs/benchmarks.md" fig3 "$work/fig3.md" || failed=1
BUILD=$build OUT=$work "$source/bench/quality.sh" >"$work/quality.md" &&
  python3 "$source/scripts/doc_tables.py" check "$source/docs/benchmarks.md" quality "$work/quality.md" || failed=1
"$build/tools/voronoimesh/voronoimesh" mesh -q -o "$work/demo.ply" --history "$work/history.svg" &&
  cmp -s "$work/history.svg" "$source/docs/images/four_spheres_history.svg" ||
  { echo "docs/images/four_spheres_history.svg differs from a fresh run (scripts/regenerate_docs.sh)"; failed=1; }
"$build/tools/voronoimesh/voronoimesh" passes | python3 "$source/scripts/pass_help_xml.py" >"$work/passes.xml" &&
  python3 "$source/scripts/doc_tables.py" check "$source/paraview/plugin/filter/VoronoiMeshFilter.xml" passes \
    "$work/passes.xml" || failed=1
[ $failed = 0 ] && echo "docs: Fig. 3 table, quality table, quality history and the ParaView filter's passes as a fresh run makes them"
exit $failed
