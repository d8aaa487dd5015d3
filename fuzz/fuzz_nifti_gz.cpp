/// @file fuzz/fuzz_nifti_gz.cpp
/// libFuzzer target: vm::io::read_nifti on any bytes, as a .nii.gz file: the
/// gzip stream itself is fuzzed (znzlib's inflating, truncated and corrupt streams).

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".nii.gz", [](const std::string& path) { vm::io::read_nifti(path); });
}
