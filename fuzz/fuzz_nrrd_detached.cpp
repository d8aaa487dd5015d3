/// @file fuzz/fuzz_nrrd_detached.cpp
/// libFuzzer target: vm::io::read_nrrd on a detached header, input.nhdr, and
/// the data files the same input holds (layout: split_files() in
/// input_layouts.hpp): "data file:" as one name, a LIST, or a numbered pattern,
/// in any encoding (the compressed bytes as they are).

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_files(data, size, "input.nhdr", [](const std::string& path) { vm::io::read_nrrd(path); });
}
