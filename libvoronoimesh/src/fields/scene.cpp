#include "voronoimesh/fields/scene.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/input_file.hpp"
#include "core/json_object.hpp"
#include "core/scale_limits.hpp"
#include "core/text.hpp"
#include "fields/phase_function.hpp"
#include "fields/phase_reader.hpp"
#include "fields/voxel_grid.hpp"

#include <cmath>
#include <map>

namespace vm {

namespace {

using detail::brief;
using detail::JsonObject;
using nlohmann::json;

/// Largest grid a scene may ask for: 4096^3 nodes is already far beyond memory.
constexpr int max_grid_cells = 4096;

int grid_cells(const JsonObject& scene, const json& v, const std::string& what) {
  if (v.is_number()) {
    const double d = v.get<double>();
    if (d >= 1 && d <= max_grid_cells && d == std::floor(d)) return int(d);
  }
  scene.fail(what + " must be an integer in [1, " + std::to_string(max_grid_cells) +
             "] (cells per axis), got " + brief(v));
}

std::array<int, 3> read_grid(const JsonObject& scene) {
  const json& g = scene.at("grid");
  if (!g.is_array()) {
    const int n = grid_cells(scene, g, "grid");
    return {n, n, n};
  }
  if (g.size() != 3)
    scene.fail("grid must be an integer or an array of 3 integers, got " + brief(g));
  std::array<int, 3> cells{};
  for (size_t a = 0; a < 3; ++a) cells[a] = grid_cells(scene, g[a], "grid[" + std::to_string(a) + "]");
  return cells;
}

Box read_domain(const JsonObject& domain) {
  domain.allow_only({"min", "max"});
  Box box{domain.vec3("min"), domain.vec3("max")};
  for (int a = 0; a < 3; ++a)
    if (!(box.min[a] < box.max[a]))
      domain.fail("'min' must be below 'max' on every axis, not on axis " + std::string(1, "xyz"[a]));
  // As every input's grid (core/scale_limits.hpp), said here with the scene's line.
  constexpr double largest = detail::kFarthestCoordinate;
  if (box.min.cwiseAbs().maxCoeff() > largest || box.max.cwiseAbs().maxCoeff() > largest)
    domain.fail(detail::cat("must lie within -", largest, " and ", largest, " on every axis"));
  return box;
}

/// The phase's display name: its "name", or "phase<i>".
std::string phase_name(const JsonObject& phase, size_t i) {
  if (!phase.has("name")) return "phase" + std::to_string(i);
  std::string name = phase.string("name");
  if (name.empty()) phase.fail("'name' must not be empty");
  return name;
}

std::shared_ptr<const PhaseField> read_phases(const JsonObject& scene, const detail::PhaseContext& context) {
  const json& list = scene.at("phases");
  if (!list.is_array()) scene.fail("'phases' must be an array of phase objects, got " + brief(list));
  if (list.size() < 2)
    scene.fail("a scene needs at least two phases, got " + std::to_string(list.size()));
  if (list.size() > kMaxPhases)
    scene.fail("too many phases (" + std::to_string(list.size()) + "; at most " +
               std::to_string(kMaxPhases) + ")");
  auto field = std::make_shared<detail::CompositeField>(scene.source());
  std::map<std::string, size_t> used; // names are how outputs tell phases apart
  for (size_t i = 0; i < list.size(); ++i) {
    const JsonObject phase(list[i], scene.source(), "phase " + std::to_string(i));
    std::string name = phase_name(phase, i);
    if (auto [it, fresh] = used.emplace(name, i); !fresh)
      phase.fail("name '" + name + "' is already used by phase " + std::to_string(it->second));
    field->add(std::move(name), detail::read_phase(phase, context));
  }
  return field;
}

/// examples/four_spheres.json, word for word (a unit test holds them together).
constexpr const char* four_spheres_json = R"({
  "description": "The paper's Fig. 3: four overlapping spheres and the outside; 10 surfaces, 10 triple curves, 5 quadruple points.",
  "domain": {"min": [0, 0, 0], "max": [1, 1, 1]},
  "grid": 64,
  "phases": [
    {"name": "outside", "kind": "constant", "value": 0},
    {"name": "sphere1", "kind": "sphere", "center": [0.6181, 0.5991, 0.6101], "radius": 0.222},
    {"name": "sphere2", "kind": "sphere", "center": [0.6001, 0.4039, 0.3859], "radius": 0.205},
    {"name": "sphere3", "kind": "sphere", "center": [0.3989, 0.6121, 0.4049], "radius": 0.229},
    {"name": "sphere4", "kind": "sphere", "center": [0.3849, 0.3899, 0.6001], "radius": 0.212}
  ]
}
)";

} // namespace

Scene parse_scene(const std::string& json_text, const std::string& source) {
  const json root = detail::parse_json(json_text, source);
  const JsonObject scene(root, source, "");
  scene.allow_only({"description", "domain", "grid", "phases"});
  if (scene.has("description")) scene.string("description"); // checks that it is text

  Scene out;
  // Grid phases first: without a "domain" the scene meshes their voxels, on
  // the voxel grid, as load_input does for a multi-component file.
  const detail::GridFiles grids(scene);
  if (scene.has("domain")) {
    const JsonObject domain = scene.object("domain");
    out.grid.domain = read_domain(domain);
    if (!grids.empty()) grids.check_domain(domain, out.grid.domain);
  } else if (!grids.empty()) {
    out.grid = detail::even_scene_grid(grids.grid(), source);
  }
  if (scene.has("grid")) out.grid.cells = read_grid(scene);
  out.field = read_phases(scene, {out.grid.domain, grids});
  return out;
}

/// A scene is small: grid data lives in files of its own.
constexpr uint64_t kMaxSceneBytes = uint64_t(64) << 20;

Scene load_scene(const std::string& path) {
  return parse_scene(detail::read_text_file(path, kMaxSceneBytes, "a scene"), path);
}

Scene demo_scene() { return parse_scene(four_spheres_json, "demo scene"); }

} // namespace vm
