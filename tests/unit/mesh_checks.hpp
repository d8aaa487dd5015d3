#pragma once
/// @file mesh_checks.hpp
/// Orientation checks of improved meshes, shared by the improvement tests and
/// the property tests (tests/property).

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <algorithm>
#include <vector>

namespace vm::test {

/// Triangles whose normal does not point from their first phase into their second
/// (grad (phi_q - phi_p) at the centroid), among those where that direction is clear
/// (|grad (phi_q - phi_p)| > 0.1). Meaningful for closed-form fields only: a
/// sampled field's gradient is that of its interpolant, not of the lattice's.
inline size_t inverted_triangles(const NodeMesh& m, const PhaseField& f) {
  size_t bad = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const auto& tri = m.triangles[t];
    const Vec3 &a = m.points[size_t(tri[0])], &b = m.points[size_t(tri[1])], &c = m.points[size_t(tri[2])];
    const Vec3 centroid = (a + b + c) / 3;
    const Vec3 dir = f.gradient(m.pairs[t][1], centroid) - f.gradient(m.pairs[t][0], centroid);
    const Vec3 n = (b - a).cross(c - a);
    if (dir.norm() > 0.1 && n.normalized().dot(dir.normalized()) <= 0) ++bad;
  }
  return bad;
}

/// Nodes that lie outside the mesh's domain box by more than the tolerance of
/// its faces (1e-9 of the diagonal, InterfaceMesh::box_faces()): the lattice's
/// nodes on a face can stand an ulp out.
inline size_t nodes_outside_the_domain(const NodeMesh& m) {
  const double tol = 1e-9 * (m.domain.max - m.domain.min).norm();
  return size_t(std::count_if(m.points.begin(), m.points.end(), [&](const Vec3& p) {
    return (p.array() < m.domain.min.array() - tol).any() || (p.array() > m.domain.max.array() + tol).any();
  }));
}

/// Normals of every face of the mesh, by face index (valid to follow faces
/// across passes that do not change the topology).
inline std::vector<Vec3> face_normals(const InterfaceMesh& m) {
  const NodeMesh n = m.to_node_mesh();
  std::vector<Vec3> out;
  for (const auto& t : n.triangles)
    out.push_back((n.points[size_t(t[1])] - n.points[size_t(t[0])]).cross(n.points[size_t(t[2])] - n.points[size_t(t[0])]));
  return out;
}

/// Faces whose normal turned by 90 degrees or more between `before` and
/// `after` (same faces, same order): the inversions clamping rules out.
inline size_t turned_faces(const std::vector<Vec3>& before, const std::vector<Vec3>& after) {
  size_t turned = 0;
  for (size_t f = 0; f < after.size() && f < before.size(); ++f) turned += after[f].dot(before[f]) <= 0;
  return turned;
}

} // namespace vm::test
