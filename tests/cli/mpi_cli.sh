#!/usr/bin/env bash
# `voronoimesh mesh --mpi` (and `create --mpi`) under mpirun: pieces with a ParaView index, the
# assembled file equal to the one of one process, and a failure on one rank
# (bad input, too little memory) ending every rank with one message and its exit code.
# Usage: mpi_cli.sh MPIRUN VORONOIMESH EXAMPLES_DIR WORK_DIR
set -uo pipefail
mpirun=$1 vm=$2 examples=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
run() { "$mpirun" -np 2 --oversubscribe "$vm" "$@"; }
passed=0 failed=0
pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
scene=$examples/four_spheres.json

run mesh "$scene" --grid 16 --mpi --iterations 0 --threads 1 -o pieces.pvtu 2>stderr.txt
if [ $? -ne 0 ]; then fail "pvtu: $(cat stderr.txt)"
elif [ ! -s pieces_0.vtu ] || [ ! -s pieces_1.vtu ]; then fail "pvtu: pieces missing: $(ls)"
elif [ "$(grep -c '<Piece Source=' pieces.pvtu)" -ne 2 ]; then fail "pvtu: index does not list 2 pieces"
elif ! grep -q "create (mpi, 2 ranks)" stderr.txt; then fail "pvtu: no summary: $(cat stderr.txt)"
else pass; fi

# The same file as one process, created, and improved over the ranks (the
# default pipeline under --mpi, the paper's: one process's default for scenes
# remeshes first, which does not run distributed) or on rank 0 (a pass that is
# not distributed: stats).
paper=smooth,project,clamp,flip
for iterations in 0 5; do
  "$vm" mesh "$scene" --grid 16 --iterations $iterations --pipeline $paper --threads 1 -q -o alone_$iterations.ply
  run mesh "$scene" --grid 16 --mpi --iterations $iterations --threads 1 -q -o ranks_$iterations.ply 2>stderr.txt
  if [ $? -ne 0 ]; then fail "assembled, $iterations iterations: $(cat stderr.txt)"
  elif ! cmp -s alone_$iterations.ply ranks_$iterations.ply; then fail "assembled, $iterations iterations: differs"
  else pass; fi
done

# Collapses over the ranks: at grid 30 the 30 seeds' flip passes collapse
# junction slivers and merge close quadruple points into higher-order points,
# each rank answering for its own; the assembled mesh is still one process's.
# (Grid 32 until a sliver no edge of which may collapse could lose a curve node
# beside it instead: there that kept every quadruple point apart.)
"$vm" mesh "$examples/voronoi30.json" --grid 30 --iterations 10 --pipeline $paper -q -o alone_30.ply
run mesh "$examples/voronoi30.json" --grid 30 --mpi --iterations 10 -q -o ranks_30.ply 2>stderr.txt
if [ $? -ne 0 ]; then fail "voronoi30 collapses: $(cat stderr.txt)"
elif ! cmp -s alone_30.ply ranks_30.ply; then fail "voronoi30 collapses: differs from one process"
elif ! "$vm" stats alone_30.ply | grep -E "^higher-order points +[1-9]" >/dev/null; then fail "voronoi30: no corners merged"
else pass; fi

# A label volume stops once its quality converges, as in one process (where its
# default pipeline remeshes first: here the paper's); --all-iterations runs every one.
/usr/bin/python3 - <<'PY'
n = 20  # label 2 in a ball, label 3 in a slab beside it, 1 around
with open("labels.nrrd", "wb") as f:
    f.write(b"NRRD0004\ntype: uchar\ndimension: 3\nsizes: 20 20 20\nencoding: raw\n\n")
    for k in range(n):
        for j in range(n):
            f.write(bytes(2 if (i - 8) ** 2 + (j - 10) ** 2 + (k - 10) ** 2 < 30 else 3 if i > 14 else 1
                          for i in range(n)))
PY
"$vm" mesh labels.nrrd --pipeline $paper --stop-when-converged --iterations 40 --threads 1 -q -o alone_labels.ply
run mesh labels.nrrd --mpi --iterations 40 --threads 1 -o ranks_labels.ply 2>stderr.txt
if [ $? -ne 0 ] || ! grep -q "improve (mpi): .*quality converged" stderr.txt; then
  fail "label volume, stopped when converged: $(cat stderr.txt)"
elif ! cmp -s alone_labels.ply ranks_labels.ply; then fail "label volume, stopped when converged: differs"
else pass; fi
run mesh labels.nrrd --mpi --iterations 40 --all-iterations --threads 1 -o all_labels.ply 2>stderr.txt
if [ $? -ne 0 ] || ! grep -q "improve (mpi): 40 iterations" stderr.txt; then
  fail "label volume, all iterations: $(cat stderr.txt)"
else pass; fi

# `create --mpi` is `mesh --mpi --iterations 0`.
run create "$scene" --grid 16 --mpi --threads 1 -q -o created.ply 2>stderr.txt
if [ $? -ne 0 ]; then fail "create --mpi: $(cat stderr.txt)"
elif ! cmp -s alone_0.ply created.ply; then fail "create --mpi: differs from one process"
else pass; fi
run create "$scene" --grid 16 --mpi --threads 1 -q -o created.pvtu 2>stderr.txt
if [ $? -ne 0 ] || [ ! -s created_0.vtu ] || [ ! -s created_1.vtu ]; then fail "create --mpi, pvtu: $(cat stderr.txt)"
else pass; fi

# NaN in the top layers, which rank 1 samples: every rank exits 2, one message.
cat >nan.json <<'JSON'
{"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": 16, "phases": [
  {"kind": "sphere", "center": [0.5, 0.5, 0.5], "radius": 0.3},
  {"kind": "expr", "expr": "z > 0.9 ? sqrt(-1) : 0.1 - abs(x - 0.5)"}]}
JSON
timeout 60 "$mpirun" -np 2 --oversubscribe "$vm" mesh nan.json --mpi --iterations 0 -o nan.ply 2>stderr.txt
code=$?
if [ $code -ne 2 ]; then fail "nan: exit $code, expected 2: $(cat stderr.txt)"
elif [ "$(grep -c 'voronoimesh: rank 1 of 2: .*NaN' stderr.txt)" -ne 1 ]; then fail "nan: message: $(cat stderr.txt)"
elif [ -e nan.ply ]; then fail "nan: wrote a file"
else pass; fi

# Too little memory on the node for the ranks' blocks (VORONOIMESH_NODE_MEMORY
# stands in for MemAvailable): refused before sampling; every rank exits 2, one message.
VORONOIMESH_NODE_MEMORY=200K timeout 60 "$mpirun" -np 2 --oversubscribe "$vm" mesh "$scene" --grid 16 --mpi \
  --iterations 0 -o small.ply 2>stderr.txt
code=$?
want="voronoimesh: rank 0 of 2: grid: layers 0\.\.7 of a 16x16x16 grid needs about 0\.12 MiB on this rank, its share of its node's memory is 0\.10 MiB (0\.20 MiB VORONOIMESH_NODE_MEMORY, 2 ranks)"
if [ $code -ne 2 ]; then fail "node memory: exit $code, expected 2: $(cat stderr.txt)"
elif [ "$(grep -c "$want" stderr.txt)" -ne 1 ]; then fail "node memory: message: $(cat stderr.txt)"
elif [ -e small.ply ]; then fail "node memory: wrote a file"
else pass; fi

run mesh "$scene" --grid 16 --mpi --iterations 5 --threads 1 -o improved.ply 2>stderr.txt
if ! grep -q "improve (mpi): 5 iterations" stderr.txt; then fail "not improved over the ranks: $(cat stderr.txt)"
else pass; fi
"$vm" mesh "$scene" --grid 16 --iterations 5 --pipeline smooth,project,clamp,flip,stats --threads 1 -q -o alone_stats.ply
run mesh "$scene" --grid 16 --mpi --iterations 5 --pipeline smooth,project,clamp,flip,stats --threads 1 \
  -o ranks_stats.ply 2>stderr.txt
if [ $? -ne 0 ] || ! grep -q "on rank 0 alone" stderr.txt; then fail "stats pass: $(cat stderr.txt)"
elif ! cmp -s alone_stats.ply ranks_stats.ply; then fail "stats pass on rank 0: differs"
else pass; fi

# Pieces after a distributed improvement; refused when it would be on rank 0.
run mesh "$scene" --grid 16 --mpi --iterations 5 --threads 1 -q -o improved.pvtu 2>stderr.txt
if [ $? -ne 0 ] || [ ! -s improved_1.vtu ]; then fail "improved pieces: $(cat stderr.txt)"
else pass; fi
run mesh "$scene" --grid 16 --mpi --history history.csv -o history.pvtu 2>stderr.txt
code=$?
if [ $code -ne 2 ] || ! grep -q "pieces per rank (.pvtu) need a distributed improvement" stderr.txt; then
  fail "pvtu with rank-0 improvement: exit $code: $(cat stderr.txt)"
else pass; fi
# Stopping once quality converges runs distributed, with the same mesh as one process.
"$vm" mesh "$scene" --grid 16 --pipeline $paper --stop-when-converged --threads 1 -q -o alone_converged.ply
run mesh "$scene" --grid 16 --mpi --stop-when-converged --threads 1 -o converged.pvtu 2>stderr.txt
if [ $? -ne 0 ] || ! grep -q "improve (mpi): .*quality converged" stderr.txt; then
  fail "pvtu, stopped when converged: $(cat stderr.txt)"
else pass; fi
run mesh "$scene" --grid 16 --mpi --stop-when-converged --threads 1 -q -o ranks_converged.ply 2>stderr.txt
if [ $? -ne 0 ]; then fail "assembled, stopped when converged: $(cat stderr.txt)"
elif ! cmp -s alone_converged.ply ranks_converged.ply; then fail "assembled, stopped when converged: differs"
else pass; fi

echo "mpi cli: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
