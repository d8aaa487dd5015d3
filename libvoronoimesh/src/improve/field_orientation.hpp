#pragma once
/// @file improve/field_orientation.hpp
/// Whether a triangle faces the way its phase pair says (used by the crossing
/// guard and the flip guard).

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace vm::detail {

/// False when triangle `tri`'s normal points against the direction from its first
/// phase into its second (grad phi_second - grad phi_first at its centroid),
/// where that direction is clear (a gradient difference above 0.1).
inline bool agrees_with_field(std::span<const Vec3> points, const std::array<int32_t, 3>& tri, const PhasePair& pair,
                              const PhaseField& field) {
  const Vec3 &a = points[size_t(tri[0])], &b = points[size_t(tri[1])], &c = points[size_t(tri[2])];
  const Vec3 centroid = (a + b + c) / 3;
  const Vec3 dir = field.gradient(pair[1], centroid) - field.gradient(pair[0], centroid);
  if (dir.norm() <= 0.1) return true;
  return (b - a).cross(c - a).dot(dir) > 0;
}

/// True when triangle `tri` has a corner on a junction (3 or more phases): the
/// triangles seen to stand across their surface without inverting (slivers at
/// close quadruple points); elsewhere projection holds triangles on their surface.
inline bool touches_junction(const InterfaceMesh& mesh, const std::array<int32_t, 3>& tri) {
  for (int32_t v : tri)
    if (phase_count(mesh.phases()[size_t(v)]) >= 3) return true;
  return false;
}

} // namespace vm::detail
