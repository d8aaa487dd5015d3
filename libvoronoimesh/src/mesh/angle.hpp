#pragma once
/// @file mesh/angle.hpp
/// The angle between two edges, as the statistics, the quality history and the
/// surface corners report it.

#include "voronoimesh/core/types.hpp"

#include <cmath>
#include <numbers>

namespace vm::detail {

/// The angle between `u` and `v` in degrees, in [0, 180]; atan2 of the cross
/// and dot products, accurate for angles near 0 and 180 where acos is not.
inline double angle_deg(const Vec3& u, const Vec3& v) {
  return std::atan2(u.cross(v).norm(), u.dot(v)) * (180.0 / std::numbers::pi);
}

} // namespace vm::detail
