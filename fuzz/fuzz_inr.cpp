/// @file fuzz/fuzz_inr.cpp
/// libFuzzer target: vm::io::read_inr on any bytes, as a .inr file: INRIMAGE-4 (.inr, plain or gzip).

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".inr", [](const std::string& path) { vm::io::read_inr(path); });
}
