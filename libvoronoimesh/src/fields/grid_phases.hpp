#pragma once
/// @file fields/grid_phases.hpp
/// A scene's "grid" phases (docs/scenes.md): phi is one component of a
/// distance-grid file, one file per phase as level-set simulations write them.

#include "voronoimesh/io/volume.hpp"

#include "core/json_object.hpp"
#include "fields/phase_function.hpp"

#include <map>
#include <memory>
#include <string>

namespace vm::detail {

/// The files of every "grid" phase of one scene, each read once, all on one
/// voxel grid. Read before the other phases, since a scene without "domain"
/// takes its domain from them (and expressions their step from the domain).
class GridFiles {
public:
  /// Reads the file of every phase of kind "grid" in the scene's "phases",
  /// relative to the folder of the scene's source. Other mistakes in "phases"
  /// are left to the phase reader. Throws IoError (unreadable file) or
  /// InvalidInput (bad keys, not a real volume, grids that differ), one line
  /// "<scene>: phase <i>: ...".
  explicit GridFiles(const JsonObject& scene);

  bool empty() const { return files_.empty(); }
  /// The grid whose nodes are the shared voxel centres (precondition: !empty()).
  const GridSpec& grid() const { return grid_; }
  /// Throws InvalidInput at `where` when `box` reaches beyond the voxels
  /// (voxel centres +- half a voxel), where the files hold no values.
  void check_domain(const JsonObject& where, const Box& box) const;
  /// The phase function of grid phase `phase`: the chosen component,
  /// interpolated trilinearly between voxel centres. Throws InvalidInput for a
  /// component out of range.
  std::unique_ptr<const PhaseFunction> read_phase(const JsonObject& phase) const;

private:
  std::string path_of(const JsonObject& phase) const;

  std::string folder_;
  std::map<std::string, io::Volume> files_; ///< by resolved path
  GridSpec grid_;
};

} // namespace vm::detail
