#pragma once
/// @file mesh/triangle_quality.hpp
/// The shape measure every pass and report judges triangles by.

#include "voronoimesh/core/types.hpp"

namespace vm {

/// Triangle quality q = 4 sqrt(3) area / (sum of squared edge lengths); 1 for an
/// equilateral triangle, 0 for a degenerate one (paper sect. 4.3). Bit for bit
/// the same for any order of the corners.
/// @param a first corner
/// @param b second corner
/// @param c third corner
/// @return q in [0, 1]; 0 also when a coordinate is not finite
double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c);

} // namespace vm
