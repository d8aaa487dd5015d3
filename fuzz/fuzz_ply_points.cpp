/// @file fuzz/fuzz_ply_points.cpp
/// libFuzzer target: a PLY labelled point cloud through point_cloud_scene (the
/// PLY point reader, then the scene built from the points, evaluated once).

#include "input_file.hpp"

#include "fields/point_cloud.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return vm::fuzz::read_as_file(data, size, ".ply", [](const std::string& path) {
    vm::fuzz::evaluate_at_centre(vm::detail::point_cloud_scene(path, {}));
  });
}
