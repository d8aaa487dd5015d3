/// @file fuzz/fuzz_nifti.cpp
/// libFuzzer target: vm::io::read_nifti on any bytes, as a .nii file: NIfTI-1/2 (.nii; nifti2_io and our checks).

#include "input_file.hpp"

#include "voronoimesh/io/volume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".nii", [](const std::string& path) { vm::io::read_nifti(path); });
}
