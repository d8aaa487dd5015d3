/// @file fuzz/fuzz_metaimage.cpp
/// libFuzzer target: vm::io::read_metaimage on any bytes, as a .mha file: MetaImage (.mha with the data after the header).

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".mha", [](const std::string& path) { vm::io::read_metaimage(path); });
}
