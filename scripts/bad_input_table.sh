#!/usr/bin/env bash
# Writes the table of bad inputs in docs/reliability.md: every failure case of the command-line
# tests (tests/cli/cli_tests.sh, expect_error), with the exit code and the one
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
BAD_INPUT_TABLE=$table bash tests/cli/cli_tests.sh "$(realpath build/tools/voronoimesh/voronoimesh)" \
  "$(realpath examples)" /tmp/voronoimesh_bad_inputs >/dev/null
python3 - "$table" <<'PY'
import sys
table = open(sys.argv[1]).read()
begin, end = "<!-- bad-inputs:begin -->", "<!-- bad-inputs:end -->"
readme = open("docs/reliability.md").read()
head, rest = readme.split(begin, 1)
_, tail = rest.split(end, 1)
open("docs/reliability.md", "w").write(f"{head}{begin}\n{table}{end}{tail}")
PY
echo "docs/reliability.md: $(($(wc -l <"$table") - 2)) bad inputs written between the bad-inputs markers" >&2
