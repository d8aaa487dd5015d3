#!/usr/bin/env bash
# Plugins through the tool and the example host: listing, use in pipelines, and
# one-line refusals of broken plugins.
# Usage: cli_plugins.sh VORONOIMESH PLUGIN_DIR FAKE_PLUGIN_DIR HOST WORK_DIR
set -uo pipefail
vm=$1 plugins=$2 fakes=$3 host=$4 work=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
passed=0 failed=0
pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
# Only the plugins a test names (and those of the installed folder).
export VORONOIMESH_PLUGIN_PATH=

# expect_refusal NAME PATTERN -- command...: exit 2 (or $CODE) and one line on stderr matching PATTERN.
expect_refusal() {
  local name=$1 pattern=$2 code=${CODE:-2}
  shift 3
  "$@" >stdout.txt 2>stderr.txt
  local got=$? lines
  lines=$(wc -l <stderr.txt)
  if [ "$got" -ne "$code" ]; then fail "$name: exit $got, expected $code ($(cat stderr.txt))"
  elif [ "$lines" -ne 1 ]; then fail "$name: $lines lines on stderr: $(cat stderr.txt)"
  elif ! grep -qE -e "$pattern" stderr.txt; then fail "$name: '$(cat stderr.txt)' does not match '$pattern'"
  else pass; fi
}

# Listing: what was found in the path and loaded, with its passes.
VORONOIMESH_PLUGIN_PATH=$plugins "$vm" plugins >list.txt 2>&1
if grep -q "^loaded   relax 1.0  $plugins/relax.so (VORONOIMESH_PLUGIN_PATH)" list.txt &&
   grep -q "^loaded   cvt 1.0  $plugins/cvt.so" list.txt && grep -q "passes: relax" list.txt &&
   grep -q "2 loaded, 0 refused" list.txt; then pass; else fail "plugins listing: $(cat list.txt)"; fi
# The refused ones are listed with the reason, and the command still succeeds.
if VORONOIMESH_PLUGIN_PATH=$fakes "$vm" plugins >list.txt 2>&1 && grep -q " loaded, 3 refused" list.txt &&
   grep -q "built for plugin ABI version 2" list.txt && grep -q "no voronoimesh_plugin_v1 entry point" list.txt &&
   grep -q "a pass named 'smooth' is already registered" list.txt; then pass; else fail "refusals listed: $(cat list.txt)"; fi

# passes: plugin passes beside the built-in ones.
"$vm" passes --plugin "$plugins/relax.so" --plugin "$plugins/cvt.so" >passes.txt 2>&1
for want in "^relax  \[plugin relax 1.0\]" "^cvt  \[plugin cvt 1.0\]" "^smooth" "^    lambda +0.5" "^    step +0.5"; do
  if grep -qE "$want" passes.txt; then pass; else fail "passes lacks '$want': $(cat passes.txt)"; fi
done

# Pipelines use them by name; the result is valid and uncrossed (stats fails otherwise).
if "$vm" mesh -q --grid 16 --plugin "$plugins/relax.so" --pipeline relax,project,clamp,flip --iterations 5 -o relax.ply &&
   "$vm" stats --json relax.ply >stats.txt && grep -q '"self_intersections": *0' stats.txt; then pass; else fail "mesh with relax: $(cat stats.txt)"; fi
# Found through the path, on a mesh alone (cvt needs no phase functions).
if VORONOIMESH_PLUGIN_PATH=$plugins "$vm" smooth -q relax.ply --pipeline cvt,clamp,flip --iterations 3 -o cvt.ply &&
   "$vm" stats --json cvt.ply >stats.txt && grep -q '"self_intersections": *0' stats.txt; then pass
else fail "smooth with cvt from the path: $(cat stats.txt)"; fi
expect_refusal "unknown pass without its plugin" "unknown pass 'fake'" -- "$vm" mesh -q --pipeline fake -o x.ply

# Refusals, each one line naming the file.
echo "not a plugin" >notes.so
expect_refusal "text file" "^voronoimesh: notes.so: not a voronoimesh plugin: cannot load it as a shared library \(" -- \
  "$vm" passes --plugin notes.so
expect_refusal "wrong ABI" "^voronoimesh: $fakes/fake_wrong_abi.so: built for plugin ABI version 2, but this voronoimesh loads version 1 only" -- \
  "$vm" passes --plugin "$fakes/fake_wrong_abi.so"
expect_refusal "no entry point" "^voronoimesh: $fakes/fake_no_entry.so: not a voronoimesh plugin: no voronoimesh_plugin_v1 entry point$" -- \
  "$vm" mesh -q --plugin "$fakes/fake_no_entry.so" -o x.ply
expect_refusal "name clash" "^voronoimesh: $fakes/fake_clash.so: plugin 'fake' cannot add its passes: a pass named 'smooth' is already registered$" -- \
  "$vm" passes --plugin "$fakes/fake_clash.so"
# A plugin's fault is its own exit code, 6, naming the plugin and the pass.
CODE=6 expect_refusal "failing pass" "^voronoimesh: $fakes/fake_failing.so: pass 'fake': cannot relax [0-9]+ nodes today$" -- \
  "$vm" mesh -q --grid 12 --plugin "$fakes/fake_failing.so" --pipeline fake -o x.ply
CODE=6 expect_refusal "pass moving by NaN" "^voronoimesh: $fakes/fake_nan.so: pass 'nan_move' moved node 0 by \(nan, " -- \
  "$vm" mesh -q --grid 12 --plugin "$fakes/fake_nan.so" --pipeline nan_move,project,clamp,flip -o x.ply
# A broken plugin in a folder is named once on stderr; the command still works.
VORONOIMESH_PLUGIN_PATH=$fakes "$vm" passes >passes.txt 2>stderr.txt
if [ $? -eq 0 ] && [ "$(grep -c "plugin skipped" stderr.txt)" -eq 3 ]; then pass; else fail "skipped plugins: $(cat stderr.txt)"; fi

# A plugin hidden by one of the same name says so, naming the one loaded.
mkdir -p mine && cp "$plugins/relax.so" mine/relax.so
VORONOIMESH_PLUGIN_PATH=$plugins "$vm" passes --plugin mine/relax.so >passes.txt 2>stderr.txt
if grep -qF "plugin skipped: $plugins/relax.so: a plugin named 'relax' was loaded before, from mine/relax.so" stderr.txt
then pass; else fail "a shadowed plugin is not named: $(cat stderr.txt)"; fi
# A plugin anyone could have put there loads with a warning.
mkdir -p open && cp "$plugins/cvt.so" open/cvt.so && chmod 777 open
VORONOIMESH_PLUGIN_PATH=open "$vm" passes >passes.txt 2>stderr.txt
if grep -qF "warning: plugin open/cvt.so: loaded, but anyone may write its folder open" stderr.txt &&
   VORONOIMESH_PLUGIN_PATH=open "$vm" plugins | grep -F "warning: open/cvt.so: loaded, but anyone may write its folder open" >/dev/null
then pass; else fail "a plugin in a world-writable folder loads silently: $(cat stderr.txt)"; fi

# The example host loads a plugin and runs a pipeline through the library.
if "$host" "$plugins/relax.so" relax,project,clamp,flip host.ply >host.txt 2>&1 &&
   grep -q "loaded plugin relax 1.0 with 1 pass" host.txt && grep -q "valid, no intersections" host.txt &&
   "$vm" stats host.ply | grep -E "^topology +valid" >/dev/null; then pass; else fail "host: $(cat host.txt)"; fi
if ! "$host" "$fakes/fake_wrong_abi.so" relax host2.ply >host.txt 2>&1 && grep -q "plugin ABI version 2" host.txt &&
   [ ! -e host2.ply ]; then pass; else fail "host with a wrong ABI: $(cat host.txt)"; fi

echo "cli_plugins: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
