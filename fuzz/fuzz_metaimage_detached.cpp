/// @file fuzz/fuzz_metaimage_detached.cpp
/// libFuzzer target: vm::io::read_metaimage on a .mhd header, input.mhd, and
/// the data files the same input holds (layout: split_files() in
/// input_layouts.hpp): ElementDataFile naming a file, raw or zlib-compressed,
/// with HeaderSize; the LIST and pattern forms, which are refused.

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_files(data, size, "input.mhd",
                                 [](const std::string& path) { vm::io::read_metaimage(path); });
}
