#pragma once
/// @file fields/scene.hpp
/// Scenes read from JSON: phase functions in closed form or from distance-grid
/// files (format: docs/scenes.md).

#include "voronoimesh/core/types.hpp"
#include "voronoimesh/fields/phase_field.hpp"

#include <memory>
#include <string>
#include <vector>

namespace vm {

/// A closed-form scene: the domain and background grid, and the phase functions.
struct Scene {
  GridSpec grid;                           ///< the domain and the default background grid
  std::shared_ptr<const PhaseField> field; ///< the phase functions (shared: scenes are cheap to copy)
  /// The grid is the input's own voxel grid (a label volume), not one chosen to
  /// resolve its surfaces: a run's default pipeline then coarsens the mesh
  /// toward the size of its features (run/meshing.hpp, pipeline_for()).
  bool voxel_grid = false;
  /// For a label volume, the voxels of each phase (by phase id), so that a phase
  /// the mesh loses can be named with its size; empty otherwise.
  std::vector<int64_t> phase_voxels = {};
  /// For a label volume, the phase that each phase of at most 100,000 voxels
  /// touches most across its voxels' faces (by phase id; -1 for larger
  /// phases, or one touching none): the phase that takes its place when the
  /// mesh loses it, for the line naming it. Empty otherwise.
  std::vector<int32_t> phase_around = {};
  /// What reading the input resolved that a user should hear of (segments
  /// with no voxels, overlapping segments), one line each.
  std::vector<std::string> notes = {};
  /// For a volume, the frame of the coordinates: "LPS" or "RAS", and whether
  /// the file's or converted (InputOptions::world); empty for other inputs.
  std::string world = {};
  /// A label volume read with InputOptions::voxel_faithful, on its voxel grid,
  /// with a label the bcc lattice (every second node) would lose more than 1%
  /// of: structures one voxel thin along an axis where the lattice has no node.
  /// create then takes every grid node (the cube6 lattice) unless a lattice is
  /// given (run/meshing.hpp, lattice_for()). Always false without voxel_faithful.
  bool needs_every_grid_node = false;
};

/// Parses a scene from JSON text (format: docs/scenes.md).
/// @param json_text the scene as JSON
/// @param source    names the text in error messages (usually the file name); the files of "grid" phases
///                  are found relative to its folder (the working directory if it has none)
/// @return the scene
/// @throws InvalidInput with a one-line message naming `source` and the problem (malformed JSON, unknown
///         phase kind, grid out of range [1, 4096], fewer than two phases, a bad expression, grid phase
///         files on different grids...)
/// @throws IoError if a grid phase's file cannot be read
Scene parse_scene(const std::string& json_text, const std::string& source);

/// Reads and parses a scene file (parse_scene() with the path as source).
/// @param path the scene file (JSON)
/// @return the scene
/// @throws IoError      if it (or a grid phase's file) cannot be read
/// @throws InvalidInput as parse_scene()
Scene load_scene(const std::string& path);

/// The built-in demo: the paper's four overlapping spheres (5 phases, 10
/// surfaces, 10 triple curves, 5 quadruple points) at grid 64.
/// @return the demo scene, on the unit cube
Scene demo_scene();

} // namespace vm
