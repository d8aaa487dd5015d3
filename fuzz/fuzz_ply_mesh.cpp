/// @file fuzz/fuzz_ply_mesh.cpp
/// libFuzzer target: vm::io::read_ply, the node-level PLY mesh reader (ascii and
/// binary, either endianness, phase comments and face properties).

#include "input_file.hpp"

#include "voronoimesh/io/ply.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".ply", [](const std::string& path) { vm::io::read_ply(path); });
}
