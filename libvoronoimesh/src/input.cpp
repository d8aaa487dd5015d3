#include "voronoimesh/input.hpp"

#include "voronoimesh/errors.hpp"
#include "voronoimesh/io/volume.hpp"

#include "detail/axis_align.hpp"
#include "detail/label_field.hpp"
#include "detail/memory.hpp"
#include "detail/point_cloud.hpp"
#include "detail/text.hpp"
#include "detail/voxel_grid.hpp"

#include <algorithm>
#include <unordered_set>

namespace vm {

namespace {

using detail::lower;

using detail::cat;

void check_options(const InputOptions& o) {
  if (!(o.smoothing > 0 && o.smoothing <= 8)) throw InvalidInput(cat("--smoothing: must be in (0, 8] voxels, got ", o.smoothing));
  if (!(o.band >= 1 && o.band <= 64)) throw InvalidInput(cat("--band: must be in [1, 64] voxels, got ", o.band));
  if (o.top_k < 1 || o.top_k > 16) throw InvalidInput("--top-k: must be between 1 and 16");
  for (const auto& group : o.merge_labels)
    if (group.size() < 2) throw InvalidInput("--merge-labels: each group needs two labels or more, as A+B");
}

/// The distinct values of `labels`, sorted (runs of equal labels cost one lookup).
std::vector<int32_t> distinct(const std::vector<int32_t>& labels) {
  std::unordered_set<int32_t> seen;
  int32_t last = 0;
  bool any = false;
  for (int32_t l : labels)
    if (!any || l != last) seen.insert(l), last = l, any = true;
  std::vector<int32_t> out(seen.begin(), seen.end());
  std::sort(out.begin(), out.end());
  return out;
}

/// What each label present becomes after --drop-labels, --merge-labels and the
/// background rule: a label value, or -1 for no phase.
std::vector<int32_t> label_targets(const std::vector<int32_t>& present, const InputOptions& o, const std::string& path) {
  auto require_present = [&](int32_t l, const char* option) {
    if (!std::binary_search(present.begin(), present.end(), l))
      throw InvalidInput(located(path, cat(option, ": label ", l, " is not in the volume")));
  };
  std::vector<int32_t> target = present;
  for (int32_t l : o.drop_labels) require_present(l, "--drop-labels");
  for (const auto& group : o.merge_labels) for (int32_t l : group) require_present(l, "--merge-labels");
  for (size_t i = 0; i < present.size(); ++i) {
    int32_t& t = target[i];
    if (std::find(o.drop_labels.begin(), o.drop_labels.end(), t) != o.drop_labels.end()) t = o.background;
    for (const auto& group : o.merge_labels)
      if (std::find(group.begin(), group.end(), t) != group.end()) t = *std::min_element(group.begin(), group.end());
    if (o.no_background && t == o.background) t = -1;
  }
  return target;
}

/// Refuses, before building them, phase functions that cannot fit in memory:
/// per voxel a phase id, K ids and values, a floor and the working copies of the
/// label field's passes (about as much again).
void refuse_huge_field(const io::Volume& v, const InputOptions& o, const std::string& path) {
  detail::refuse_beyond_memory(double(v.voxel_count()) * (13.0 + 8.0 * o.top_k) * 2, path,
                               cat("building the phase functions of ", double(v.voxel_count()), " voxels"));
}

Scene label_scene(const io::Volume& v, const InputOptions& o, const std::string& path) {
  if (v.components != 1)
    throw InvalidInput(located(path, cat("has ", v.components, " integer components per voxel; a label volume has one")));
  refuse_huge_field(v, o, path);
  const std::vector<int32_t> present = distinct(v.labels);
  const std::vector<int32_t> target = label_targets(present, o, path);
  detail::PhaseVoxels pv{v.size, v.spacing, v.origin, {}, {}, {}};
  for (int32_t t : target) if (t >= 0) pv.labels.push_back(t);
  std::sort(pv.labels.begin(), pv.labels.end());
  pv.labels.erase(std::unique(pv.labels.begin(), pv.labels.end()), pv.labels.end());
  if (pv.labels.size() < 2)
    throw InvalidInput(located(path, cat("has ", pv.labels.size(), " phase(s) after the label options; meshing needs 2 or more")));
  if (pv.labels.size() > kMaxPhases)
    throw InvalidInput(located(path, cat("has ", pv.labels.size(), " labels; at most ", kMaxPhases)));
  for (int32_t l : pv.labels) pv.names.push_back(l == o.background ? std::string("background") : cat("label", l));
  // Label value -> phase id, through the position of the label among `present`.
  std::vector<int32_t> phase_of(present.size());
  for (size_t i = 0; i < present.size(); ++i)
    phase_of[i] = target[i] < 0 ? -1
                                : int32_t(std::lower_bound(pv.labels.begin(), pv.labels.end(), target[i]) - pv.labels.begin());
  pv.phase.resize(v.labels.size());
  for (size_t n = 0; n < v.labels.size(); ++n)
    pv.phase[n] = phase_of[size_t(std::lower_bound(present.begin(), present.end(), v.labels[n]) - present.begin())];
  detail::LabelFieldParams params;
  params.signed_distance = o.label_function == LabelFunction::signed_distance;
  params.smoothing = o.smoothing;
  params.band = o.band;
  params.k = o.top_k;
  auto field = detail::label_field(pv, params, path);
  return Scene{detail::even_scene_grid(field->grid(), path), field};
}

Scene distance_scene(const io::Volume& v, const InputOptions& o, const std::string& path) {
  if (v.components < 2)
    throw InvalidInput(located(path, "has one real component per voxel; a distance grid needs one per phase (2 or more), "
                                     "or one file per phase through a scene's \"grid\" phases"));
  if (size_t(v.components) > kMaxPhases)
    throw InvalidInput(located(path, cat("has ", v.components, " components; at most ", kMaxPhases)));
  refuse_huge_field(v, o, path);
  const GridSpec grid = detail::voxel_grid(v.size, v.spacing, v.origin, path, "a distance grid");
  std::vector<std::string> names;
  for (int i = 0; i < v.components; ++i) names.push_back(cat("phase", i));
  auto field = std::make_shared<detail::TopKGridField>(grid, o.top_k, std::move(names), std::vector<int32_t>{});
  const size_t c = size_t(v.components);
  for (int64_t n = 0; n < v.voxel_count(); ++n)
    for (size_t i = 0; i < c; ++i) field->offer(n, int32_t(i), v.values[size_t(n) * c + i]);
  field->finish(0.f); // every phase was offered everywhere: nothing to pad
  return Scene{detail::even_scene_grid(grid, path), field};
}

} // namespace

Scene load_input(const std::string& path, const InputOptions& options) {
  check_options(options);
  if (lower(path).ends_with(".json")) return load_scene(path);
  if (io::is_volume_file(path)) {
    io::Volume v = io::read_volume(path);
    detail::axis_align(v, path, options.ignore_direction);
    return v.integer ? label_scene(v, options, path) : distance_scene(v, options, path);
  }
  if (detail::is_point_file(path)) return detail::point_cloud_scene(path, options);
  throw InvalidInput(located(path, "unknown input type: expected a scene (.json), a volume (.nrrd, .nhdr, .nii, .nii.gz, "
                                   ".mha, .mhd, .inr, .inr.gz) or a point file (.xyz, .txt, .pts, .csv, .ply)"));
}

} // namespace vm
