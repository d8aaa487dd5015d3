#!/usr/bin/env bash
# Command-line tests: the built tool on the shipped scenes and on bad input.
# Usage: cli_tests.sh VORONOIMESH EXAMPLES_DIR WORK_DIR
set -uo pipefail
vm=$1 examples=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
source "$here/expect.sh"

# The main job on the built-in demo, read back by stats.
if "$vm" create -q -o demo.ply && "$vm" stats demo.ply >stats.txt; then pass; else fail "create/stats on the demo"; fi
for want in "surfaces +10" "triple curves +10" "quadruple points +5" "topology +valid"; do
  if grep -qE "^$want" stats.txt; then pass; else fail "demo stats lack '$want': $(cat stats.txt)"; fi
done
if "$vm" stats --json demo.ply | contains '"surfaces": *10'; then pass; else fail "stats --json"; fi
if "$vm" stats --json demo.ply | contains '"self_intersections": *0'; then pass; else fail "stats self-intersections"; fi
# --worst N lists N triangles (a first line each, then one per corner), also in JSON; a negative N is refused.
if [ "$("$vm" stats --worst 4 demo.ply | grep -cE '^triangle [0-9]+: q ')" = 4 ]; then pass; else fail "stats --worst 4"; fi
if "$vm" stats --json --worst 2 demo.ply | python3 -c 'import json, sys; w = json.load(sys.stdin)["worst_triangles"]; sys.exit(not (len(w) == 2 and w[0]["quality"] <= w[1]["quality"] and len(w[0]["corners"]) == 3))'; then pass; else fail "stats --json --worst 2"; fi
if "$vm" stats --worst -1 demo.ply >/dev/null 2>worst.err; then fail "stats --worst -1 accepted"; elif grep -q "worst" worst.err; then pass; else fail "stats --worst -1: $(cat worst.err)"; fi
# --folds N lists the sharpest folds (a first line each, then one per end): a
# tetrahedron flattened to its apex 0.05 over its base folds at the base's three edges.
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nelement face 4\nproperty list uchar int vertex_indices\nproperty int phase0\nproperty int phase1\nend_header\n0 0 0\n1 0 0\n0 1 0\n0.3 0.3 0.05\n3 0 2 1 0 1\n3 0 1 3 0 1\n3 1 2 3 0 1\n3 2 0 3 0 1\n' >flat.ply
if [ "$("$vm" stats --folds 2 flat.ply | grep -cE '^edge [0-9]+-[0-9]+: turns 1[5-8][0-9]\.[0-9] deg')" = 2 ]; then pass; else fail "stats --folds 2"; fi
if "$vm" stats --json --folds 5 flat.ply | python3 -c 'import json, sys; s = json.load(sys.stdin); f = s["sharpest_folds"]; sys.exit(not (s["folds"] == 3 and len(f) == 3 and f[0]["turn_deg"] >= f[2]["turn_deg"] > 150 and len(f[0]["ends"]) == 2))'; then pass; else fail "stats --json --folds 5"; fi
if "$vm" stats --folds -1 flat.ply >/dev/null 2>folds.err; then fail "stats --folds -1 accepted"; elif grep -q "folds" folds.err; then pass; else fail "stats --folds -1: $(cat folds.err)"; fi
# --field: how far the nodes lie from the interface of the input; a field the mesh was not made from is refused.
if "$vm" stats --field "$examples/four_spheres.json" demo.ply >offsets.txt && grep -qE "^  quadruple points +5: rms" offsets.txt &&
  "$vm" stats --json --field "$examples/four_spheres.json" demo.ply | python3 -c 'import json, sys; o = json.load(sys.stdin)["offsets"]; sys.exit(not (o["surface"]["nodes"] > 1000 and 0 < o["triple_curve"]["max_h"] < 0.5))'; then pass
else fail "stats --field: $(cat offsets.txt)"; fi
# Offsets are told in the h of the grid the mesh was created on (its PLY says), not the input's default grid.
if "$vm" create -q "$examples/four_spheres.json" --grid 24 --ascii -o g24.ply &&
  "$vm" stats --json --field "$examples/four_spheres.json" g24.ply | python3 -c 'import json, sys; o = json.load(sys.stdin)["offsets"]; sys.exit(not abs(o["spacing"] - 1 / 24) < 1e-15)' &&
  grep -v '^comment grid_spacing' g24.ply >g24_unsaid.ply && "$vm" stats --field "$examples/four_spheres.json" g24_unsaid.ply | grep -q "the mesh does not say its own"; then pass
else fail "stats --field on a mesh created at --grid 24"; fi
cp "$examples/voronoi7.json" seven.json
expect_error "stats --field of another input" 2 "seven\.json: its phase 0 is .cell0., but demo\.ply" -- "$vm" stats --field seven.json demo.ply
# Label options say how to read --field: without it they are refused, not ignored.
expect_error "stats label option without --field" 2 "--keep-labels requires --field" -- "$vm" stats --keep-labels 1 demo.ply
expect_error "smooth label option without --field" 2 "--world requires --field" -- "$vm" smooth demo.ply --world ras -o out.ply

# Every shipped scene, both lattices, ascii and binary.
for scene in "$examples"/*.json; do
  for lattice in bcc cube6; do
    if "$vm" create -q "$scene" --grid 24 --lattice "$lattice" -o s.ply && "$vm" stats s.ply >/dev/null; then pass
    else fail "$(basename "$scene") --lattice $lattice"; fi
  done
done
if "$vm" create -q --grid 16 --ascii -o a.ply && head -2 a.ply | contains "format ascii"; then pass; else fail "--ascii"; fi

# Closed domains: an extra phase 'exterior', a valid mesh that smooth can improve again.
if "$vm" mesh -q "$examples/voronoi7.json" --grid 24 --close --iterations 5 -o closed.ply &&
  "$vm" stats closed.ply >closed.txt && grep -qE "^phases +8" closed.txt && grep -q "topology *valid" closed.txt &&
  grep -q "comment phase 7 exterior" closed.ply; then pass; else fail "mesh --close: $(cat closed.txt)"; fi
if "$vm" smooth -q closed.ply --field "$examples/voronoi7.json" --iterations 3 -o closed2.ply &&
  "$vm" stats closed2.ply | contains "topology *valid"; then pass; else fail "smooth of a closed mesh"; fi

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
# The library names its options (top_k); the tool names them as its command line does.
expect_error "--top-k 0" 2 "^voronoimesh: --top-k: must be between 1 and 16, got 0" -- "$vm" create --top-k 0 -o out.ply
expect_error "--iterations -1" 2 "^voronoimesh: --iterations: must be 0 or more" -- "$vm" mesh --iterations -1 -o out.ply
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
"$vm" improve -q demo.ply --field "$examples/four_spheres.json" --iterations 3 -o im.ply
if cmp -s sm.ply im.ply; then pass; else fail "improve is not smooth's synonym"; fi
if "$vm" flip -q demo.ply -o fl.ply && "$vm" stats fl.ply >/dev/null; then pass; else fail "flip"; fi
if "$vm" passes | contains "rest_factor" && "$vm" passes | contains "^flip"; then pass; else fail "passes listing"; fi
# --stop-when-converged stops early, and where it stops is the mesh of that many iterations.
"$vm" mesh --grid 24 --iterations 50 --stop-when-converged -o conv.ply 2>conv.txt
done_its=$(sed -n 's/^improve: \([0-9]*\) iterations.*/\1/p' conv.txt)
if [ -n "$done_its" ] && [ "$done_its" -lt 50 ] && "$vm" mesh -q --grid 24 --iterations "$done_its" -o conv_n.ply &&
  cmp -s conv.ply conv_n.ply; then pass; else fail "--stop-when-converged: stopped after '$done_its' of 50, or not as --iterations"; fi

printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >nophase.ply
echo '{"phases": [{"kind": "constant", "value": 0}, {"kind": "constant", "value": 1}]}' >twophases.json
echo '{"domain": {"min": [5,5,5], "max": [6,6,6]}, "phases": [{"name": "outside", "kind": "constant", "value": 0},
  {"name": "sphere1", "kind": "sphere", "center": [5.5,5.5,5.5], "radius": 0.2}, {"name": "sphere2", "kind": "sphere", "center": [5.5,5.5,5.5], "radius": 0.2},
  {"name": "sphere3", "kind": "sphere", "center": [5.5,5.5,5.5], "radius": 0.2}, {"name": "sphere4", "kind": "sphere", "center": [5.5,5.5,5.5], "radius": 0.2}]}' >elsewhere.json
expect_error "mesh without phases" 3 "nophase\.ply: .*phase0" -- "$vm" smooth nophase.ply --field "$examples/four_spheres.json" -o out.ply
expect_error "field with too few phases" 2 "twophases\.json: has 2 phases" -- "$vm" smooth demo.ply --field twophases.json -o out.ply
expect_error "field elsewhere" 2 "elsewhere\.json: its domain" -- "$vm" smooth demo.ply --field elsewhere.json -o out.ply
expect_error "smooth without a field" 2 "needs the phase functions" -- "$vm" smooth demo.ply -o out.ply
expect_error "remesh tolerance without a field" 2 "remesh.tolerance needs the phase functions" -- "$vm" smooth demo.ply --pipeline remesh:tolerance=0.1,flip -o out.ply
expect_error "unknown pass" 2 "unknown pass 'smoth'" -- "$vm" mesh --grid 8 --pipeline smoth,flip -o out.ply
expect_error "unknown parameter" 2 "no parameter 'rest'" -- "$vm" mesh --grid 8 --pipeline smooth:rest=1 -o out.ply
expect_error "parameter out of range" 2 "rest_factor = 9" -- "$vm" mesh --grid 8 --pipeline smooth:rest_factor=9 -o out.ply
expect_error "bad history format" 2 "history" -- "$vm" mesh --grid 8 --history h.txt -o out.ply
expect_error "size with a pipeline" 2 "--size: .*remesh:length=L" -- "$vm" mesh --grid 8 --size 0.1 --pipeline flip -o out.ply
expect_error "negative size" 2 "--size: must be a length above 0" -- "$vm" mesh --grid 8 --size -1 -o out.ply
if out=$("$vm" mesh --grid 16 --iterations 2 --size 0.1 -o sized.ply 2>&1) && grep -q "iterations of remesh:length=0.1,smooth" <<<"$out"; then pass
else fail "--size does not remesh to the length given"; fi
# --tolerance and --min-size are world units; the pass takes them as multiples of the length.
if out=$("$vm" mesh --grid 16 --iterations 2 --max-size 0.1 --tolerance 0.002 --min-size 0.05 -o tol.ply 2>&1) &&
   grep -q "iterations of remesh:length=0.1:tolerance=0.02:min_size=0.5,smooth" <<<"$out"; then pass
else fail "--tolerance/--min-size do not reach the remesh pass: $out"; fi
expect_error "tolerance without size" 2 "--tolerance: needs --size" -- "$vm" mesh --grid 8 --tolerance 0.01 -o out.ply
expect_error "tolerance above size" 2 "--tolerance: must not exceed --size" -- "$vm" mesh --grid 8 --size 0.1 --tolerance 0.2 -o out.ply
expect_error "min size without tolerance" 2 "--min-size: needs --tolerance" -- "$vm" mesh --grid 8 --size 0.1 --min-size 0.05 -o out.ply
expect_error "min size below a tenth" 2 "--min-size: must lie between a tenth of --size and --size" -- "$vm" mesh --grid 8 --size 0.1 --tolerance 0.01 --min-size 0.001 -o out.ply

# Sequences (issue 20): a numbered pattern, one mesh per step and a ParaView collection.
mkdir -p seq seq_out
for i in 0 1 2; do
  printf '{"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": 12, "phases": [{"name": "o", "kind": "constant", "value": 0}, {"name": "s", "kind": "sphere", "center": [0.%d, 0.5, 0.5], "radius": 0.25}]}\n' $((4 + i)) >seq/step_00$i.json
done
if out=$("$vm" mesh 'seq/step_%03d.json' -o 'seq_out/m_%02d.vtu' --iterations 2 2>&1) && grep -q "^step 3 of 3: seq/step_002.json -> seq_out/m_02.vtu" <<<"$out" &&
  [ "$(grep -c '<DataSet timestep="[0-2]" group="" part="0" file="m_0[0-2].vtu"/>' seq_out/m.pvd)" = 3 ] &&
  "$vm" mesh -q seq/step_001.json -o seq_alone.vtu --iterations 2 && cmp -s seq_alone.vtu seq_out/m_01.vtu; then pass
else fail "a numbered sequence is not meshed step by step as lone runs mesh each step, with a .pvd"; fi
expect_error "sequence without a numbered output" 2 "-o: a sequence needs a numbered output" -- "$vm" mesh seq/step_000.json seq/step_001.json -o out.ply
expect_error "pattern without files" 2 "nothing_%03d.json: no file matches this numbered pattern" -- "$vm" mesh 'nothing_%03d.json' -o 'out_%d.ply'
# A field too wide for any file name is no numbered output (it cut every step's name to one file, each
# step writing over the last); a step number beyond a long was an internal error.
expect_error "output field too wide" 2 "-o: a sequence needs a numbered output" -- "$vm" mesh 'seq/step_%03d.json' -o 'o_%9999d.ply'
cp seq/step_000.json seq/step_99999999999999999999.json
expect_error "step number too long" 2 "step_99999999999999999999.json: matches seq/step_%d.json with a step number of 20 digits" -- "$vm" mesh 'seq/step_%d.json' -o 'o_%d.ply'
rm seq/step_99999999999999999999.json
"$vm" mesh -q --grid 8 -o seq/cloud.ply && "$vm" mesh -q --grid 8 -o seq/cloud_1.ply # any PLYs: checked before reading
expect_error "sequence output over a later input" 2 "seq/cloud_1.ply: is also an input of this sequence \\(seq/cloud_1.ply\\)" -- \
  "$vm" mesh seq/cloud_1.ply seq/cloud.ply -o 'seq/cloud_%d.ply'
if out=$("$vm" mesh -q 'seq/step_%03d.json' -o 'seq_out/w_%5d.ply' --iterations 1 2>&1) && [ -f 'seq_out/w_    2.ply' ]; then pass
else fail "a numbered output of width 5 does not pad with spaces as printf does: $out"; fi

# Label volumes (NRRD written here): a 16^3 cube of label 1 inside label 3, and a cube of label 5 beside it.
nrrd_labels() { # FILE [extra header lines]: 16x16x16 uchar
  { printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 16 16 16\n%bencoding: raw\n\n' "${2:-}"
    for k in $(seq 16); do for j in $(seq 16); do
      if [ "$k" -gt 4 ] && [ "$k" -le 12 ] && [ "$j" -gt 4 ] && [ "$j" -le 12 ]; then printf '\3\3\3\3\1\1\1\1\5\5\5\5\3\3\3\3'
      else printf '\3\3\3\3\3\3\3\3\3\3\3\3\3\3\3\3'; fi
    done; done; } >"$1"
}
nrrd_labels labels.nrrd
nrrd_labels oblique.nrrd 'space dimension: 3\nspace directions: (1,0.2,0) (0,1,0) (0,0,1)\n'
if "$vm" create -q labels.nrrd -o l.ply && "$vm" stats l.ply | contains -E "^phases +3" ; then pass; else fail "create on a label volume"; fi
if "$vm" stats l.ply | contains -E "^topology +valid"; then pass; else fail "label volume mesh is not valid"; fi
if "$vm" mesh -q labels.nrrd --iterations 3 -o lm.ply && "$vm" stats lm.ply | contains -E "^topology +valid"; then pass; else fail "mesh on a label volume"; fi
# stats --field on a label volume: where the voxel centres lie in a closed mesh, or why not.
if "$vm" mesh -q labels.nrrd --close --iterations 3 -o lclosed.ply &&
  "$vm" stats lclosed.ply --field labels.nrrd | contains -E "^voxel centres in their label's phase: 9[0-9]\.[0-9]{3}% of 4096 \(interior ones 100\.000%" &&
  "$vm" stats lclosed.ply --field labels.nrrd | contains -E "^  labels with none in their phase: none$" &&
  "$vm" stats lm.ply --field labels.nrrd | contains "voxel centres not located: the mesh is not closed"; then pass
else fail "stats --field on a label volume: voxel centres"; fi
# smooth --field improves a created mesh as mesh does with the same pipeline: the same file,
# byte for byte. Its default is the paper's (a mesh from a file is not coarsened again);
# mesh's default for a label volume remeshes first, to fewer triangles.
paper=smooth,project,clamp,flip
if "$vm" smooth -q l.ply --field labels.nrrd --iterations 2 -o ls.ply && "$vm" mesh -q labels.nrrd --iterations 2 --pipeline $paper -o lm2.ply &&
  cmp -s ls.ply lm2.ply && ! cmp -s ls.ply l.ply; then pass; else fail "smooth --field on a label volume is not mesh's improvement"; fi
if out=$("$vm" mesh labels.nrrd --iterations 2 -o lr.ply 2>&1) && grep -q "iterations of remesh:size=1.4,$paper" <<<"$out" &&
  [ "$("$vm" stats --json lr.ply | python3 -c 'import json,sys; print(json.load(sys.stdin)["triangles"])')" -lt \
    "$("$vm" stats --json lm2.ply | python3 -c 'import json,sys; print(json.load(sys.stdin)["triangles"])')" ]; then pass
else fail "mesh on a label volume does not remesh by default"; fi
# A label volume stops once quality converges, and the mesh is the one --iterations that many makes
# with --all-iterations; the two flags exclude each other.
if out=$("$vm" mesh labels.nrrd --iterations 60 -o lc.ply 2>&1) &&
  done_its=$(sed -n 's/^improve: \([0-9]*\) iterations .*; quality converged.*/\1/p' <<<"$out") && [ -n "$done_its" ] &&
  [ "$done_its" -lt 60 ] && "$vm" mesh -q labels.nrrd --iterations "$done_its" --all-iterations -o lc_n.ply &&
  cmp -s lc.ply lc_n.ply && ! "$vm" mesh -q labels.nrrd --stop-when-converged --all-iterations -o lx.ply 2>/dev/null; then pass
else fail "a label volume's run did not stop when converged ('$done_its' of 60), or not as --iterations"; fi
# A label too small for the grid is named with its size, not dropped in silence (issue 19):
# the default loses the one-voxel label 1 and says --voxel-faithful may keep it, which does.
{ printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n'; printf '\0\0\0\1\2\3\2\3'; } >two.nrrd
if out=$("$vm" mesh two.nrrd -o two.ply 2>&1) && grep -q "^label 1: 1 voxel, no surface in the mesh.*--voxel-faithful" <<<"$out" &&
  out=$("$vm" mesh two.nrrd --voxel-faithful -o two.ply 2>&1) && ! grep -q "no surface in the mesh" <<<"$out"; then pass
else fail "a lost label is not reported, or --voxel-faithful loses it"; fi
# Labels saved as reals (float NIfTI from ITK and deep-learning tools): the same mesh as the
# integers, with a note; a value that is no label (linear interpolation's) is refused by its voxel.
{ printf 'NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\n\n'; echo 0 0 0 1 2 3 2 3; } >two_reals.nrrd
if out=$("$vm" mesh two_reals.nrrd -o two_reals.ply 2>&1) && grep -q "^voxels stored as reals, every one a whole number" <<<"$out" &&
  "$vm" mesh -q two.nrrd -o two_integers.ply && cmp -s two_integers.ply two_reals.ply; then pass; else fail "a label volume saved as reals: $out"; fi
# A volume that says no voxel size has unit voxels, said; --voxel-size gives them theirs.
if out=$("$vm" mesh two.nrrd -o two_unit.ply 2>&1) && grep -q "^the file says no voxel size along some axis" <<<"$out" &&
  out=$("$vm" mesh two.nrrd --voxel-size 2 -o two_sized.ply 2>&1) && grep -q "^voxels of 2 x 2 x 2 (--voxel-size; the file's: none)" <<<"$out" &&
  "$vm" stats --json two_sized.ply | python3 -c 'import json, sys; sys.exit(not json.load(sys.stdin)["max_edge"] > 1.5)'
then pass; else fail "--voxel-size: $out"; fi
# A closed mesh measured against its input read with another voxel size: refused, not measured.
if "$vm" mesh -q two.nrrd --voxel-size 0.5 --close -o two_closed.ply &&
  "$vm" stats two_closed.ply --field two.nrrd --voxel-size 0.5 | contains "voxel centres in their label's phase"; then pass
else fail "stats --field --voxel-size of a closed mesh"; fi
expect_error "stats --field read with another voxel size" 2 "two\.nrrd: its domain .* is not the box of the closed mesh two_closed\.ply, .*--voxel-size" -- "$vm" stats two_closed.ply --field two.nrrd
expect_error "--voxel-size of two sizes" 2 "--voxel-size: one size \(S\) or three \(SX,SY,SZ\), got 2" -- "$vm" mesh two.nrrd --voxel-size 1,2 -o out.ply
sed 's/^0 0 0 1 2 3 2 3$/0 0 0 1 2.5 3 2 3/' two_reals.nrrd >blurred.nrrd
expect_error "labels saved as reals, one not whole" 2 "blurred\.nrrd: .*voxel \(0, 0, 1\) holds 2\.5, not a label" -- "$vm" mesh blurred.nrrd -o out.ply
if "$vm" create -q labels.nrrd --signed-distance --band 2 -o sd.ply && ! cmp -s sd.ply l.ply &&
  "$vm" stats sd.ply | contains -E "^topology +valid"; then pass; else fail "--signed-distance changes nothing"; fi
if "$vm" create -q labels.nrrd --merge-labels 1+5 -o m.ply && "$vm" stats m.ply | contains -E "^phases +2"; then pass; else fail "--merge-labels"; fi
if "$vm" create -q labels.nrrd --drop-labels 5 --background 3 -o d.ply && "$vm" stats d.ply | contains -E "^phases +2"; then pass; else fail "--drop-labels"; fi
if "$vm" create --help | contains "Label volumes"; then pass; else fail "--help lacks the 'Label volumes' group"; fi
# A 3D Slicer segmentation: the same voxels, named segments (liver 1, tumour 5, vessel 3), LPS.
nrrd_labels organ.seg.nrrd 'space: left-posterior-superior\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (0,0,0)\nSegment0_ID:=S1\nSegment0_Name:=liver\nSegment0_LabelValue:=1\nSegment1_ID:=S2\nSegment1_Name:=tumour\nSegment1_LabelValue:=5\nSegment2_ID:=S3\nSegment2_Name:=vessel\nSegment2_LabelValue:=3\n'
if out=$("$vm" create organ.seg.nrrd --background 3 -o seg.msh 2>&1) && grep -q '"1-liver_5-tumour"' seg.msh &&
  grep -q "world LPS (the file's)" <<<"$out"; then pass; else fail "segment names do not name the MSH physical groups"; fi
if "$vm" create -q organ.seg.nrrd --background 3 --keep-labels tumour -o keep.ply && "$vm" stats keep.ply | contains -E "^phases +2" &&
  grep -aq "comment phase 5 tumour" keep.ply; then pass; else fail "--keep-labels by segment name"; fi
if "$vm" create -q organ.seg.nrrd --background 3 --drop-labels tumour -o drop.ply && "$vm" stats drop.ply | contains -E "^phases +2" &&
  grep -aq "comment phase 1 liver" drop.ply; then pass; else fail "--drop-labels by segment name"; fi
expect_error "unknown segment name" 2 "organ.seg.nrrd: --drop-labels: no segment is named 'kidney' \(its segments: 'liver', 'tumour', 'vessel'\)" -- \
  "$vm" create organ.seg.nrrd --drop-labels kidney -o out.ply
expect_error "segment names in a plain volume" 2 "labels.nrrd: --keep-labels: no segment is named 'liver' \(this volume names none" -- \
  "$vm" create labels.nrrd --keep-labels liver -o out.ply
# --world: the LPS file meshed in RAS is its mirror image in x and y.
bounds() { grep -a -m1 "^comment domain" "$1" | cut -d' ' -f3-; }
if out=$("$vm" create organ.seg.nrrd --world ras -o ras.ply 2>&1) && grep -q "world RAS (converted from the file's LPS)" <<<"$out" &&
  [ "$(bounds ras.ply)" = "-15 -15 0 1 1 16" ]; then pass; else fail "--world ras does not mirror an LPS file: $(bounds ras.ply)"; fi
expect_error "--world without a frame" 2 "labels.nrrd: --world lps: the file does not say" -- "$vm" create labels.nrrd --world lps -o out.ply
expect_error "--world on a scene" 2 "--world applies only to volumes" -- "$vm" create --world ras -o out.ply
printf '# x y z label\n0 0 0 1\n0 1 0 1\n1 0 0 2\n1 1 1 2\n0.5 0.5 1 3\n' >cloud.xyz
if "$vm" create -q cloud.xyz -o c.ply && "$vm" stats c.ply | contains -E "^phases +3"; then pass; else fail "create on a point cloud"; fi
printf '0 0 0 1\n1 1 one 2\n' >badcloud.xyz
: >later.nii.gz
expect_error "oblique direction" 2 "oblique.*--ignore-direction" -- "$vm" create oblique.nrrd -o out.ply
# Voxels too far from the origin for doubles to tell their centres apart (1 mm at 1e20
# once crashed in create); a non-finite origin (DREAM.3D's is not checked on reading).
nrrd_labels far.nrrd 'space dimension: 3\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (1e20,0,0)\n'
expect_error "voxels at 1e20" 2 "far\.nrrd: cells of 0 along x at coordinates up to 1e\+20 are finer than doubles resolve there" -- \
  "$vm" create far.nrrd -o out.ply
nrrd_labels beyond.nrrd 'space dimension: 3\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (0,1e300,0)\n'
expect_error "voxels at 1e300" 2 "beyond\.nrrd: the domain reaches 1e\+300 along y; it must lie within" -- \
  "$vm" create beyond.nrrd -o out.ply
expect_error "drop to one phase" 2 "1 phase\(s\) after the label options" -- "$vm" create labels.nrrd --drop-labels 1,5 --background 3 -o out.ply
expect_error "absent label" 2 "label 7 is not in the volume" -- "$vm" create labels.nrrd --drop-labels 7 -o out.ply
expect_error "bad merge group" 2 "merge-labels: expected groups" -- "$vm" create labels.nrrd --merge-labels 1++5 -o out.ply
expect_error "bad point line" 2 "badcloud\.xyz: line 2" -- "$vm" create badcloud.xyz -o out.ply
printf '0 0 0 1\n1 1 1 1\n0 1 0 1\n1 1 1 2\n' >twolabels.xyz # label 2's one point is also label 1's: it meshed to nothing
expect_error "point with two labels" 2 "twolabels\.xyz: points 2 and 4 lie at the same place \(1, 1, 1\) with different labels \(1 and 2\)" -- "$vm" create twolabels.xyz -o out.ply
# Point clouds as PLY (any vertex element with x, y, z and label), and bad point input.
# The four-region mesh must come out free of self-intersections (stats exits 4 otherwise):
# its interfaces are jagged, and without the crossing guard surfaces fold onto themselves.
{ printf 'ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nproperty int label\nend_header\n'
  grep -v '^#' cloud.xyz; } >cloud.ply
if "$vm" create -q cloud.ply -o cp.ply && "$vm" stats cp.ply | contains -E "^phases +3" && cmp -s c.ply cp.ply; then pass; else fail "create on a PLY point cloud (same mesh as its .xyz)"; fi
if "$vm" smooth -q cp.ply --field cloud.ply --iterations 2 -o cps.ply &&
  "$vm" mesh -q cloud.ply --iterations 2 --pipeline smooth,project,clamp,flip -o cpm.ply &&
  cmp -s cps.ply cpm.ply && ! cmp -s cps.ply cp.ply; then pass; else fail "smooth --field on a PLY point cloud is not mesh's improvement"; fi
if python3 "$examples/../scripts/make_point_cloud.py" --count 2000 four.ply 2>/dev/null \
  && "$vm" mesh -q four.ply --grid 32 --iterations 20 -o four_mesh.ply && "$vm" stats four_mesh.ply >four.txt \
  && grep -qE "^phases +4" four.txt && grep -qE "^quadruple points +[1-9]" four.txt; then pass; else fail "four-region point cloud: $(cat four.txt)"; fi
printf 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 1 1\n' >nolabel.ply
: >empty.xyz
printf '0 0 0 1\n1 1 1 1\n' >onelabel.xyz
printf '0 0 0 1\n1 1 1 99999999999\n' >biglabel.xyz
printf '0 0 0 1\n1 nan 1 2\n' >nan.xyz
sed 's/^1 1 1 2$/1 inf 1 2/' cloud.ply >inf.ply
awk 'BEGIN { for (i = 0; i <= 32767; ++i) print i, 0, 0, i }' >manylabels.xyz
expect_error "PLY cloud without labels" 2 "nolabel\.ply: no vertex property 'label' \(a labelled point cloud needs one\)" -- "$vm" create nolabel.ply -o out.ply
expect_error "empty point file" 2 "empty\.xyz: has no points" -- "$vm" create empty.xyz -o out.ply
expect_error "point file with one label" 2 "onelabel\.xyz: has 1 label\(s\); a labelled point cloud needs 2 or more" -- "$vm" create onelabel.xyz -o out.ply
expect_error "label beyond int32" 2 "biglabel\.xyz: line 2: label 99999999999 is not a 32-bit integer" -- "$vm" create biglabel.xyz -o out.ply
expect_error "too many labels" 2 "manylabels\.xyz: has 32768 distinct labels; at most 32767" -- "$vm" create manylabels.xyz -o out.ply
expect_error "nan coordinate" 2 "nan\.xyz: line 2: coordinates must be finite" -- "$vm" create nan.xyz -o out.ply
expect_error "inf coordinate in PLY" 2 "inf\.ply: vertex 3: coordinates must be finite" -- "$vm" mesh inf.ply -o out.ply
expect_error "empty NIfTI" 2 "later\.nii\.gz: not a NIfTI file" -- "$vm" create later.nii.gz -o out.ply
{ printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 10 10 10\nencoding: raw\n\n'; head -c 500 /dev/zero; } >truncated.nrrd
{ printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n'; head -c 64 /dev/zero; } >single.nrrd
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n\n' >huge.nrrd
printf 'NRRD0004\ntype: float\ndimension: 4\nsizes: 2 2 2 2\nkinds: vector domain domain domain\nencoding: ascii\n\n0 0 0 0 0 nan 0 0 0 0 0 0 0 0 0 0\n' >nan.nrrd
sed 's/nan/inf/' nan.nrrd >inf.nrrd
expect_error "truncated volume" 2 "truncated\.nrrd: truncated: .*1000 samples of raw data" -- "$vm" create truncated.nrrd -o out.ply
expect_error "volume with one label" 2 "single\.nrrd: has 1 phase\(s\)" -- "$vm" create single.nrrd -o out.ply
expect_error "volume beyond memory" 2 "huge\.nrrd: reading 1e\+15 samples needs about .* GiB, this machine has" -- "$vm" create huge.nrrd -o out.ply
expect_error "NaN in a distance grid" 2 "nan\.nrrd: value nan at sample 5" -- "$vm" create nan.nrrd -o out.ply
expect_error "inf in a distance grid" 2 "inf\.nrrd: value inf at sample 5" -- "$vm" create inf.nrrd -o out.ply
expect_error "unknown input" 2 "unknown input type" -- "$vm" create labels.vtk -o out.ply
# Detached and compressed NRRD data: a header of a hundred bytes must not make Teem allocate what its data
# files cannot hold (here 134 MB from 64 bytes of slices, and from 1 MB of zeros in 45 bytes of bzip2), nor
# hand Teem a data file pattern its sprintf cannot expand safely.
mkdir -p slices && for k in 0 1 2 3; do head -c 16 /dev/zero >"slices/s00$k.raw"; done
nhdr() { printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: %s\nencoding: raw\ndata file: %s\n' "$1" "$2"; }
nhdr "512 512 512" "s%03d.raw 0 3 1 3" >slices/big.nhdr
nhdr "2 2 2" "s%d%n.raw 0 1 1" >slices/unsafe.nhdr
nhdr "2 2 2" "LIST" >slices/gone.nhdr && printf 's000.raw\ngone.raw\n' >>slices/gone.nhdr
nhdr "2 2 2" "-" >stdin.nhdr
{ printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 512 512 512\nencoding: bzip2\n\n'
  head -c 1048576 /dev/zero | python3 -c 'import bz2, sys; sys.stdout.buffer.write(bz2.compress(sys.stdin.buffer.read()))'; } >zeros.nrrd
expect_error "NRRD data files shorter than its sizes" 2 "slices/big\.nhdr: truncated: the header describes 134217728 samples of raw data, .*its 4 data files \(.*slices/s000\.raw \.\.\. .*slices/s003\.raw\) hold 64" -- "$vm" create slices/big.nhdr -o out.ply
expect_error "bzip2 NRRD data short of its sizes" 2 "zeros\.nrrd: truncated: .*134217728 bytes\) of bzip2 data; its file inflates to 1048576 of the 134217728 bytes" -- "$vm" create zeros.nrrd -o out.ply
expect_error "unsafe NRRD data file pattern" 2 "slices/unsafe\.nhdr: data file pattern 's%d%n\.raw' must hold one %d" -- "$vm" create slices/unsafe.nhdr -o out.ply
expect_error "missing NRRD data file" 3 "slices/gone\.nhdr: cannot open its data file .*slices/gone\.raw" -- "$vm" create slices/gone.nhdr -o out.ply
expect_error "NRRD data from standard input" 2 "stdin\.nhdr: data file '-' \(standard input\) is not read" -- "$vm" create stdin.nhdr -o out.ply </dev/null

# Scene "grid" phases: one ASCII float NRRD per phase (two spheres on 16^3 voxels), beside the scene in a
# folder of their own, mesh exactly as the same values in one 3-component file.
nrrd_distance() { # FILE COMPONENTS [SLICES]: components (0 outside, 1 and 2 spheres) per voxel of 16x16xSLICES
  local count=$(( $(tr -cd , <<<"$2" | wc -c) + 1 )) slices=${3:-16} sizes
  sizes="16 16 $slices" && [ "$count" -gt 1 ] && sizes="$count $sizes"
  { printf 'NRRD0004\ntype: float\ndimension: %s\nsizes: %s\nencoding: ascii\n\n' "$(wc -w <<<"$sizes")" "$sizes"
    awk -v comps="$2" -v slices="$slices" 'BEGIN { n = split(comps, c, ",")
      for (k = 0; k < slices; k++) for (j = 0; j < 16; j++) for (i = 0; i < 16; i++) {
        line = ""
        for (m = 1; m <= n; m++) {
          if (c[m] == 0) v = 0
          else if (c[m] == 1) v = 5 - sqrt((i - 6.2) ^ 2 + (j - 7.4) ^ 2 + (k - 7.7) ^ 2)
          else v = 4.5 - sqrt((i - 10.1) ^ 2 + (j - 8.3) ^ 2 + (k - 7.1) ^ 2)
          line = line (m > 1 ? " " : "") v
        }
        print line
      } }'; } >"$1"
}
mkdir -p grids
nrrd_distance grids/p0.nrrd 0 && nrrd_distance grids/p1.nrrd 1 && nrrd_distance grids/p2.nrrd 2
nrrd_distance all.nrrd 0,1,2
nrrd_distance grids/short.nrrd 1 8
printf '{"phases": [{"kind": "grid", "file": "p0.nrrd"}, {"kind": "grid", "file": "p1.nrrd"}, {"kind": "grid", "file": "p2.nrrd"}]}\n' >grids/scene.json
printf '{"phases": [{"kind": "grid", "file": "p0.nrrd"}, {"kind": "grid", "file": "p1.nrrd", "component": 2}]}\n' >grids/component.json
printf '{"phases": [{"kind": "grid", "file": "p0.nrrd"}, {"kind": "grid", "file": "gone.nrrd"}]}\n' >grids/missing.json
printf '{"phases": [{"kind": "grid", "file": "p0.nrrd"}, {"kind": "grid", "file": "short.nrrd"}]}\n' >grids/other.json
printf '{"domain": {"min": [0, 0, 0], "max": [20, 1, 1]}, "phases": [{"kind": "grid", "file": "p0.nrrd"}, {"kind": "sphere", "center": [5, 5, 5], "radius": 2}]}\n' >grids/domain.json
# Command-line mistakes: one line naming the option, exit 2.
expect_error "unknown option" 2 "The following argument was not expected: --bogus \(see --help\)" -- "$vm" mesh --bogus -o out.ply
expect_error "option without its value" 2 "--grid.*\(see --help\)" -- "$vm" mesh -o out.ply --grid
expect_error "option value not a number" 2 "--snap.*abc.*\(see --help\)" -- "$vm" mesh --snap abc -o out.ply
expect_error "output option missing" 2 "--output is required \(see --help\)" -- "$vm" mesh
# A misspelt option is named even where a required one is missing too (CLI11 would name only the latter).
expect_error "unknown option, output missing" 2 "The following argument was not expected: --bogus \(see --help\)" -- "$vm" mesh --bogus
expect_error "unknown option, mesh missing" 2 "The following argument was not expected: --bogus \(see --help\)" -- "$vm" smooth --bogus
expect_error "no subcommand" 2 "subcommand.*\(see --help\)" -- "$vm"
# Options for volumes are refused where they would be ignored, naming the input and the option.
expect_error "volume option on a scene" 2 "grids/scene\.json: --voxels-per-cell applies only to volumes, and this is a scene" -- "$vm" create grids/scene.json --voxels-per-cell 2 -o out.ply
expect_error "label option on a distance grid" 2 "all\.nrrd: --smoothing applies only to label volumes, and this is a distance grid" -- "$vm" create all.nrrd --smoothing 2 -o out.ply
expect_error "label options on the demo" 2 "the built-in demo: --drop-labels, --signed-distance apply only to label volumes" -- "$vm" mesh --drop-labels 3 --signed-distance -o out.ply
expect_error "volume option on a point cloud" 2 "cloud\.xyz: --ignore-direction applies only to volumes, and this is a point cloud" -- "$vm" create cloud.xyz --ignore-direction -o out.ply
if "$vm" create -q grids/scene.json -o gs.ply && "$vm" create -q all.nrrd -o ga.ply && cmp -s gs.ply ga.ply; then pass
else fail "grid phases do not mesh as the multi-component file"; fi
if "$vm" stats gs.ply | contains -E "^phases +3" && "$vm" stats gs.ply | contains -E "^topology +valid"; then pass; else fail "grid phase mesh is not valid"; fi
if "$vm" mesh -q grids/scene.json --iterations 3 -o gm.ply && "$vm" stats gm.ply >/dev/null; then pass; else fail "mesh on grid phases"; fi
expect_error "grid file missing" 3 "grids/missing\.json: phase 1: .*gone\.nrrd: cannot open" -- "$vm" create grids/missing.json -o out.ply
expect_error "grid component" 2 "grids/component\.json: phase 1: 'component' 2 is out of range" -- "$vm" create grids/component.json -o out.ply
expect_error "grids differ" 2 "grids/other\.json: phase 1: 'short\.nrrd' is not on the grid of 'p0\.nrrd' \(phase 0\): sizes 16x16x8 vs 16x16x16" -- "$vm" create grids/other.json -o out.ply
expect_error "domain beyond grids" 2 "grids/domain\.json: domain: reaches beyond the voxels of the grid phases along x" -- "$vm" create grids/domain.json -o out.ply

# Output formats: every extension, chosen by the file name, checked before any work.
for ext in ply obj msh vtu vtp mesh; do
  if "$vm" create -q --grid 12 -o "fmt.$ext" && [ -s "fmt.$ext" ]; then pass; else fail "create -o fmt.$ext"; fi
done
if "$vm" create -q --grid 12 -o surf.stl --per-phase phases && [ ! -e surf.stl ] && [ "$(ls surf_*.stl | wc -l)" -eq 10 ] &&
  [ -s surf_0-outside_1-sphere1.stl ] && [ "$(ls phases/phase_*.stl | wc -l)" -eq 5 ]; then pass
else fail "-o surf.stl: one file per phase pair, --per-phase: one per phase"; fi
if "$vm" create --grid 12 -o surf2.stl 2>&1 | contains "10 STL files, one per phase pair"; then pass; else fail "STL files reported"; fi
# Files of an earlier run's other pairs or phases are named, not silently left to mix with this run's.
if "$vm" create --grid 12 -o surf2.stl 2>&1 | contains "note:"; then fail "the same pairs again: a note on other files"
else pass; fi
if "$vm" create grids/scene.json -o surf.stl --per-phase phases 2>&1 >/dev/null |
  contains -E "^note: 10 other surf_\*\.stl files in this folder \(such as surf_0-outside_1-sphere1\.stl\) are not from this run"
then pass; else fail "an earlier run's STL files beside this run's are not named"; fi
if "$vm" create grids/scene.json -o surf.stl --per-phase phases 2>&1 | contains -E "^note: 5 other phase_\*\.stl files in phases"
then pass; else fail "an earlier run's per-phase STL files are not named"; fi
if "$vm" create --help | contains "\.vtp" && "$vm" create --help | contains "per-phase"; then pass; else fail "--help lists the formats"; fi
if "$vm" flip -q demo.ply -o fl.msh && grep -q '^\$PhysicalNames' fl.msh; then pass; else fail "flip -o .msh"; fi
# A mesh written in another format given back to stats or smooth: read from PLY only, and said so.
expect_error "stats of a .msh" 3 "fl\.msh: a \.msh file, not a PLY: voronoimesh reads meshes back from PLY only \(mesh with -o NAME\.ply" -- "$vm" stats fl.msh
: >blocker
expect_error "unknown extension" 2 "out\.xyz: unknown output format '\.xyz' \(known: \.ply, \.obj, \.stl, \.msh, \.vtu, \.vtp, \.mesh\)" \
  -- "$vm" create --grid 4096 -o out.xyz
expect_error "no extension" 2 "out: no extension" -- "$vm" mesh --grid 4096 -o out
expect_error "--per-phase in a missing directory" 3 "/nonexistent/dir: cannot write" \
  -- "$vm" mesh --grid 4096 -o out.ply --per-phase /nonexistent/dir
expect_error "--per-phase on a file" 3 "blocker: not a directory" -- "$vm" create --grid 4096 -o out.ply --per-phase blocker
expect_error "smooth to an unknown format" 2 "out\.off: unknown output format" -- "$vm" smooth demo.ply -o out.off

# Ctrl-C: the run stops at the next iteration, says so on one line, exits 130 and
# writes nothing (no output, no temporary file). A long run, interrupted after 2 s.
rm -f out.ply
"$vm" mesh --grid 64 --iterations 100000 -o out.ply >stdout.txt 2>stderr.txt &
pid=$!
sleep 2
kill -INT "$pid"
wait "$pid"
got=$?
if [ "$got" -ne 130 ]; then fail "Ctrl-C: exit $got, expected 130 ($(tail -1 stderr.txt))"
elif ! tail -1 stderr.txt | contains "voronoimesh: interrupted; nothing was written"; then fail "Ctrl-C: $(tail -1 stderr.txt)"
elif [ -e out.ply ] || ls out.ply.tmp-* >/dev/null 2>&1; then fail "Ctrl-C: left an output file behind"
else pass; fi

# kill -9 at any moment leaves out.ply as it was (absent or a complete mesh), never a
# partial file; the next run that writes out.ply removes the killed runs' temporaries.
rm -f out.ply out.ply.tmp-*
for delay in 0.05 0.1 0.15 0.2 0.25; do
  "$vm" mesh --grid 40 --iterations 4 -q -o out.ply &
  pid=$!
  sleep "$delay"
  kill -KILL "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  if [ -e out.ply ] && ! "$vm" stats out.ply >/dev/null 2>&1; then fail "kill -9 after ${delay}s: out.ply is not a complete mesh"; fi
done
if "$vm" mesh --grid 8 --iterations 0 -q -o out.ply && "$vm" stats out.ply >/dev/null && ! ls out.ply.tmp-* >/dev/null 2>&1
then pass; else fail "kill -9: temporaries left after the next run"; fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
