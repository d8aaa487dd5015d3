#pragma once
/// @file detail/point_cloud.hpp
/// Labelled point clouds (paper sect. 5, eq. 7): phi_i(x) = minus the distance
/// from x to the nearest point labelled i.

#include "voronoimesh/input.hpp"
#include "voronoimesh/scene.hpp"

#include <string>

namespace vm::detail {

/// True for the extensions of point files: .xyz, .txt, .pts, .csv.
bool is_point_file(const std::string& path);

/// Reads a text point file, one point per line "x y z label" (whitespace or
/// commas between; '#' starts a comment; a .csv file may start with a header
/// row), and builds its scene: one phase per label, ordered by label; the
/// domain is the points' bounding box grown by 5% of its largest side on every
/// side, the grid 64 cells along the longest side and as many of that size as
/// fit along the others. Throws InvalidInput naming the file and line.
Scene point_cloud_scene(const std::string& path, const InputOptions& options);

} // namespace vm::detail
