# The checks the command-line tests share (sourced by cli_tests.sh and
# hostile_inputs.sh, which have set $work, the folder they run in).
passed=0 failed=0

pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

# `command | contains PATTERN`: grep that reads all its input. `grep -q` stops at
# the first match; a command still writing then dies of SIGPIPE, which pipefail
# reports as a failed check.
contains() { grep "$@" >/dev/null; }

# expect_error NAME EXIT_CODE PATTERN -- command...: the command fails with that
# exit code, prints exactly one line on stderr matching PATTERN, and leaves no out.ply.
expect_error() {
  local name=$1 code=$2 pattern=$3
  shift 4
  rm -f out.ply
  "$@" >stdout.txt 2>stderr.txt
  local got=$?
  local lines
  lines=$(wc -l <stderr.txt)
  if [ "$got" -ne "$code" ]; then fail "$name: exit $got, expected $code ($(cat stderr.txt))"
  elif [ "$lines" -ne 1 ]; then fail "$name: $lines lines on stderr, expected 1: $(cat stderr.txt)"
  elif ! grep -qE -e "$pattern" stderr.txt; then fail "$name: message '$(cat stderr.txt)' does not match '$pattern'"
  elif [ -e out.ply ] || ls out.ply.tmp-* >/dev/null 2>&1; then fail "$name: left an output file behind"
  else pass; fi
  # scripts/bad_input_table.sh collects every case's message for docs/reliability.md.
  if [ -n "${BAD_INPUT_TABLE:-}" ]; then
    printf '| %s | %s | %s |\n' "$name" "$got" "$(sed -e "s#$work/##g" -e 's/|/\\|/g' stderr.txt)" >>"$BAD_INPUT_TABLE"
  fi
}
