#pragma once
/// @file fields/voxel_grid.hpp
/// The grids gridded inputs (label volumes, distance grids, a scene's "grid"
/// phases) are stored and meshed on, in one place so they cannot drift apart.

#include "voronoimesh/core/types.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vm::detail {

/// Throws InvalidInput naming `source` unless every axis of `grid` spans a
/// finite interval within kFarthestCoordinate of 0 whose cells are at least
/// kFinestLength (core/scale_limits.hpp) and resolved by doubles where they
/// lie: at least 2^-40 of the largest coordinate, so that a cell holds
/// thousands of distinct positions. Beyond that, voxel centres coincide in
/// floating point and create divides by zero (a NRRD whose origin was 1e20,
/// with 1 mm voxels, crashed).
void require_resolvable(const GridSpec& grid, const std::string& source);

/// The grid whose nodes are the centres of `size` voxels of `spacing`, voxel
/// (0, 0, 0) at `origin`. Throws InvalidInput naming `source` when an axis has
/// fewer than 2 voxels (no cell to interpolate in; `what` names the input in
/// that message, "a label volume") or as require_resolvable().
GridSpec voxel_grid(const std::array<int64_t, 3>& size, const Vec3& spacing, const Vec3& origin,
                    const std::string& source, const std::string& what);

/// `voxel_grid` as a scene's grid: one more cell along an axis with an odd
/// count, so the bcc lattice (even cells) keeps the voxel centres as nodes; the
/// field extends constantly over that cell. Throws InvalidInput naming
/// `source` beyond 4096 cells along an axis.
GridSpec even_scene_grid(const GridSpec& voxel_grid, const std::string& source);

/// Voxels whose longest side is more than this many times their shortest are
/// flat: the default grid of their volume has cubic cells instead (below).
constexpr double kFlatVoxels = 1.2;

/// The cells, in voxels of the smallest spacing, that InputOptions::voxels_per_cell
/// asks for: itself when given; for 0 (the default) 1, the voxel grid, unless
/// the voxels are flat (kFlatVoxels), as CT and MR slices thicker than their
/// pixels are: then cubes of the voxels' volume, about as many cells as voxels.
/// The bcc lattice on flat cells cuts the interfaces into slivers, which the
/// improvement must then mend: on CGAL's liver (0.617 x 0.617 x 1.333 mm) the
/// cubic cells took the default run from 6.3 to 4.7 s and min q from 0.35 to
/// 0.42, with the same share of voxel centres in their label (docs/inputs.md).
double resolved_voxels_per_cell(double voxels_per_cell, const Vec3& spacing);

/// The scene grid of a volume with voxel grid `voxel_grid`: even_scene_grid
/// when resolved_voxels_per_cell() is 1, else the same box cut into an even number of
/// cells per axis (the bcc lattice needs it), each about that many times the
/// smallest spacing long. When the default made the cells cubic, a line
/// saying so goes to `notes`.
GridSpec volume_scene_grid(const GridSpec& voxel_grid, double voxels_per_cell, const std::string& source,
                           std::vector<std::string>& notes);

} // namespace vm::detail
