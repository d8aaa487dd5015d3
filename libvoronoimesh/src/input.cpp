#include "voronoimesh/input.hpp"

#include "voronoimesh/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include "detail/axis_align.hpp"
#include "detail/point_cloud.hpp"
#include "detail/text.hpp"
#include "detail/volume_scenes.hpp"
#include "detail/voxel_grid.hpp"

#include <algorithm>

namespace vm {

namespace {

using detail::cat;

/// A distance grid: one real component per phase per voxel.
Scene distance_scene(const io::Volume& v, const InputOptions& o, const std::string& path) {
  if (v.components < 2)
    throw InvalidInput(located(path, "has one real component per voxel; a distance grid needs one per phase (2 or more), "
                                     "or one file per phase through a scene's \"grid\" phases"));
  const GridSpec grid = detail::voxel_grid(v.size, v.spacing, v.origin, path, "a distance grid");
  const size_t c = size_t(v.components);
  const auto fill = [&](int64_t n, std::span<float> out) {
    std::copy_n(v.values.begin() + ptrdiff_t(size_t(n) * c), c, out.begin());
  };
  Scene scene = detail::phase_values_scene(grid, v.components, fill, {}, {}, o.top_k, path);
  scene.grid = detail::volume_scene_grid(grid, o.voxels_per_cell, path);
  return scene;
}

} // namespace

Scene load_input(const std::string& path, const InputOptions& options) {
  detail::check_input_options(options);
  if (detail::lower(path).ends_with(".json")) return load_scene(path);
  if (io::is_volume_file(path)) {
    io::Volume v = io::read_volume(path);
    detail::axis_align(v, path, options.ignore_direction);
    return v.integer ? detail::label_volume_scene(std::move(v), options, path) : distance_scene(v, options, path);
  }
  if (detail::is_point_file(path)) return detail::point_cloud_scene(path, options);
  throw InvalidInput(located(path, "unknown input type: expected a scene (.json), a volume (.nrrd, .nhdr, .nii, .nii.gz, "
                                   ".mha, .mhd, .inr, .inr.gz) or a point file (.xyz, .txt, .pts, .csv, .ply)"));
}

} // namespace vm
