#pragma once
/// @file core/scale_limits.hpp
/// The sizes voronoimesh works at, one pair for every input (a scene's domain,
/// a volume's voxels, any grid) and every mesh read from a file.
///
/// Squared lengths and areas in doubles would allow far more, but the crossing
/// index files triangle boxes in single precision (check/crossing_index.hpp),
/// whose normal range ends at 1.2e-38 and 3.4e38: a mesh 1e-45 across took 8 s
/// to improve instead of 0.07 (its boxes, rounded to the smallest floats, each
/// covered millions of cells), one 1e-60 across never finished, and a label
/// volume of 1e40 voxels gave NaN phase values. Thirty orders of magnitude
/// either side of 1 leave every physical unit room (nanometres in metres,
/// light years in millimetres).

namespace vm::detail {

/// The farthest a coordinate may lie from the origin.
constexpr double kFarthestCoordinate = 1e30;
/// The least a mesh may span, or a grid cell or voxel measure.
constexpr double kFinestLength = 1e-30;

} // namespace vm::detail
