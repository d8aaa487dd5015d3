#pragma once
/// @file mesh/topology.hpp
/// Incidence tables of a node-level triangle soup, shared by the mesh builder,
/// the validator and the statistics. All are built by counting and local sorts
/// (no hashing, no global sort), so they cost O(triangles x small valence).

#include "voronoimesh/core/types.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

using Triangles = std::vector<std::array<int32_t, 3>>;

/// Halfedge h = 3t + k is edge k of triangle t: it runs from corner k to corner
/// (k+1) mod 3, in the triangle's own orientation.
inline int32_t he_triangle(int32_t h) {
  return h / 3;
}
inline int32_t he_from(const Triangles& tris, int32_t h) {
  return tris[size_t(h / 3)][size_t(h % 3)];
}
inline int32_t he_to(const Triangles& tris, int32_t h) {
  return tris[size_t(h / 3)][size_t((h % 3 + 1) % 3)];
}

/// True when the triangle's node ids are in [0, num_nodes) and distinct: the
/// precondition of every table below.
inline bool well_formed(const std::array<int32_t, 3>& t, size_t num_nodes) {
  for (int32_t v : t)
    if (v < 0 || size_t(v) >= num_nodes) return false;
  return t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
}

/// Per triangle, whether it is well formed and has a phase pair (`num_pairs`
/// of the triangles have one), so measured: malformed ones are left out of
/// every measure (validate() reports them).
inline std::vector<char> measured_triangles(const Triangles& tris, size_t num_pairs, size_t num_nodes) {
  std::vector<char> measured(tris.size());
  for (size_t t = 0; t < tris.size(); ++t) measured[t] = t < num_pairs && well_formed(tris[t], num_nodes);
  return measured;
}

/// Triangles around each node (CSR), ascending triangle ids per node.
struct NodeTriangles {
  std::vector<int32_t> off; ///< num_nodes + 1 offsets
  std::vector<int32_t> tri;
  std::span<const int32_t> of(size_t n) const { return {tri.data() + off[n], size_t(off[n + 1] - off[n])}; }
};

/// Builds the node-triangle table. Triangles with `usable[t] == 0` are left out
/// (the validator passes only triangles whose node ids are in range and distinct);
/// a null `usable` means all, and then every node id must be in range.
NodeTriangles node_triangles(size_t num_nodes, std::span<const std::array<int32_t, 3>> tris,
                             const std::vector<char>* usable = nullptr);

/// Every node-edge {a < b} with the halfedges lying on it, sorted by (a, b).
struct EdgeTable {
  std::vector<std::array<int32_t, 2>> nodes; ///< (a, b), a < b
  std::vector<int32_t> off;                  ///< size() + 1 offsets into `he`
  std::vector<int32_t> he;                   ///< halfedges of each edge, ascending
  std::vector<int32_t> first;                ///< num_nodes + 1: edges whose smaller node is a start at first[a]

  size_t size() const { return nodes.size(); }
  std::span<const int32_t> halfedges(size_t e) const { return {he.data() + off[e], size_t(off[e + 1] - off[e])}; }
  /// Index of the edge {a, b} (either order), or -1 if no triangle has it.
  int64_t find(int32_t a, int32_t b) const;
};

EdgeTable edge_table(const Triangles& tris, const NodeTriangles& nt);

/// The node-edges {a, b} with b > a, each with its halfedges: node a's part of
/// edge_table(), in the same order (ascending b, ascending halfedges), made on
/// the fly. Reusing one EdgesAt for many nodes allocates only while it grows,
/// so a pass over all nodes can check edges without building the whole table.
class EdgesAt {
public:
  void gather(int32_t a, const Triangles& tris, const NodeTriangles& nt);
  size_t size() const { return other_.size(); }
  int32_t other(size_t i) const { return other_[i]; } ///< b of the i-th edge
  std::span<const int32_t> halfedges(size_t i) const {
    return {he_.data() + off_[i], size_t(off_[i + 1] - off_[i])};
  }
  /// The halfedges of all the edges, one edge after the other (to copy them at
  /// once): halfedges(i) ends at halfedges_end(i) in it.
  std::span<const int32_t> halfedges() const { return he_; }
  int32_t halfedges_end(size_t i) const { return off_[i + 1]; }

private:
  std::vector<uint64_t> local_; // (b, halfedge) of gather()
  std::vector<int32_t> other_, off_, he_;
};

/// True when the halfedges of a node-edge lie inside one surface patch: exactly
/// two triangles, of the same pair, running along it in opposite directions.
/// Such an edge is the only kind the patch-split mesh glues (openmesh-probe.md, Q2).
inline bool is_patch_interior(std::span<const int32_t> halfedges, const Triangles& tris,
                              const std::vector<PhasePair>& pairs) {
  if (halfedges.size() != 2) return false;
  const PhasePair &p = pairs[size_t(he_triangle(halfedges[0]))], &q = pairs[size_t(he_triangle(halfedges[1]))];
  // (Compared by element: std::array's == is an out-of-line memcmp here, and this is hot in validate().)
  return p[0] == q[0] && p[1] == q[1] && he_from(tris, halfedges[0]) != he_from(tris, halfedges[1]);
}
inline bool is_patch_interior(const EdgeTable& et, size_t e, const Triangles& tris,
                              const std::vector<PhasePair>& pairs) {
  return is_patch_interior(et.halfedges(e), tris, pairs);
}

/// Distinct phases of the triangles around each node, sorted (CSR).
struct NodePhases {
  std::vector<int32_t> off;
  std::vector<int32_t> phase;
  std::span<const int32_t> of(size_t n) const { return {phase.data() + off[n], size_t(off[n + 1] - off[n])}; }
  size_t count(size_t n) const { return size_t(off[n + 1] - off[n]); }
};

NodePhases node_phases(const NodeTriangles& nt, const std::vector<PhasePair>& pairs);

} // namespace vm::detail
