#pragma once
/// @file random_scenes.hpp
/// Random scenes for the property tests: case `index` of `seed` is always the
/// same scene and options, on every machine and standard library (the numbers
/// come from std::mt19937_64's raw output, whose sequence the standard fixes,
/// never from std:: distributions, whose algorithms it does not).

#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <cstdint>
#include <string>

namespace vm::test {

/// The kinds of scene, chosen by case index (index % kSceneKinds), so that any
/// run of kSceneKinds consecutive cases covers them all.
enum class SceneKind {
  spheres,      ///< overlapping spheres, some duplicated or tied up to round-off, some crossing the box
  seeds,        ///< Voronoi cells of seed points, half of them on grid nodes (ties at nodes)
  grid_values,  ///< random phase values at the grid nodes (fields/array_input.hpp)
  tied_values,  ///< small integer values at the nodes: exact ties of 2 and more phases, absent phases
  labels,       ///< a random label per grid node, or grains of random seeds (fields/array_input.hpp)
  thin_slabs,   ///< slabs thinner than the grid spacing, any orientation
  vanishing,    ///< phases that never win: constant below another, radius 0, outside the box, sub-cell
  lattice_ties, ///< planes and spheres through grid nodes (values tie exactly at lattice nodes)
};
inline constexpr int kSceneKinds = 8;

/// "spheres", "seeds"...
const char* scene_kind_name(SceneKind kind);

/// One generated case: a scene and the options to mesh it with.
struct RandomCase {
  uint64_t seed = 0;
  uint64_t index = 0;
  SceneKind kind = SceneKind::spheres;
  Scene scene;
  /// grid (kept from the scene: {0,0,0}), lattice, snap (from 0 through 1e-12
  /// to the maximum 0.5), top_k, close; iterations and threads are the checker's.
  MeshOptions options;
  /// The scene as JSON for the CLI (`voronoimesh mesh scene.json`), for the
  /// closed-form kinds; empty for array scenes.
  std::string scene_json;
  /// True when the phases are closed forms whose gradients give each surface's
  /// direction (not sampled data), so triangle orientation can be checked against them.
  bool closed_form = false;
  /// A label case read voxel-faithful (random_case()).
  bool voxel_faithful = false;
  /// One line: kind, domain, grid, lattice, snap, top_k, close, phases.
  std::string description() const;
};

/// Case `index` of `seed`. With `voxel_faithful`, a label case reads its
/// labels voxel-faithful (InputOptions::voxel_faithful: kept points the passes
/// must not carry out of their phase); the other kinds are as without.
RandomCase random_case(uint64_t seed, uint64_t index, bool voxel_faithful = false);

} // namespace vm::test
