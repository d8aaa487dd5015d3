#pragma once
/// @file improve/field_orientation.hpp
/// Whether a triangle faces the way its phase pair says (used by the crossing
/// guard and the flip guard).

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <cstddef>

namespace vm::detail {

/// False when triangle t's normal points against the direction from its first
/// phase into its second (grad phi_second - grad phi_first at its centroid),
/// where that direction is clear (a gradient difference above 0.1).
inline bool agrees_with_field(const NodeMesh& m, size_t t, const PhaseField& field) {
  const auto& tri = m.triangles[t];
  const Vec3 &a = m.points[size_t(tri[0])], &b = m.points[size_t(tri[1])], &c = m.points[size_t(tri[2])];
  const Vec3 centroid = (a + b + c) / 3;
  const Vec3 dir = field.gradient(m.pairs[t][1], centroid) - field.gradient(m.pairs[t][0], centroid);
  if (dir.norm() <= 0.1) return true;
  return (b - a).cross(c - a).dot(dir) > 0;
}

/// True when triangle t has a corner on a junction (3 or more phases): the
/// triangles seen to stand across their surface without inverting (slivers at
/// close quadruple points); elsewhere projection holds triangles on their surface.
inline bool touches_junction(const InterfaceMesh& mesh, const NodeMesh& m, size_t t) {
  for (int32_t v : m.triangles[t])
    if (phase_count(mesh.phases()[size_t(v)]) >= 3) return true;
  return false;
}

} // namespace vm::detail
