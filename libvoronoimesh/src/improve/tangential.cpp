/// @file improve/tangential.cpp
/// Moves kept on a node's surface, curve and box faces (improve/tangential.hpp).

#include "improve/tangential.hpp"

#include <array>

namespace vm::detail {

bool keep_tangential(const InterfaceMesh& mesh, const PhaseField& field, int32_t n, const Vec3& x, Vec3& move) {
  const PhaseSet& phases = mesh.phases()[size_t(n)];
  const size_t count_of_phases = size_t(phase_count(phases));
  const uint8_t box_faces = mesh.box_faces()[size_t(n)];
  std::array<Vec3, 5> normals;
  size_t count = 0;
  if (count_of_phases >= 2) {
    const Vec3 g0 = field.gradient(phases[0], x);
    for (size_t i = 1; i < count_of_phases && count < 2; ++i) normals[count++] = g0 - field.gradient(phases[i], x);
  }
  for (int a = 0; a < 3; ++a)
    if (box_faces >> (2 * a) & 3u) normals[count++] = Vec3::Unit(a);
  // Gram-Schmidt: each normal loses its parts along the earlier ones; one that
  // is (almost) in their span adds no constraint.
  for (size_t i = 0; i < count; ++i) {
    Vec3 normal = normals[i];
    if (!normal.allFinite()) return false;
    for (size_t j = 0; j < i; ++j) normal -= normal.dot(normals[j]) * normals[j];
    const double len = normal.norm();
    normals[i] = len > 1e-6 * normals[i].norm() ? Vec3(normal / len) : Vec3::Zero();
    move -= move.dot(normals[i]) * normals[i];
  }
  return true;
}

} // namespace vm::detail
