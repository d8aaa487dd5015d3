#pragma once
/// @file fields/point_cloud.hpp
/// Labelled point clouds (paper sect. 5, eq. 7): phi_i(x) = minus the distance
/// from x to the nearest point labelled i.

#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/fields/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace vm::detail {

/// True for the extensions of point files: .xyz, .txt, .pts, .csv, .ply.
bool is_point_file(const std::string& path);

/// Points and the label of each, as a point file holds them.
struct LabelledPoints {
  std::vector<Vec3> points;
  std::vector<int32_t> labels;
};

/// Reads a PLY point cloud (ply_points.cpp): the vertex element's scalar
/// properties x, y, z and label (or, failing that, phase or region), which
/// must hold 32-bit integer values in any type; other elements and properties
/// are skipped. Throws IoError for a broken PLY, InvalidInput for a missing
/// property, a non-integer label or a non-finite coordinate.
LabelledPoints read_ply_points(const std::string& path);

/// Reads a point file, .ply as read_ply_points, any other as text, one point
/// per line "x y z label" (whitespace or commas between; '#' starts a comment;
/// a .csv file may start with a header row), and builds its scene: one phase per label, ordered by label; the
/// domain is the points' bounding box grown by 5% of its largest side on every
/// side, the grid 64 cells along the longest side and as many of that size as
/// fit along the others. Throws InvalidInput naming the file (and line) for no
/// points, fewer than 2 or more than kMaxPhases labels, a label outside int32
/// or a non-finite coordinate.
Scene point_cloud_scene(const std::string& path, const InputOptions& options);

/// The scene of points already in memory, as point_cloud_scene(path) builds it;
/// `source` names them in errors. Also throws InvalidInput when the points and
/// labels differ in number, or a coordinate is not finite (naming the point).
Scene point_cloud_scene(LabelledPoints cloud, const std::string& source);

} // namespace vm::detail
