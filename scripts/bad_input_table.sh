#!/usr/bin/env bash
# Writes the table of bad inputs in docs/reliability.md: every failure case of the command-line
# tests (tests/cli/cli_tests.sh and hostile_inputs.sh, expect_error), with the exit code and the one
# line the tool prints. The table comes from the tests themselves, so it cannot
# drift from what they check (one line, the exit code, no output file left).
# Usage: scripts/bad_input_table.sh   (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out
table=$(realpath out/bad_inputs.md)
{
  echo "| bad input | exit | message |"
  echo "|---|---|---|"
} >"$table"
for script in cli_tests.sh hostile_inputs.sh; do
  BAD_INPUT_TABLE=$table bash "tests/cli/$script" "$(realpath build/tools/voronoimesh/voronoimesh)" \
    "$(realpath examples)" /tmp/voronoimesh_bad_inputs >/dev/null
done
scripts/doc_tables.py replace docs/reliability.md bad-inputs "$table"
echo "docs/reliability.md: $(($(wc -l <"$table") - 2)) bad inputs written between the bad-inputs markers" >&2
