/// @file improve/mesh_part.cpp
/// A part of an InterfaceMesh as a NodeMesh of its own.

#include "improve/mesh_part.hpp"

#include <algorithm>

namespace vm::detail {

int32_t MeshPart::part_node(int32_t n) const {
  if (is_whole) return n;
  const auto at = std::lower_bound(nodes.begin(), nodes.end(), n);
  return at != nodes.end() && *at == n ? int32_t(at - nodes.begin()) : -1;
}

MeshPart part_at(const InterfaceMesh& mesh, std::span<const int32_t> seeds) {
  MeshPart part;
  part.triangles = mesh.faces_at(seeds);
  part.mesh = mesh.to_node_mesh(part.triangles, part.nodes);
  part.whole_points = mesh.positions();
  part.whole_triangles = mesh.triangles();
  return part;
}

MeshPart whole_part(const InterfaceMesh& mesh) {
  MeshPart part;
  part.mesh = mesh.to_node_mesh();
  part.is_whole = true;
  part.whole_points = mesh.positions();
  part.whole_triangles = mesh.triangles();
  return part;
}

void put_back(const MeshPart& part, const NodeMesh& merged, std::span<const int32_t> kept_triangles,
              const NodeMesh& before, NodeMesh& whole, std::vector<int32_t>& whole_kept) {
  whole = before.empty_like();
  whole.points = before.points;
  for (size_t n = 0; n < part.nodes.size(); ++n) whole.points[size_t(part.nodes[n])] = merged.points[n];
  whole_kept.clear();
  // Both the part's triangles and those it kept ascend, as the whole mesh's do.
  size_t in_part = 0, kept = 0;
  for (size_t t = 0; t < before.num_triangles(); ++t) {
    if (in_part == part.triangles.size() || part.triangles[in_part] != int32_t(t)) {
      whole.triangles.push_back(before.triangles[t]);
      whole.pairs.push_back(before.pairs[t]);
      whole_kept.push_back(int32_t(t));
      continue;
    }
    if (kept < kept_triangles.size() && size_t(kept_triangles[kept]) == in_part) {
      const auto& tri = merged.triangles[kept];
      whole.triangles.push_back({part.nodes[size_t(tri[0])], part.nodes[size_t(tri[1])], part.nodes[size_t(tri[2])]});
      whole.pairs.push_back(merged.pairs[kept++]);
      whole_kept.push_back(int32_t(t));
    }
    ++in_part;
  }
}

} // namespace vm::detail
