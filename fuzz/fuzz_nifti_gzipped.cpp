/// @file fuzz/fuzz_nifti_gzipped.cpp
/// libFuzzer target: vm::io::read_nifti on a .nii.gz file holding the input
/// gzipped by the target, so that the mutations reach the NIfTI header and the
/// voxel data through the decompressor (header and data sizes against the
/// compressed file's length, reads past the end of the stream).

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string gz = vm::fuzz::gzip(std::string_view(reinterpret_cast<const char*>(data), size));
  return vm::fuzz::read_cleanly(vm::fuzz::write_file("input.nii.gz", gz),
                                [](const std::string& path) { vm::io::read_nifti(path); });
}
