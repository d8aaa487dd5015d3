#include "voronoimesh/fields/input.hpp"

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include "core/text.hpp"
#include "fields/axis_align.hpp"
#include "fields/point_cloud.hpp"
#include "fields/volume_scenes.hpp"
#include "fields/voxel_grid.hpp"
#include "io/voxel_data.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace vm {

namespace {

using detail::cat;
using detail::lower;

/// Whole numbers a float tells apart: beyond 2^24 neighbouring ones round to one value.
constexpr double kLargestWholeFloatLabel = 16777216;

/// A volume of one real value per voxel is a label volume saved as reals, as
/// many segmenters (ITK filters, deep-learning tools, writers of float arrays)
/// save labels: it cannot be a distance grid, which has a value per phase. Makes
/// it one when every value is a whole number (of at most 2^24 in magnitude),
/// and otherwise refuses it naming the first voxel that is not; voxel indices
/// as in the file, so call it before axis_align().
void labels_from_whole_values(io::Volume& v, const std::string& path) {
  if (v.integer || v.components != 1) return;
  const auto not_label = std::find_if(v.values.begin(), v.values.end(), [](float x) {
    return !(std::abs(double(x)) <= kLargestWholeFloatLabel && x == std::trunc(x));
  });
  if (not_label != v.values.end()) {
    char value[32];
    *std::to_chars(value, value + sizeof value - 1, *not_label).ptr = '\0';
    throw InvalidInput(located(
        path, cat("holds one real value per voxel, but ", detail::voxel_name(v, size_t(not_label - v.values.begin())),
                  " holds ", value,
                  ", not a label (labels saved as reals must be whole numbers, of at most 2^24: a label map resampled "
                  "with linear interpolation? resample it with nearest neighbour); a distance grid needs one value "
                  "per phase (2 or more), or one file per phase through a scene's \"grid\" phases")));
  }
  v.labels.assign(v.values.begin(), v.values.end());
  v.values = {};
  v.integer = true;
  v.notes.push_back("voxels stored as reals, every one a whole number: read as labels");
}

/// Puts `size` (--voxel-size) in place of the file's voxel size, along the
/// file's axes, and says so; or says that the file gives none.
void set_voxel_size(io::Volume& v, const std::optional<Vec3>& size) {
  const auto sizes = [](const Vec3& s) { return cat(s.x(), " x ", s.y(), " x ", s.z()); };
  if (size) {
    v.notes.push_back(cat("voxels of ", sizes(*size), " (--voxel-size; the file's: ",
                          v.spacing_stated ? sizes(v.spacing) : std::string("none"), ")"));
    v.spacing = *size;
    v.spacing_stated = true;
  } else if (!v.spacing_stated) {
    v.notes.push_back(cat("the file says no voxel size along some axis: voxels of ", sizes(v.spacing),
                          " (--voxel-size gives them theirs)"));
  }
}

/// A distance grid: one real component per phase per voxel.
/// (One real component is a label volume: read_placed_volume() makes it one or refuses it.)
Scene distance_scene(const io::Volume& v, const InputOptions& o, const std::string& path) {
  const GridSpec grid = detail::voxel_grid(v.size, v.spacing, v.origin, path, "a distance grid");
  const size_t c = size_t(v.components);
  const auto fill = [&](int64_t n, std::span<float> out) {
    std::copy_n(v.values.begin() + ptrdiff_t(size_t(n) * c), c, out.begin());
  };
  Scene scene = detail::phase_values_scene(grid, v.components, fill, {}, {}, o.top_k, path);
  scene.notes = v.notes;
  scene.grid = detail::volume_scene_grid(grid, o.voxels_per_cell, path, scene.notes);
  return scene;
}

/// The options of `o` that differ from their defaults but mean nothing for an
/// input of this kind ("--smoothing" ...), so that none is silently ignored.
/// `volume` and `labels`: whether options for volumes, and for label volumes, apply.
std::vector<std::string> options_that_do_not_apply(const InputOptions& o, bool volume, bool labels) {
  const InputOptions defaults;
  std::vector<std::string> given;
  if (!labels) {
    if (!o.drop_labels.empty()) given.push_back("--drop-labels");
    if (!o.merge_labels.empty()) given.push_back("--merge-labels");
    if (!o.keep_labels.empty()) given.push_back("--keep-labels");
    if (o.background != defaults.background) given.push_back("--background");
    if (o.no_background) given.push_back("--no-background");
    if (o.label_function != defaults.label_function) given.push_back("--signed-distance");
    if (o.smoothing != defaults.smoothing) given.push_back("--smoothing");
    if (o.voxel_faithful) given.push_back("--voxel-faithful");
    if (o.band != defaults.band) given.push_back("--band");
  }
  if (!volume) {
    if (o.voxels_per_cell != defaults.voxels_per_cell) given.push_back("--voxels-per-cell");
    if (o.voxel_size) given.push_back("--voxel-size");
    if (o.ignore_direction) given.push_back("--ignore-direction");
    if (o.world != defaults.world) given.push_back("--world");
  }
  return given;
}

/// The frame's name in messages.
const char* frame_name(io::WorldFrame f) { return f == io::WorldFrame::lps ? "LPS" : "RAS"; }

/// Puts `v` in the frame `o.world` asks for (LPS and RAS differ in the signs of
/// x and y), and says which frame its coordinates are in.
std::string convert_world(io::Volume& v, World world, const std::string& path) {
  if (world == World::file)
    return v.world == io::WorldFrame::unknown ? std::string() : cat(frame_name(v.world), " (the file's)");
  const io::WorldFrame want = world == World::lps ? io::WorldFrame::lps : io::WorldFrame::ras;
  if (v.world == io::WorldFrame::unknown)
    throw InvalidInput(located(path, cat("--world ", lower(frame_name(want)),
                                         ": the file does not say which anatomical frame its coordinates are in (NIfTI "
                                         "with a qform or sform, NRRD with space LPS or RAS, and MetaImage do)")));
  if (v.world == want) return cat(frame_name(want), " (the file's)");
  const Vec3 flip(-1, -1, 1);
  v.origin = v.origin.cwiseProduct(flip);
  v.direction = flip.asDiagonal() * v.direction;
  const std::string said = cat(frame_name(want), " (converted from the file's ", frame_name(v.world), ")");
  v.world = want;
  return said;
}

} // namespace

void refuse_options_that_do_not_apply(const InputOptions& o, bool volume, bool labels, const std::string& kind,
                                      const std::string& what) {
  const std::vector<std::string> given = options_that_do_not_apply(o, volume, labels);
  if (given.empty()) return;
  std::string list = given.front();
  for (size_t i = 1; i < given.size(); ++i) list += ", " + given[i];
  const bool label_options_only = options_that_do_not_apply(o, true, labels).size() == given.size();
  throw InvalidInput(located(what, cat(list, given.size() > 1 ? " apply" : " applies", " only to ",
                                       label_options_only ? "label volumes" : "volumes", ", and this is ", kind,
                                       " (docs/inputs.md)")));
}

io::Volume read_placed_volume(const std::string& path, const InputOptions& options, std::string* world) {
  io::Volume v = io::read_volume(path);
  set_voxel_size(v, options.voxel_size);
  labels_from_whole_values(v, path);
  const std::string frame = convert_world(v, options.world, path);
  detail::axis_align(v, path, options.ignore_direction);
  if (world) *world = frame;
  return v;
}

Scene load_input(const std::string& path, const InputOptions& options) {
  detail::check_input_options(options);
  if (detail::lower(path).ends_with(".json")) {
    refuse_options_that_do_not_apply(options, false, false, "a scene", path);
    return load_scene(path);
  }
  if (io::is_volume_file(path)) {
    std::string world;
    io::Volume v = read_placed_volume(path, options, &world);
    if (!v.integer) refuse_options_that_do_not_apply(options, true, false, "a distance grid (real values)", path);
    Scene scene = v.integer ? detail::label_volume_scene(std::move(v), options, path) : distance_scene(v, options, path);
    scene.world = world;
    return scene;
  }
  if (detail::is_point_file(path)) {
    refuse_options_that_do_not_apply(options, false, false, "a point cloud", path);
    return detail::point_cloud_scene(path, options);
  }
  throw InvalidInput(located(path, "unknown input type: expected a scene (.json), a volume (.nrrd, .nhdr, .nii, .nii.gz, "
                                   ".mha, .mhd, .inr, .inr.gz, .dream3d, .tif, .tiff) or a point file (.xyz, .txt, .pts, .csv, .ply)"));
}

} // namespace vm
