/// @file fuzz/fuzz_tiff.cpp
/// libFuzzer target: vm::io::read_tiff on any bytes, as a .tif file: a TIFF stack (classic or BigTIFF).

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".tif", [](const std::string& path) { vm::io::read_tiff(path); });
}
