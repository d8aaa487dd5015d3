#!/usr/bin/env bash
# Makes every table and figure the docs quote from runs anew, in place (between
# their markers, scripts/doc_tables.py), from this one command.
#   default: the deterministic ones (about a minute): the paper's Fig. 3 table and
#            the quality table (docs/benchmarks.md), the demo's quality history
#            (docs/images/four_spheres_history.svg, the paper's Fig. 7), and the
#            table of bad inputs (docs/reliability.md), and the passes the ParaView
#            filter's Pipeline help lists (paraview/plugin/filter/VoronoiMeshFilter.xml).
#            The docs_drift test fails when the first three or the passes differ
#            from a fresh run.
#   --all:   also the timed ones, which take long: the benchmark table
#            (bench/run_table.sh). The label-volume and MPI tables print their rows
#            (bench/run_labels.sh, bench/run_mpi.sh) for the text around them.
# Usage: scripts/regenerate_docs.sh [--all]   (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
all=0
case "${1:-}" in
  --all) all=1 ;;
  "") ;;
  *) echo "usage: scripts/regenerate_docs.sh [--all]" >&2; exit 2 ;;
esac
out=out/docs
mkdir -p "$out"
OUT=$out bench/fig3.sh >"$out/fig3.md"
scripts/doc_tables.py replace docs/benchmarks.md fig3 "$out/fig3.md"
OUT=$out bench/quality.sh >"$out/quality.md"
scripts/doc_tables.py replace docs/benchmarks.md quality "$out/quality.md"
build/tools/voronoimesh/voronoimesh mesh -q -o "$out/demo.ply" --history docs/images/four_spheres_history.svg
echo "docs/images/four_spheres_history.svg written" >&2
scripts/bad_input_table.sh
build/tools/voronoimesh/voronoimesh passes | scripts/pass_help_xml.py >"$out/passes.xml"
scripts/doc_tables.py replace paraview/plugin/filter/VoronoiMeshFilter.xml passes "$out/passes.xml"
if [ $all = 1 ]; then bench/run_table.sh; fi
