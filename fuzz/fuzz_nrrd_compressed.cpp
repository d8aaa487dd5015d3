/// @file fuzz/fuzz_nrrd_compressed.cpp
/// libFuzzer target: vm::io::read_nrrd on an attached NRRD whose data the
/// target compresses as the header's encoding says (gzip or bzip2;
/// compress_nrrd_data() in input_layouts.hpp), so that mutated sizes, types and
/// skips meet data that decompresses.

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string nrrd = vm::fuzz::compress_nrrd_data(std::string_view(reinterpret_cast<const char*>(data), size));
  return vm::fuzz::read_cleanly(vm::fuzz::write_file("input.nrrd", nrrd),
                                [](const std::string& path) { vm::io::read_nrrd(path); });
}
