#include "fields/grid_phases.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/text.hpp"
#include "fields/axis_align.hpp"
#include "fields/top_k_grid_field.hpp"
#include "fields/voxel_grid.hpp"

#include <cmath>
#include <filesystem>

namespace vm::detail {

namespace {

/// One component of a file, kept in a one-phase TopKGridField: its trilinear
/// values and gradients are exactly those a multi-component file of the same
/// data gives (load_input), so both ways of writing a simulation mesh alike.
class GridPhase final : public PhaseFunction {
public:
  explicit GridPhase(std::shared_ptr<const TopKGridField> field) : field_(std::move(field)) {}
  double value(const Vec3& x) const override { return field_->value(0, x); }
  Vec3 gradient(const Vec3& x) const override { return field_->gradient(0, x); }

private:
  std::shared_ptr<const TopKGridField> field_;
};

bool is_grid_phase(const nlohmann::json& phase) {
  return phase.is_object() && phase.contains("kind") && phase["kind"] == "grid";
}

std::string vec(const Vec3& v) { return cat("[", v.x(), ", ", v.y(), ", ", v.z(), "]"); }

/// How the voxels of `b` differ from those of `a` ("" if they agree). Spacing and
/// origin within a millionth of a voxel, since headers print them rounded.
std::string grid_difference(const io::Volume& a, const io::Volume& b) {
  if (a.size != b.size)
    return cat("sizes ", b.size[0], "x", b.size[1], "x", b.size[2], " vs ", a.size[0], "x", a.size[1], "x", a.size[2]);
  const double tol = 1e-6 * a.spacing.minCoeff();
  if ((a.spacing - b.spacing).cwiseAbs().maxCoeff() > tol) return cat("spacing ", vec(b.spacing), " vs ", vec(a.spacing));
  if ((a.origin - b.origin).cwiseAbs().maxCoeff() > tol)
    return cat("origin ", vec(b.origin), " vs ", vec(a.origin), " (after applying each file's direction)");
  return "";
}

} // namespace

GridFiles::GridFiles(const JsonObject& scene) {
  folder_ = std::filesystem::path(scene.source()).parent_path().string();
  if (!scene.has("phases") || !scene.at("phases").is_array()) return; // reported by the phase reader
  const nlohmann::json& list = scene.at("phases");
  std::string first; // "'file' (phase i)", the grid the others must match
  const io::Volume* reference = nullptr;
  for (size_t i = 0; i < list.size(); ++i) {
    if (!is_grid_phase(list[i])) continue;
    const JsonObject phase(list[i], scene.source(), cat("phase ", i));
    const std::string path = path_of(phase);
    if (files_.contains(path)) continue;
    io::Volume v;
    try {
      v = io::read_volume(path);
      // No --ignore-direction in scenes: an oblique file is refused.
      axis_align(v, path, false);
    } catch (const IoError& e) {
      throw IoError(located(scene.source(), cat("phase ", i, ": ", e.what())));
    } catch (const Error& e) {
      phase.fail(e.what());
    }
    if (v.integer)
      phase.fail(cat("'", phase.string("file"), "' holds integers (a label volume?); a grid phase needs real values"));
    if (!reference) {
      grid_ = voxel_grid(v.size, v.spacing, v.origin, path, "a grid phase's file");
      first = cat("'", phase.string("file"), "' (phase ", i, ")");
    } else if (const std::string d = grid_difference(*reference, v); !d.empty()) {
      phase.fail(cat("'", phase.string("file"), "' is not on the grid of ", first, ": ", d,
                     "; all grid phases must share one voxel grid"));
    }
    const io::Volume& kept = files_.emplace(path, std::move(v)).first->second;
    if (!reference) reference = &kept;
  }
}

std::string GridFiles::path_of(const JsonObject& phase) const {
  phase.allow_only({"kind", "name", "file", "component"});
  const std::filesystem::path file = phase.string("file");
  if (file.empty()) phase.fail("'file' must not be empty");
  return file.is_absolute() ? file.string() : (std::filesystem::path(folder_) / file).string();
}

void GridFiles::check_domain(const JsonObject& where, const Box& box) const {
  const Vec3 half = grid_.spacing() / 2;
  const Vec3 lo = grid_.domain.min - half, hi = grid_.domain.max + half;
  const double tol = 1e-6 * grid_.spacing().minCoeff();
  for (int a = 0; a < 3; ++a)
    if (box.min[a] < lo[a] - tol || box.max[a] > hi[a] + tol)
      where.fail(cat("reaches beyond the voxels of the grid phases along ", std::string(1, "xyz"[a]), " (they cover ",
                     vec(lo), " to ", vec(hi), "); give a domain inside them, or none to mesh all of them"));
}

std::unique_ptr<const PhaseFunction> GridFiles::read_phase(const JsonObject& phase) const {
  const io::Volume& v = files_.at(path_of(phase));
  int component = 0;
  if (phase.has("component")) {
    const double c = phase.number("component");
    if (c != std::floor(c) || c < 0 || c >= v.components)
      phase.fail(cat("'component' ", brief(phase.at("component")), " is out of range: '", phase.string("file"), "' has ",
                     v.components, " component(s), 0 to ", v.components - 1));
    component = int(c);
  }
  auto field = std::make_shared<TopKGridField>(grid_, 1, std::vector<std::string>{"grid"}, std::vector<int32_t>{});
  const size_t stride = size_t(v.components);
  for (int64_t n = 0; n < v.voxel_count(); ++n) field->offer(n, 0, v.values[size_t(n) * stride + size_t(component)]);
  field->finish(0.f); // every node was offered its one phase: nothing to pad
  return std::make_unique<GridPhase>(std::move(field));
}

} // namespace vm::detail
