#pragma once
/// @file mesh/node_rings.hpp
/// The node-level queries of a NodeMesh that edits such as collapses ask
/// (neighbours, triangles at a node, phase sets, box faces), built in
/// O(triangles) without OpenMesh: a batch of edits can be followed by the next
/// on the NodeMesh itself, and the InterfaceMesh rebuilt once at the end. It
/// answers as InterfaceMesh does for the same mesh.

#include "mesh/topology.hpp"

#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// Faces of `domain` each point lies on, as InterfaceMesh::box_faces(): bit 2a
/// for the min side of axis a, bit 2a+1 for the max (within 1e-9 of the box diagonal).
std::vector<uint8_t> box_faces_of(const std::vector<Vec3>& points, const Box& domain);
/// box_faces_of() for one point.
uint8_t box_faces_at(const Vec3& point, const Box& domain);

/// The number of phases and box faces at a node (junction_order() of improve/smooth.hpp).
inline int junction_order(const PhaseSet& phases, uint8_t box_faces) {
  return phase_count(phases) + std::popcount(unsigned(box_faces));
}

/// The number of independent constraints on node n of `mesh` (an InterfaceMesh
/// or a NodeRings): its junction order less one for the outside phase of a
/// closed mesh (whose surfaces are the box faces). 2 on a surface, 3 on a curve
/// (a triple curve, a surface meeting the box, a box edge), more at a corner.
template <class Mesh> int constraint_order(const Mesh& mesh, int32_t n) {
  const int32_t outside = mesh.outside_phase();
  return junction_order(mesh.phases()[size_t(n)], mesh.box_faces()[size_t(n)]) -
         (outside >= 0 && mesh.has_phase(n, outside) ? 1 : 0);
}

/// True when the phases and box faces of a are all among b's (InterfaceMesh::constraints_within()).
bool constraints_within(const PhaseSet& phases_a, uint8_t box_a, const PhaseSet& phases_b, uint8_t box_b);

class NodeRings {
public:
  /// Tables of `m`, which must outlive this and stay unchanged while it is asked.
  explicit NodeRings(const NodeMesh& m);

  size_t num_nodes() const { return m_.num_nodes(); }
  const std::vector<Vec3>& positions() const { return m_.points; }
  /// Neighbouring nodes of n, sorted.
  std::span<const int32_t> neighbours(int32_t n) const {
    return {adj_.data() + adj_off_[size_t(n)], size_t(adj_off_[size_t(n) + 1] - adj_off_[size_t(n)])};
  }
  /// Calls f(a, b) for every triangle at node n, with (n, a, b) in the
  /// triangle's orientation order.
  template <class F> void for_each_triangle_at(int32_t n, F&& f) const {
    for (int32_t t : at_.of(size_t(n))) {
      const auto& tri = m_.triangles[size_t(t)];
      const int k = tri[0] == n ? 0 : tri[1] == n ? 1 : 2;
      f(tri[size_t((k + 1) % 3)], tri[size_t((k + 2) % 3)]);
    }
  }
  /// The triangles at node n, ascending.
  std::span<const int32_t> triangles_at(int32_t n) const { return at_.of(size_t(n)); }
  const std::vector<PhaseSet>& phases() const { return phases_; } ///< phases meeting at each node
  const std::vector<uint8_t>& box_faces() const { return box_; }  ///< as box_faces_of()
  int32_t outside_phase() const { return m_.outside_phase; }      ///< NodeMesh::outside_phase
  const NodeMesh& mesh() const { return m_; }
  /// True when phase p is among node n's phases.
  bool has_phase(int32_t n, int32_t p) const;
  /// True when the edge a-b runs along a curve: its triangles are not exactly two
  /// of one phase pair (a junction, or a surface's edge on the box), or both ends
  /// lie on one edge of the box.
  bool along_curve(int32_t a, int32_t b) const;
  /// True when a's phases and box faces are all among b's.
  bool constraints_within(int32_t a, int32_t b) const {
    return detail::constraints_within(phases_[size_t(a)], box_[size_t(a)], phases_[size_t(b)], box_[size_t(b)]);
  }

private:
  const NodeMesh& m_;
  NodeTriangles at_;
  std::vector<int32_t> adj_off_, adj_;
  std::vector<PhaseSet> phases_;
  std::vector<uint8_t> box_;
};

} // namespace vm::detail
