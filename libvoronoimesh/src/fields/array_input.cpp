#include "voronoimesh/fields/array_input.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/text.hpp"
#include "fields/point_cloud.hpp"
#include "fields/volume_scenes.hpp"

#include <algorithm>
#include <cmath>

namespace vm {

namespace {

using detail::cat;

/// Throws InvalidInput naming `source` unless `grid` has [1, 4096] cells per
/// axis over a non-empty, finite domain, and `count` (entries per node) x its
/// node count is the length `given`.
void check_grid(const GridSpec& grid, size_t given, size_t per_node, const std::string& source, const char* what) {
  for (int a = 0; a < 3; ++a) {
    if (grid.cells[size_t(a)] < 1 || grid.cells[size_t(a)] > 4096)
      throw InvalidInput(located(source, cat("grid: ", grid.cells[size_t(a)], " cells along axis ", std::string(1, "xyz"[a]),
                                             "; must be between 1 and 4096")));
    if (!(grid.domain.max[a] > grid.domain.min[a]) || !std::isfinite(grid.domain.max[a] - grid.domain.min[a]))
      throw InvalidInput(located(source, cat("grid: the domain is empty or not finite along axis ", std::string(1, "xyz"[a]))));
  }
  const size_t expected = size_t(grid.node_count()) * per_node;
  if (given != expected)
    throw InvalidInput(located(source, cat(what, " holds ", given, " values; the grid's ", grid.node_count(),
                                           " nodes need ", expected)));
}

void check_top_k(int top_k, const std::string& source) {
  if (top_k < 1 || top_k > 16) throw InvalidInput(located(source, cat("top_k: must be between 1 and 16, got ", top_k)));
}

} // namespace

Scene scene_from_phase_values(const GridSpec& grid, const std::vector<std::span<const double>>& phases,
                              const PhaseValuesOptions& options) {
  check_top_k(options.top_k, options.source);
  for (size_t p = 0; p < phases.size(); ++p)
    check_grid(grid, phases[p].size(), 1, options.source, cat("phase ", p).c_str());
  const auto fill = [&](int64_t n, std::span<float> out) {
    for (size_t p = 0; p < phases.size(); ++p) out[p] = float(phases[p][size_t(n)]);
  };
  return detail::phase_values_scene(grid, int(phases.size()), fill, options.names, options.labels, options.top_k,
                                    options.source);
}

Scene scene_from_interleaved_values(const GridSpec& grid, std::span<const double> values, int num_phases,
                                    const PhaseValuesOptions& options) {
  check_top_k(options.top_k, options.source);
  if (num_phases < 1) throw InvalidInput(located(options.source, cat("has ", num_phases, " phases; meshing needs 2 or more")));
  check_grid(grid, values.size(), size_t(num_phases), options.source, "the array");
  const auto fill = [&](int64_t n, std::span<float> out) {
    std::transform(values.begin() + ptrdiff_t(size_t(n) * out.size()), values.begin() + ptrdiff_t(size_t(n + 1) * out.size()),
                   out.begin(), [](double v) { return float(v); });
  };
  return detail::phase_values_scene(grid, num_phases, fill, options.names, options.labels, options.top_k,
                                    options.source);
}

Scene scene_from_labels(const GridSpec& grid, std::span<const int32_t> labels, const InputOptions& options,
                        const std::string& source) {
  detail::check_input_options(options);
  check_grid(grid, labels.size(), 1, source, "the label array");
  io::Volume v;
  v.size = grid.nodes();
  v.spacing = grid.spacing();
  v.origin = grid.domain.min;
  v.integer = true;
  v.labels.assign(labels.begin(), labels.end());
  return detail::label_volume_scene(std::move(v), options, source);
}

Scene scene_from_points(std::span<const Vec3> points, std::span<const int32_t> labels, const std::string& source) {
  return detail::point_cloud_scene(
      detail::LabelledPoints{{points.begin(), points.end()}, {labels.begin(), labels.end()}}, source);
}

} // namespace vm
