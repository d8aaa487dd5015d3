#pragma once
/// @file improve/mesh_part.hpp
/// The part of an InterfaceMesh around some nodes, as a NodeMesh of its own:
/// the junction-sliver collapses try and check their merges on it
/// (improve/node_merge.hpp) and make them from it (improve/merges_made.hpp).
/// A NodeMesh of the whole mesh for every call, and one more for every trial,
/// faulted in tens of MB of fresh pages each on 1M triangles
/// (docs/edits-in-place.md, step 4).

#include "voronoimesh/mesh/interface_mesh.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

struct MeshPart {
  /// Every face at the nodes the part was cut at, in the whole mesh's order,
  /// and their corners (to_node_mesh(faces, nodes)); or the whole mesh.
  NodeMesh mesh;
  /// Whether `mesh` is the whole mesh: then `nodes` and `triangles` are empty
  /// and the part's numbers are the whole mesh's.
  bool is_whole = false;
  /// The whole mesh's node of each node of `mesh`, and face of each triangle, ascending.
  std::vector<int32_t> nodes, triangles;
  /// The whole mesh's positions and triangles (InterfaceMesh::triangles(), as
  /// the crossing index saw them).
  std::span<const Vec3> whole_points;
  std::span<const std::array<int32_t, 3>> whole_triangles;

  int32_t whole_node(int32_t n) const { return is_whole ? n : nodes[size_t(n)]; }
  int32_t whole_triangle(int32_t t) const { return is_whole ? t : triangles[size_t(t)]; }
  /// The node of the part that is whole node n, or -1.
  int32_t part_node(int32_t n) const;
};

/// The faces at the nodes `seeds` (any order, repeats allowed) and their corners.
MeshPart part_at(const InterfaceMesh& mesh, std::span<const int32_t> seeds);

/// The whole mesh as a part (to_node_mesh()).
MeshPart whole_part(const InterfaceMesh& mesh);

/// Merges made on a part put back into the whole mesh (where the merged mesh
/// is needed whole: a rebuild).
/// @param part           the part (not the whole mesh), as it was before the merges
/// @param merged         `part.mesh` merged (merge_nodes(): all its nodes kept)
/// @param kept_triangles the triangle of `part.mesh` each triangle of `merged` was
/// @param before         the whole mesh before the merges (to_node_mesh())
/// @param whole          set to `before` merged, all its nodes kept
/// @param whole_kept     set to the triangle of `before` each triangle of `whole` was
void put_back(const MeshPart& part, const NodeMesh& merged, std::span<const int32_t> kept_triangles,
              const NodeMesh& before, NodeMesh& whole, std::vector<int32_t>& whole_kept);

} // namespace vm::detail
