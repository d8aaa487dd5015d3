/// @file fuzz/fuzz_points.cpp
/// libFuzzer target: a text labelled point cloud ("x y z label" lines) through
/// point_cloud_scene (evaluated once), as a .csv so that the header-row rule
/// is exercised too.

#include "input_file.hpp"

#include "fields/point_cloud.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".csv", [](const std::string& path) {
    vm::fuzz::evaluate_at_centre(vm::detail::point_cloud_scene(path, {}));
  });
}
