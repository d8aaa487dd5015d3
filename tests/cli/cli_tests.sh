#!/usr/bin/env bash
# Command-line tests: the built tool on the shipped scenes and on bad input.
# Usage: cli_tests.sh VORONOIMESH EXAMPLES_DIR WORK_DIR
set -uo pipefail
vm=$1 examples=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
passed=0 failed=0

pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

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
}

# The main job on the built-in demo, read back by stats.
if "$vm" create -q -o demo.ply && "$vm" stats demo.ply >stats.txt; then pass; else fail "create/stats on the demo"; fi
for want in "surfaces +10" "triple curves +10" "quadruple points +5" "topology +valid"; do
  if grep -qE "^$want" stats.txt; then pass; else fail "demo stats lack '$want': $(cat stats.txt)"; fi
done
if "$vm" stats --json demo.ply | grep -q '"surfaces": *10'; then pass; else fail "stats --json"; fi
if "$vm" stats --json demo.ply | grep -q '"self_intersections": *0'; then pass; else fail "stats self-intersections"; fi

# Every shipped scene, both lattices, ascii and binary.
for scene in "$examples"/*.json; do
  for lattice in bcc cube6; do
    if "$vm" create -q "$scene" --grid 24 --lattice "$lattice" -o s.ply && "$vm" stats s.ply >/dev/null; then pass
    else fail "$(basename "$scene") --lattice $lattice"; fi
  done
done
if "$vm" create -q --grid 16 --ascii -o a.ply && head -2 a.ply | grep -q "format ascii"; then pass; else fail "--ascii"; fi

# Identical files for any thread count.
"$vm" create -q "$examples/voronoi30.json" --grid 40 --threads 1 -o t1.ply
"$vm" create -q "$examples/voronoi30.json" --grid 40 --threads 2 -o t2.ply
if cmp -s t1.ply t2.ply; then pass; else fail "--threads 1 and 2 give different files"; fi

# Bad input: one line naming the problem, a non-zero exit, no output file.
echo '{"phases": [' >malformed.json
echo '{"phases": [{"kind": "spere", "center": [0,0,0], "radius": 1}, {"kind": "constant", "value": 0}]}' >kind.json
echo '{"phases": [{"kind": "constant", "value": 0}]}' >one.json
echo '{"grid": 0, "phases": [{"kind": "constant", "value": 0}, {"kind": "constant", "value": 1}]}' >grid0.json
echo '{"grid": 1000000, "phases": [{"kind": "constant", "value": 0}, {"kind": "constant", "value": 1}]}' >gridbig.json
: >empty.json
expect_error "missing file" 3 "missing\.json: cannot open" -- "$vm" create missing.json -o out.ply
expect_error "malformed JSON" 2 "malformed\.json: malformed JSON" -- "$vm" create malformed.json -o out.ply
expect_error "empty file" 2 "empty\.json: " -- "$vm" create empty.json -o out.ply
expect_error "unknown kind" 2 "kind\.json: .*unknown kind 'spere'" -- "$vm" create kind.json -o out.ply
expect_error "one phase" 2 "one\.json: .*two phases" -- "$vm" create one.json -o out.ply
expect_error "grid 0" 2 "grid0\.json: .*grid" -- "$vm" create grid0.json -o out.ply
expect_error "grid 10^6" 2 "gridbig\.json: .*grid" -- "$vm" create gridbig.json -o out.ply
expect_error "--grid 0" 2 "--grid: must be between 1 and 4096" -- "$vm" create --grid 0 -o out.ply
expect_error "--grid too big" 2 "--grid: .* needs about .* GiB" -- "$vm" create --grid 4096 -o out.ply
expect_error "--snap 2" 2 "snap: must be between 0 and 0.5" -- "$vm" create --snap 2 -o out.ply
expect_error "unwritable output" 3 "/nonexistent/out\.ply" -- "$vm" create --grid 8 -o /nonexistent/out.ply
expect_error "stats of a non-PLY" 3 "kind\.json: not a PLY" -- "$vm" stats kind.json
expect_error "stats of a missing file" 3 "nothere\.ply" -- "$vm" stats nothere.ply

# Improvement: the main job, its options, and the commands around it.
if "$vm" mesh -q --grid 32 --history hist.svg -o m.ply && "$vm" stats m.ply >mstats.txt; then pass; else fail "mesh with --history"; fi
if grep -qE "^topology +valid" mstats.txt && grep -q "</svg>" hist.svg; then pass; else fail "mesh result or history picture"; fi
"$vm" mesh -q "$examples/voronoi30.json" --grid 32 --iterations 5 --threads 1 -o mt1.ply
"$vm" mesh -q "$examples/voronoi30.json" --grid 32 --iterations 5 --threads 2 -o mt2.ply
if cmp -s mt1.ply mt2.ply; then pass; else fail "mesh --threads 1 and 2 give different files"; fi
if "$vm" smooth -q demo.ply --field "$examples/four_spheres.json" --iterations 3 -o sm.ply && "$vm" stats sm.ply >/dev/null; then pass
else fail "smooth"; fi
if "$vm" flip -q demo.ply -o fl.ply && "$vm" stats fl.ply >/dev/null; then pass; else fail "flip"; fi
if "$vm" passes | grep -q "rest_factor" && "$vm" passes | grep -q "^flip"; then pass; else fail "passes listing"; fi
if "$vm" mesh -q --grid 24 --iterations 50 --stop-when-converged -o conv.ply; then pass; else fail "--stop-when-converged"; fi

printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >nophase.ply
echo '{"phases": [{"kind": "constant", "value": 0}, {"kind": "constant", "value": 1}]}' >twophases.json
echo '{"domain": {"min": [5,5,5], "max": [6,6,6]}, "phases": [{"kind": "constant", "value": 0}, {"kind": "sphere", "center": [5.5,5.5,5.5], "radius": 0.2},
  {"kind": "sphere", "center": [5.5,5.5,5.5], "radius": 0.2}, {"kind": "sphere", "center": [5.5,5.5,5.5], "radius": 0.2},
  {"kind": "sphere", "center": [5.5,5.5,5.5], "radius": 0.2}]}' >elsewhere.json
expect_error "mesh without phases" 3 "nophase\.ply: .*phase0" -- "$vm" smooth nophase.ply --field "$examples/four_spheres.json" -o out.ply
expect_error "field with too few phases" 2 "twophases\.json: has 2 phases" -- "$vm" smooth demo.ply --field twophases.json -o out.ply
expect_error "field elsewhere" 2 "elsewhere\.json: its domain" -- "$vm" smooth demo.ply --field elsewhere.json -o out.ply
expect_error "smooth without a field" 2 "needs the phase functions" -- "$vm" smooth demo.ply -o out.ply
expect_error "unknown pass" 2 "unknown pass 'smoth'" -- "$vm" mesh --grid 8 --pipeline smoth,flip -o out.ply
expect_error "unknown parameter" 2 "no parameter 'rest'" -- "$vm" mesh --grid 8 --pipeline smooth:rest=1 -o out.ply
expect_error "parameter out of range" 2 "rest_factor = 9" -- "$vm" mesh --grid 8 --pipeline smooth:rest_factor=9 -o out.ply
expect_error "bad history format" 2 "history" -- "$vm" mesh --grid 8 --history h.txt -o out.ply

# Output formats: every extension, chosen by the file name, checked before any work.
for ext in ply obj msh vtu vtp mesh; do
  if "$vm" create -q --grid 12 -o "fmt.$ext" && [ -s "fmt.$ext" ]; then pass; else fail "create -o fmt.$ext"; fi
done
if "$vm" create -q --grid 12 -o surf.stl --per-phase phases && [ ! -e surf.stl ] && [ "$(ls surf_*.stl | wc -l)" -eq 10 ] &&
  [ -s surf_0-outside_1-sphere1.stl ] && [ "$(ls phases/phase_*.stl | wc -l)" -eq 5 ]; then pass
else fail "-o surf.stl: one file per phase pair, --per-phase: one per phase"; fi
if "$vm" create --grid 12 -o surf2.stl 2>&1 | grep -q "10 STL files, one per phase pair"; then pass; else fail "STL files reported"; fi
if "$vm" create --help | grep -q "\.vtp" && "$vm" create --help | grep -q "per-phase"; then pass; else fail "--help lists the formats"; fi
if "$vm" flip -q demo.ply -o fl.msh && grep -q '^\$PhysicalNames' fl.msh; then pass; else fail "flip -o .msh"; fi
: >blocker
expect_error "unknown extension" 2 "out\.xyz: unknown output format '\.xyz' \(known: \.ply, \.obj, \.stl, \.msh, \.vtu, \.vtp, \.mesh\)" \
  -- "$vm" create --grid 4096 -o out.xyz
expect_error "no extension" 2 "out: no extension" -- "$vm" mesh --grid 4096 -o out
expect_error "--per-phase in a missing directory" 3 "/nonexistent/dir: cannot write" \
  -- "$vm" mesh --grid 4096 -o out.ply --per-phase /nonexistent/dir
expect_error "--per-phase on a file" 3 "blocker: --per-phase: not a directory" -- "$vm" create --grid 4096 -o out.ply --per-phase blocker
expect_error "smooth to an unknown format" 2 "out\.off: unknown output format" -- "$vm" smooth demo.ply -o out.off

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
