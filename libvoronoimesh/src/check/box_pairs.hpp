#pragma once
/// @file check/box_pairs.hpp
/// Candidate pairs for intersection tests: every pair of overlapping
/// axis-aligned boxes, found through a multi-level uniform grid in time linear
/// in the boxes and the pairs (boxes of very different sizes included).

#include "voronoimesh/core/types.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <span>

namespace vm::detail {

/// A closed axis-aligned box.
struct Bounds {
  Vec3 lo, hi;
  bool overlaps(const Bounds& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

/// The bounding box of triangle `tri` (node ids into `points`).
inline Bounds triangle_bounds(std::span<const Vec3> points, const std::array<int32_t, 3>& tri) {
  const Vec3 &a = points[size_t(tri[0])], &b = points[size_t(tri[1])], &c = points[size_t(tri[2])];
  return {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

/// Indices {i, j}, i < j, of two boxes.
using BoxPair = std::array<int32_t, 2>;

/// Every pair of boxes that overlap (touching included), each once, handed to
/// `visit` a few thousand at a time as they are found, from several threads at
/// once (`visit` must be safe to call so), in an order that depends on the
/// thread count (callers must not depend on it). Boxes must be finite. With
/// `involved` (one flag per box; empty: all boxes), only the pairs with at
/// least one involved box: checking a few moved triangles against the rest
/// then costs little more than finding their neighbours. No list of them all
/// is made: where each pair is looked at once (a check), that spares it (on
/// 1.7M triangles after the remesh pass's splits, 8.3M pairs, 66 MB written to
/// fresh memory and read back); a caller that keeps some keeps only those.
void for_each_overlapping_box_pair(std::span<const Bounds> boxes, std::span<const uint8_t> involved,
                                   const std::function<void(std::span<const BoxPair>)>& visit);

} // namespace vm::detail
