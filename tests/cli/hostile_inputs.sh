#!/usr/bin/env bash
# The command-line tool against what a hostile or careless user gives it (issue
# 16's adversarial review): every case failed before its fix. Deep JSON, labels of
# any sign, outputs that are inputs, planted links, devices as inputs, outputs
# left behind, absurd headers, non-finite gradients, fields of other scenes, and
# the minor ones. Usage: hostile_inputs.sh VORONOIMESH EXAMPLES_DIR WORK_DIR
set -uo pipefail
vm=$1 examples=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
source "$here/expect.sh"

# nrrd_labels FILE TYPE SIZE VALUE_OF_VOXEL...: an ASCII NRRD of SIZE^3 labels,
# the voxels of the inner box [1, SIZE-2]^3 labelled INNER, the rest OUTER.
nrrd_labels() {
  local file=$1 type=$2 size=$3 outer=$4 inner=$5
  { printf 'NRRD0004\ntype: %s\ndimension: 3\nsizes: %d %d %d\nencoding: ascii\n\n' "$type" "$size" "$size" "$size"
    awk -v n="$size" -v o="$outer" -v i="$inner" 'BEGIN { for (z = 0; z < n; z++) for (y = 0; y < n; y++)
      for (x = 0; x < n; x++) print (x > 0 && y > 0 && z > 0 && x < n - 1 && y < n - 1 && z < n - 1) ? i : o }'
  } >"$file"
}

# 1. Deeply nested JSON is refused in one line, wherever the nesting is.
deep() { python3 -c "print('['*$1 + ']'*$1)"; }
echo "{\"description\": $(deep 50000), \"phases\": []}" >deep.json
expect_error "JSON nested 50,000 deep" 2 "deep\.json: JSON nested deeper than 64 levels" -- "$vm" create deep.json -o out.ply
echo "{\"phases\": [{\"kind\": \"constant\", \"value\": $(deep 50000)}, {\"kind\": \"constant\", \"value\": 1}]}" >deepvalue.json
expect_error "JSON nested deep in a value" 2 "deepvalue\.json: JSON nested deeper than 64 levels" -- "$vm" create deepvalue.json -o out.ply
echo "{\"phases\": [{\"kind\": \"constant\", \"value\": 0, \"name\": $(deep 50)}, {\"kind\": \"constant\", \"value\": 1}]}" >deepname.json
expect_error "a name that is an array" 2 "deepname\.json: phase 0: 'name' must be a string, got an array of 1 item" -- "$vm" create deepname.json -o out.ply
echo '{"phases": [{"kind": "constant", "value": 0, "value": 1}, {"kind": "constant", "value": 1}]}' >dupkey.json
expect_error "a key given twice" 2 "dupkey\.json: key 'value' appears twice in one object" -- "$vm" create dupkey.json -o out.ply

# 2. Every integer label is a label: negative ones too, and the extremes of 32 bits.
nrrd_labels negative.nrrd short 8 0 -3
if "$vm" mesh -q negative.nrrd --iterations 2 -o negative.ply && grep -q "^comment phase -3 label-3" negative.ply &&
  "$vm" stats negative.ply | contains -E "^phases +2"; then pass; else fail "a label of -3 is lost"; fi
nrrd_labels signs.nrrd short 8 -5 5
if "$vm" create -q signs.nrrd -o signs.ply && grep -q "^comment phase -5 " signs.ply && grep -q "^comment phase 5 " signs.ply
then pass; else fail "labels -5 and 5"; fi
nrrd_labels extremes.nrrd int 8 -2147483648 2147483647
if "$vm" create -q extremes.nrrd -o extremes.ply && grep -q "^comment phase -2147483648 " extremes.ply &&
  grep -q "^comment phase 2147483647 " extremes.ply; then pass; else fail "labels INT32_MIN and INT32_MAX"; fi
# Closed, the exterior takes the label above the largest, which 2147483647 leaves none of.
expect_error "--close with label 2147483647" 2 "^voronoimesh: --close: .*'label2147483647' has label 2147483647, the largest" -- \
  "$vm" create -q extremes.nrrd --close -o out.ply

# 3. No output is an input of the same run, by file identity; the input is untouched.
cp "$examples/four_spheres.json" scene.json && cp scene.json scene.orig
expect_error "--history onto the scene" 2 "scene\.json: is also an input of this run" -- \
  "$vm" mesh scene.json --grid 12 --history scene.json -o out.ply
ln -sf scene.json link.json
expect_error "--history onto a link to the scene" 2 "link\.json: is also an input of this run" -- \
  "$vm" mesh scene.json --grid 12 --history link.json -o out.ply
if cmp -s scene.json scene.orig; then pass; else fail "the scene was overwritten"; fi
python3 "$here/../../scripts/make_point_cloud.py" --count 500 cloud.ply >/dev/null && cp cloud.ply cloud.orig
expect_error "-o onto the point cloud" 2 "cloud\.ply: is also an input of this run" -- "$vm" create cloud.ply --grid 8 -o cloud.ply
if cmp -s cloud.ply cloud.orig; then pass; else fail "the point cloud was overwritten"; fi
"$vm" create -q --grid 12 -o m.ply && cp m.ply m.orig
expect_error "smooth onto its own mesh" 2 "m\.ply: is also an input of this run" -- \
  "$vm" smooth m.ply --field scene.json --iterations 1 -o m.ply
if cmp -s m.ply m.orig; then pass; else fail "smooth overwrote its mesh"; fi

# 4. Temporaries never follow a planted link, and a rewrite keeps the output's permissions.
echo "keep me" >victim.txt
(ln -s victim.txt "o.ply.tmp-$BASHPID-0" && ln -s victim.txt "o.ply.tmp-$BASHPID" &&
  exec "$vm" create -q --grid 8 -o o.ply)
if [ "$(cat victim.txt)" = "keep me" ] && [ -f o.ply ] && [ ! -L o.ply ] && "$vm" stats o.ply >/dev/null; then pass
else fail "a planted link at the temporary's name: victim '$(cat victim.txt)', o.ply $(ls -l o.ply)"; fi
chmod 600 o.ply && "$vm" create -q --grid 8 -o o.ply
if [ "$(stat -c %a o.ply)" = 600 ]; then pass; else fail "a rewrite made a 0600 output $(stat -c %a o.ply)"; fi

# 5. Devices and other non-files as inputs: refused at once, in one line.
for name in zero.json zero.xyz zero.ply zero.mha zero.nrrd zero.nii; do
  ln -sf /dev/zero "$name"
  expect_error "$name -> /dev/zero" 3 "$name: cannot read: it is a character device, not a regular file" -- \
    timeout 20 "$vm" create "$name" -o out.ply
done
"$vm" create -q --grid 8 -o devmesh.ply
ln -sf /dev/zero zero_mesh.ply
expect_error "smooth a mesh that is /dev/zero" 3 "zero_mesh\.ply: cannot read: it is a character device" -- \
  timeout 20 "$vm" smooth zero_mesh.ply --field scene.json -o out.ply
printf 'NRRD0004\ntype: short\ndimension: 3\nsizes: 4 4 4\nencoding: raw\ndata file: /dev/zero\n' >devdata.nhdr
expect_error "NRRD data file /dev/zero" 3 "devdata\.nhdr: its data file /dev/zero is not a regular file" -- \
  timeout 20 "$vm" create devdata.nhdr -o out.ply

# 6. A run's outputs appear all or none: a write that fails (here a file-size
# limit) leaves no file of the run, not even the ones written before it.
rm -rf limited && mkdir limited
(ulimit -f 40 && exec "$vm" create -q --grid 24 --ascii -o limited/out.stl --per-phase limited/pp) 2>limit.txt
got=$?
if [ "$got" -eq 3 ] && grep -q "File too large" limit.txt && [ -z "$(find limited -type f)" ]; then pass
else fail "a failing write: exit $got, $(cat limit.txt), left $(find limited -type f | head -3)"; fi

# 8. A gzip NRRD whose header claims far more than its data: memory touched grows
# with what inflates, not with the claim (2 GiB claimed, run within 600 MB).
{ printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2048 1024 1024\nencoding: gzip\n\n'; head -c 2200000 /dev/urandom; } >claims.nrrd
# AddressSanitizer and ThreadSanitizer reserve terabytes of address space for
# their shadow, so an instrumented build (scripts/test_sanitizers.sh) runs
# without the limit.
limit=600000
if [ "$(ldd "$vm" 2>/dev/null | grep -cE 'lib(asan|tsan)' || true)" != 0 ]; then limit=unlimited; fi
expect_error "gzip NRRD claiming 2 GiB" 2 "claims\.nrrd: its file is not valid gzip data" -- \
  bash -c 'ulimit -v "$1" && exec "$0" create claims.nrrd -o out.ply' "$vm" "$limit"

# 9. A gradient that is not finite stops the run, naming the phase and the point.
cat >badgrad.json <<'EOF'
{"grid": 12, "phases": [{"name": "outside", "kind": "constant", "value": 0},
  {"name": "ball", "kind": "expr", "expr": "0.3 - sqrt((x-0.5)^2 + (y-0.5)^2 + (z-0.5)^2)", "gradient": ["0/0", "0", "0"]}]}
EOF
expect_error "gradient 0/0" 2 "badgrad\.json: phase ball: its gradient at \(.*\) is \(-?nan, 0, 0\), not finite" -- \
  "$vm" mesh -q badgrad.json --iterations 2 -o out.ply

# 10. smooth --field of another scene with as many phases and the same box.
sed 's/"sphere1"/"ball1"/' "$examples/four_spheres.json" >other.json
expect_error "--field of another scene" 2 "other\.json: its phase 1 is 'ball1', but m\.ply calls phase 1 'sphere1'" -- \
  "$vm" smooth m.ply --field other.json -o out.ply

# 12. Beyond a file-size limit the run says so, exit 3, and leaves no temporary.
(ulimit -f 20 && exec "$vm" mesh -q --grid 16 --iterations 1 --ascii -o big.ply) 2>xfsz.txt
got=$?
if [ "$got" -eq 3 ] && grep -q "big.ply: cannot write (File too large)" xfsz.txt && ! ls big.ply* >/dev/null 2>&1; then pass
else fail "SIGXFSZ: exit $got, $(cat xfsz.txt)"; fi

# 12b. TIFF stacks: a header that claims 2 x 100,000 x 100,000 pixels in 200 bytes (refused
# before anything is allocated), a text file named .tif, a stack cut in its last page directory.
python3 - <<'PY'
import struct
def ifd(next_offset):
    entries = [(256, 4, 1, 100000), (257, 4, 1, 100000), (258, 3, 1, 8), (259, 3, 1, 1), (262, 3, 1, 1),
               (273, 4, 1, 0), (277, 3, 1, 1), (278, 4, 1, 100000), (279, 4, 1, 1410065408)]
    return struct.pack("<H", len(entries)) + b"".join(struct.pack("<HHII", *e) for e in entries) + \
        struct.pack("<I", next_offset)
first = ifd(0)
with open("huge.tif", "wb") as f:
    f.write(b"II*\x00" + struct.pack("<I", 8) + ifd(8 + len(first)) + ifd(0))
with open("cut.tif", "wb") as f:
    f.write(b"II*\x00" + struct.pack("<I", 8) + ifd(8 + len(first))[:-2])
PY
expect_error "a TIFF claiming 2e10 voxels" 2 "huge\.tif: reading 20000000000 voxels needs about .* GiB, this machine has" -- \
  "$vm" mesh huge.tif -o out.ply
echo "not an image" >text.tif
expect_error "a text file named .tif" 2 "text\.tif: not a TIFF file" -- "$vm" mesh text.tif -o out.ply
expect_error "a TIFF cut in a page directory" 2 "cut\.tif: " -- "$vm" mesh cut.tif -o out.ply

# 13. The minor ones.
expect_error "--snap checked before reading" 2 "^voronoimesh: --snap: must be between 0 and 0\.5" -- \
  "$vm" create nonexistent.json --snap 2 -o out.ply
python3 -c "print('{\"phases\": [{\"kind\": \"constant\", \"value\": 0}, {\"kind\": \"expr\", \"expr\": \"' + 'x+'*200000 + '\"}]}')" >longexpr.json
expect_error "a 400 KB expression" 2 "longexpr\.json: phase 1: bad expr 'x\+x\+" -- "$vm" create longexpr.json -o out.ply
if [ "$(wc -c <stderr.txt)" -lt 400 ]; then pass; else fail "the long expression is quoted whole: $(wc -c <stderr.txt) bytes"; fi
echo '{"grid": 4, "phases": [{"kind": "constant", "value": 0}, {"name": "bad", "kind": "expr", "expr": "0/0"}]}' >nan.json
expect_error "NaN in a scene names the file" 2 "nan\.json: phase bad: value is NaN at" -- "$vm" create -q nan.json -o out.ply
echo '{"domain": {"min": [-1e308, 0, 0], "max": [1e308, 1, 1]}, "phases": [{"kind": "constant", "value": 0}, {"kind": "sphere", "center": [0, 0.5, 0.5], "radius": 0.3}]}' >huge.json
expect_error "a domain of 1e308" 2 "huge\.json: domain: must lie within -1e\+30 and 1e\+30" -- "$vm" create huge.json -o out.ply
expect_error "a pipeline parameter twice" 2 "gives smooth\.rest_factor twice" -- \
  "$vm" mesh --grid 8 --pipeline smooth:rest_factor=1:rest_factor=2,flip -o out.ply
expect_error "--band without --signed-distance" 2 "--band: applies to signed distances" -- \
  "$vm" create negative.nrrd --band 5 -o out.ply
expect_error "--smoothing with --signed-distance" 2 "--smoothing: applies to the smoothed indicator" -- \
  "$vm" create negative.nrrd --signed-distance --smoothing 2 -o out.ply
"$vm" create -q --grid 8 --ascii -o ascii.ply
for scale in 1e160 1e40 1e-40 1e-160; do # 1e40, 1e-40: beyond the crossing index's floats
  awk -v s="$scale" 'header { print; if ($0 == "end_header") header = 0; next }
    NF == 3 { printf "%.17g %.17g %.17g\n", $1 * s, $2 * s, $3 * s; next } { print }' header=1 ascii.ply >scaled.ply
  expect_error "a mesh scaled by $scale" 2 "scaled\.ply: not a valid interface mesh .*scale: the mesh spans" -- \
    "$vm" smooth scaled.ply --pipeline flip -o out.ply
done
# 14. A target edge length far below the mesh's (a typo in --size) is refused with the
# estimate before any split (it once took all 24 GB and the OOM killer ended it).
expect_error "--size 1e-9" 2 "^voronoimesh: remesh: edges of .* make about .* triangles from its [0-9]+, which needs about .* GiB, this machine has" -- \
  bash -c 'ulimit -v "$1" && exec "$0" mesh -q --grid 12 --size 1e-9 -o out.ply' "$vm" "$limit"

# 15. A mesh whose triangles cross (its first node dragged through the
# surfaces to the box's centre) is refused where the crossing guard would only
# keep it crossing; without the guard it is improved as asked.
awk 'header { print; if ($0 == "end_header") header = 0; next }
  NF == 3 && !dragged { print "0.5 0.5 0.5"; dragged = 1; next } { print }' header=1 ascii.ply >dragged.ply
crossing="dragged\.ply: [0-9]+ pairs of triangles cross \(the first: triangles [0-9]+ and [0-9]+\): improvement keeps"
expect_error "flip on a mesh whose triangles cross" 2 "$crossing" -- "$vm" flip dragged.ply -o out.ply
expect_error "smooth on a mesh whose triangles cross" 2 "$crossing" -- "$vm" smooth dragged.ply --pipeline flip -o out.ply
if "$vm" smooth -q dragged.ply --pipeline flip --no-crossing-guard -o unguarded.ply 2>stderr.txt; then pass
else fail "smooth --no-crossing-guard on a mesh whose triangles cross: $(cat stderr.txt)"; fi
printf '{"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "phases": [{"name": "a", "kind": "constant", "value": 0}, {"name": "b", "kind": "constant", "value": 1}]}\n' >nothing.json
expect_error "an input that meshes to nothing" 2 "nothing\.json: meshes to nothing" -- "$vm" create -q nothing.json --grid 8 -o out.ply
printf '0.5 0.5 0.5 1\n0.5 0.5 0.5 2\n' >onepoint.xyz # it meshed to nothing, with no word of why
expect_error "one point with two labels" 2 "onepoint\.xyz: points 1 and 2 lie at the same place" -- "$vm" create -q onepoint.xyz --grid 8 -o out.ply

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
