#pragma once
/// @file check/triangle_pair.hpp
/// Whether two triangles of a node-level mesh intersect improperly, decided
/// exactly (the definition is find_self_intersections' in check/intersections.hpp:
/// a common point outside the hull of the nodes they share, nodes compared by id).

#include "voronoimesh/core/types.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace vm::detail {

using Triangle = std::array<int32_t, 3>;

/// Sign of the turn a, b, c seen with coordinate k dropped (the cyclic order
/// of the others kept, so it is the sign of component k of the normal of abc),
/// decided exactly: +1 counterclockwise, -1 clockwise, 0 collinear.
int orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int k);

/// The coordinate to drop so that the plane of triangle abc projects one to
/// one (its largest normal component, decided exactly); -1 when a, b, c are collinear.
int8_t projection_axis(const Vec3& a, const Vec3& b, const Vec3& c);

/// Triangles a and b (node ids into `points`) intersect improperly; `a_axis`
/// and `b_axis` are their projection_axis(), for callers that test a triangle
/// many times.
bool intersect_improperly(std::span<const Vec3> points, const Triangle& a, const Triangle& b, int8_t a_axis,
                          int8_t b_axis);
/// The same, finding the axes itself.
bool intersect_improperly(std::span<const Vec3> points, const Triangle& a, const Triangle& b);

} // namespace vm::detail
