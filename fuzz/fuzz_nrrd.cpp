/// @file fuzz/fuzz_nrrd.cpp
/// libFuzzer target: vm::io::read_nrrd on any bytes, as a .nrrd file: NRRD (Teem's nrrdLoad and our checks).

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".nrrd", [](const std::string& path) { vm::io::read_nrrd(path); });
}
