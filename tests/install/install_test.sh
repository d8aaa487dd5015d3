#!/usr/bin/env bash
# Install test: installs the already-built tree to a temporary prefix, checks the
# installed layout (versioned shared library, public headers only, CMake package,
# pkg-config file, plugin folder), then builds the consumer in consumer/ against it
# twice -- with find_package only, and with pkg-config only -- runs both and checks
# their meshes with the installed CLI. With MPIRUN (a build with VM_MPI), also the MPI
# component: voronoimesh_mpi and mpi/distributed.hpp installed, and mpi_consumer/ built against
# voronoimesh::voronoimesh_mpi and run on 2 ranks. Finally moves the prefix and runs the
# CLI again.
# Usage: install_test.sh BUILD_DIR CONSUMER_DIR WORK_DIR VERSION SOVERSION CXX [MPIRUN]
set -uo pipefail
build=$1 consumer=$2 work=$3 version=$4 soversion=$5 cxx=$6 mpirun=${7:-}
public=$(cd "$(dirname "$0")/../../libvoronoimesh/include/voronoimesh" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
prefix=$work/prefix
passed=0 failed=0
pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
# ok NAME -- command...: the command succeeds (its output is shown if it does not).
ok() {
  local name=$1
  shift 2
  if "$@" >log.txt 2>&1; then pass; else fail "$name: $(tail -20 log.txt)"; return 1; fi
}
finish() {
  echo "install test: $passed passed, $failed failed"
  [ "$failed" -eq 0 ]
  exit
}

ok "cmake --install" -- cmake --install "$build" --prefix "$prefix" || finish
libdir=$(dirname "$(find "$prefix" -name "libvoronoimesh.so.$version" | head -1)")
[ -d "$libdir" ] || { fail "no libvoronoimesh.so.$version under $prefix"; finish; }
# The consumers are not instrumented. Under a ThreadSanitizer build (-DVM_SANITIZE=thread)
# the library brings the TSan runtime, which must then be loaded first: loaded after
# libtbb, it is used by libtbb's initialisation before it is set up, and the program
# crashes. `run` preloads it for the consumers only (the compilers stay as they are).
tsan_runtime=$(ldd "$libdir/libvoronoimesh.so.$version" | awk '$1 ~ /^libtsan/ {print $3}')
run() { if [ -n "$tsan_runtime" ]; then LD_PRELOAD=$tsan_runtime "$@"; else "$@"; fi; }

# The shared library: real file, SONAME link, development link, SONAME inside.
if [ "$(readlink "$libdir/libvoronoimesh.so")" = "libvoronoimesh.so.$soversion" ] &&
  [ "$(readlink "$libdir/libvoronoimesh.so.$soversion")" = "libvoronoimesh.so.$version" ]; then pass
else fail "library links: $(ls -l "$libdir" | grep libvoronoimesh)"; fi
soname=$(objdump -p "$libdir/libvoronoimesh.so.$version" | awk '$1 == "SONAME" {print $2}')
if [ "$soname" = "libvoronoimesh.so.$soversion" ]; then pass; else fail "SONAME '$soname'"; fi
# Only the public interface leaks into a program's link line (Eigen and OpenMesh are
# header-heavy dependencies of the public headers; the rest is private).
needed=$(objdump -p "$libdir/libvoronoimesh.so.$version" | awk '$1 == "NEEDED" {print $2}' | tr '\n' ' ')
for lib in libteem libnifti2 libmuparser libtbb libz libOpenMeshCore; do
  if [[ " $needed" == *" $lib."* ]]; then pass; else fail "library does not need $lib: $needed"; fi
done

# Headers: the public ones (include/voronoimesh/<stage>/) and the generated
# core/version.hpp, nothing from src/, and none includes a private header (every
# include of the library's own is "voronoimesh/...").
include=$prefix/include/voronoimesh
for h in core/errors.hpp improve/pipeline.hpp io/write_mesh.hpp core/version.hpp plugin/plugin_abi.h; do
  if [ -f "$include/$h" ]; then pass; else fail "header $h not installed"; fi
done
extra=$(cd "$include" && find . -type f ! -path ./core/version.hpp | while read -r f; do [ -f "$public/$f" ] || echo "$f"; done)
if [ -z "$extra" ]; then pass; else fail "installed headers that are not public: $extra"; fi
if ! grep -rhE '#include *"' "$include" | grep -vE '#include *"voronoimesh/' >private.txt; then pass
else fail "public headers include private ones: $(cat private.txt)"; fi
if grep -q "VORONOIMESH_VERSION_STRING \"$version\"" "$include/core/version.hpp"; then pass; else fail "core/version.hpp"; fi

# The package files and the plugin folder.
for f in cmake/voronoimesh/voronoimeshConfig.cmake cmake/voronoimesh/voronoimeshConfigVersion.cmake \
  cmake/voronoimesh/voronoimeshTargets.cmake pkgconfig/voronoimesh.pc; do
  if [ -f "$libdir/$f" ]; then pass; else fail "$f not installed"; fi
done
if [ -d "$libdir/voronoimesh/plugins" ]; then pass; else fail "no plugin folder $libdir/voronoimesh/plugins"; fi

# mpi/distributed.hpp comes with the MPI component only.
installed=no mpi_build=no
[ -f "$include/mpi/distributed.hpp" ] && installed=yes
[ -n "$mpirun" ] && mpi_build=yes
if [ "$installed" = "$mpi_build" ]; then pass; else fail "mpi/distributed.hpp installed: $installed, MPI build: $mpi_build"; fi

# Every installed header together, with only the installed tree and the public
# dependencies on the include path (mpi/distributed.hpp also needs MPI's: the MPI consumer below
# compiles it).
export PKG_CONFIG_PATH=$libdir/pkgconfig
cflags=$(pkg-config --cflags voronoimesh) && libs=$(pkg-config --libs voronoimesh) || fail "pkg-config voronoimesh"
if [ "$(pkg-config --modversion voronoimesh)" = "$version" ]; then pass; else fail "pkg-config --modversion"; fi
if [ "$(realpath "$(pkg-config --variable=plugindir voronoimesh)")" = "$libdir/voronoimesh/plugins" ]; then pass
else fail "pkg-config plugindir $(pkg-config --variable=plugindir voronoimesh)"; fi
(cd "$include" && find . -name '*.hpp' ! -path './mpi/*' | sort | sed 's|^\./|#include <voronoimesh/|; s|$|>|') >all_headers.cpp
ok "all installed headers compile" -- "$cxx" -std=c++20 -fsyntax-only $cflags all_headers.cpp

# check_output NAME MESH: the installed CLI reads the consumer's mesh back and finds
# the demo's structure, valid and without crossings.
check_output() {
  if "$prefix/bin/voronoimesh" stats "$2" >stats.txt 2>&1; then pass; else fail "$1: stats: $(cat stats.txt)"; fi
  for want in "surfaces +10" "triple curves +10" "quadruple points +5" "topology +valid"; do
    if grep -qE "^$want" stats.txt; then pass; else fail "$1: stats lack '$want': $(cat stats.txt)"; fi
  done
}

# 1. A CMake project that knows only find_package(voronoimesh CONFIG REQUIRED).
ok "configure the consumer" -- cmake -S "$consumer" -B cmake_consumer -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON || finish
ok "build the consumer" -- cmake --build cmake_consumer || finish
if run ./cmake_consumer/consumer cmake.ply >consumer.txt 2>&1; then pass; else fail "consumer: $(cat consumer.txt)"; fi
cat consumer.txt
if grep -qF "plugin folder $libdir/voronoimesh/plugins" consumer.txt; then pass; else fail "plugin folder"; fi
# loads_installed NAME PROGRAM: the program loads the installed library, no other copy.
loads_installed() {
  local loaded
  loaded=$(ldd "$2" | awk '$1 ~ /^libvoronoimesh\.so/ {print $3}') # not libvoronoimesh_mpi
  if [ -n "$loaded" ] && [ "$(realpath "$loaded")" = "$(realpath "$libdir/libvoronoimesh.so.$soversion")" ]; then pass
  else fail "$1 does not load $libdir/libvoronoimesh.so.$soversion but '$loaded'"; fi
}
loads_installed "the consumer" ./cmake_consumer/consumer
check_output "find_package consumer" cmake.ply

# 2. The same program compiled with nothing but pkg-config's flags.
# shellcheck disable=SC2086 # the flags are words
ok "build with pkg-config" -- "$cxx" -std=c++20 "$consumer/consumer.cpp" -o pc_consumer $cflags $libs -Wl,-rpath,"$libdir" || finish
if run ./pc_consumer pc.ply >pc.txt 2>&1; then pass; else fail "pkg-config consumer: $(cat pc.txt)"; fi
check_output "pkg-config consumer" pc.ply
if cmp -s cmake.ply pc.ply; then pass; else fail "the two consumers wrote different meshes"; fi

# 3. The plugin host example and the "Use it from C++" example, built against the
# installed package with find_package only: the host loads an installed plugin.
examples=$(realpath "$consumer/../../../examples")
for example in host cpp; do
  ok "configure examples/$example" -- cmake -S "$examples/$example" -B "example_$example" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON || finish
  ok "build examples/$example" -- cmake --build "example_$example" || finish
done
if [ -f "$libdir/voronoimesh/plugins/cvt.so" ] && [ -f "$libdir/voronoimesh/plugins/relax.so" ]; then pass
else fail "plugins not installed in $libdir/voronoimesh/plugins"; fi
if "$prefix/bin/voronoimesh" plugins | grep "cvt" >/dev/null; then pass; else fail "the installed CLI does not list the installed cvt plugin"; fi
if run ./example_host/voronoimesh_host "$libdir/voronoimesh/plugins/cvt.so" cvt,project,clamp,flip host.ply >host.txt 2>&1; then pass
else fail "host: $(cat host.txt)"; fi
check_output "plugin host" host.ply
if (cd example_cpp && run ./grains >grains.txt 2>&1); then pass; else fail "examples/cpp: $(cat example_cpp/grains.txt)"; fi

# 4. The MPI component: the library (versioned like the core, linking the installed
# core), and a program that knows only find_package(voronoimesh CONFIG COMPONENTS mpi),
# run on 2 ranks.
if [ -n "$mpirun" ]; then
  mpi_lib=$libdir/libvoronoimesh_mpi.so.$version
  soname=$(objdump -p "$mpi_lib" 2>/dev/null | awk '$1 == "SONAME" {print $2}')
  if [ "$soname" = "libvoronoimesh_mpi.so.$soversion" ]; then pass; else fail "voronoimesh_mpi SONAME '$soname'"; fi
  ok "configure the MPI consumer" -- cmake -S "$consumer/../mpi_consumer" -B mpi_consumer -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON || finish
  ok "build the MPI consumer" -- cmake --build mpi_consumer || finish
  loads_installed "the MPI consumer" ./mpi_consumer/mpi_consumer
  # Its ranks, not mpirun, get the sanitizer runtime of an instrumented library preloaded
  # (see run above), ASan's too: linked after voronoimesh_mpi and MPI, libOpenMeshCore's
  # static constructors allocate before the ASan runtime is set up, a crash before main.
  sanitizer_runtime=$(ldd "$libdir/libvoronoimesh.so.$version" | awk '$1 ~ /^lib[at]san/ {print $3}')
  if timeout 120 "$mpirun" -np 2 --oversubscribe ${sanitizer_runtime:+-x LD_PRELOAD="$sanitizer_runtime"} \
    ./mpi_consumer/mpi_consumer mpi.ply >mpi.txt 2>&1; then pass
  else fail "MPI consumer: $(cat mpi.txt)"; fi
  cat mpi.txt
  check_output "MPI consumer" mpi.ply
elif cmake -S "$consumer/../mpi_consumer" -B mpi_consumer -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON >mpi.txt 2>&1; then
  fail "a package built without MPI offers the component mpi"
elif grep -q "no component mpi: this voronoimesh was built without MPI" mpi.txt; then pass
else fail "asking a package without MPI for the component mpi: $(tail -5 mpi.txt)"; fi

# 5. The installed tree still works after the prefix is moved: the CLI finds its
# library relative to itself, and the library its plugin folder beside itself.
mv "$prefix" "$work/moved" && libdir=${libdir/#$prefix/$work/moved} && prefix=$work/moved
loads_installed "the moved CLI" "$prefix/bin/voronoimesh"
LD_LIBRARY_PATH=$libdir run ./pc_consumer moved.ply >moved.txt 2>&1
if grep -qF "plugin folder $libdir/voronoimesh/plugins" moved.txt; then pass
else fail "moved plugin folder: $(cat moved.txt)"; fi
if [ "$("$prefix/bin/voronoimesh" --version)" = "voronoimesh $version" ]; then pass
else fail "moved CLI --version: $("$prefix/bin/voronoimesh" --version 2>&1)"; fi
check_output "moved CLI" cmake.ply
finish
