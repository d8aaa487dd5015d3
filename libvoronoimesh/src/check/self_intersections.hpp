#pragma once
/// @file check/self_intersections.hpp
/// find_self_intersections() (voronoimesh/check/intersections.hpp) on a mesh
/// whose arrays are held elsewhere: the crossing guard keeps the mesh's
/// positions and triangles, and copying them into a NodeMesh for each check
/// (36 MB on 1M triangles) was a serial pass over fresh memory.

#include "voronoimesh/check/intersections.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace vm::detail {

/// A node-level mesh's arrays, as in NodeMesh (`pairs` may be empty).
struct MeshArrays {
  std::span<const Vec3> points;
  std::span<const std::array<int32_t, 3>> triangles;
  std::span<const PhasePair> pairs;
};

/// find_self_intersections() of the mesh `m`.
IntersectionReport find_self_intersections(const MeshArrays& m, size_t max_reported, std::span<const uint8_t> involved,
                                           bool across_surfaces_only);

} // namespace vm::detail
