#pragma once
/// @file fields/voxel_grid.hpp
/// The grids gridded inputs (label volumes, distance grids, a scene's "grid"
/// phases) are stored and meshed on, in one place so they cannot drift apart.

#include "voronoimesh/core/types.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace vm::detail {

/// The grid whose nodes are the centres of `size` voxels of `spacing`, voxel
/// (0, 0, 0) at `origin`. Throws InvalidInput naming `source` when an axis has
/// fewer than 2 voxels (no cell to interpolate in); `what` names the input in
/// that message ("a label volume").
GridSpec voxel_grid(const std::array<int64_t, 3>& size, const Vec3& spacing, const Vec3& origin,
                    const std::string& source, const std::string& what);

/// `voxel_grid` as a scene's grid: one more cell along an axis with an odd
/// count, so the bcc lattice (even cells) keeps the voxel centres as nodes; the
/// field extends constantly over that cell. Throws InvalidInput naming
/// `source` beyond 4096 cells along an axis.
GridSpec even_scene_grid(const GridSpec& voxel_grid, const std::string& source);

/// The scene grid of a volume with voxel grid `voxel_grid`: even_scene_grid
/// when `voxels_per_cell` is 1, else the same box cut into an even number of
/// cells per axis (the bcc lattice needs it), each about `voxels_per_cell`
/// times the smallest spacing long.
GridSpec volume_scene_grid(const GridSpec& voxel_grid, double voxels_per_cell, const std::string& source);

} // namespace vm::detail
