#pragma once
/// @file mesh/junctions.hpp
/// Where surfaces meet: the phases at each node, the triple curves and the
/// quadruple points of an interface mesh (paper sect. 2: surfaces meet along
/// triple curves, and triple curves at quadruple points). Writers use it to
/// tag nodes and to write the curves and points as elements of their own.

#include "voronoimesh/mesh/node_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vm {

/// A maximal chain of junction edges (edges that three or more triangles share)
/// through nodes where exactly three phases meet: it ends at quadruple (or
/// higher) points, on the domain box, or closes on itself.
struct TripleCurve {
  /// The phases meeting along it, ascending: three on a generic mesh (more where
  /// four or more phases share an edge, e.g. grains meeting along a block edge).
  std::vector<int32_t> phases;
  /// Its nodes in chain order. An open curve starts at the end with the smaller
  /// node id; a closed one starts and ends at its smallest node (listed twice).
  std::vector<int32_t> nodes;

  /// True when the curve closes on itself (its first node is its last).
  bool closed() const { return nodes.size() > 2 && nodes.front() == nodes.back(); }
  /// Number of edges, nodes.size() - 1.
  size_t num_edges() const { return nodes.size() - 1; }
};

/// The junction structure of a node-level mesh.
struct Junctions {
  /// Phases meeting at each node, ascending (CSR: node n has
  /// phase_ids[phase_offsets[n] .. phase_offsets[n+1])); the union of the pairs of
  /// the triangles around it.
  std::vector<int32_t> phase_offsets;
  std::vector<int32_t> phase_ids; ///< the phases of every node, node after node (see phase_offsets)
  /// Triple curves, sorted by phases and then by first node, so the curves of
  /// one phase triple are consecutive.
  std::vector<TripleCurve> curves;
  /// Nodes where four or more phases meet, ascending.
  std::vector<int32_t> quadruple_points;

  /// The phases meeting at `node`, ascending.
  /// @param node a node id of the mesh the junctions were found in
  std::span<const int32_t> phases_at(size_t node) const {
    return {phase_ids.data() + phase_offsets[node], size_t(phase_offsets[node + 1] - phase_offsets[node])};
  }
  /// The junction order of a node: the number of phases meeting there. 2 inside
  /// a surface, 3 on a triple curve, 4 or more at a quadruple point, 0 for a node
  /// no triangle uses.
  /// @param node a node id of the mesh the junctions were found in
  int order(size_t node) const { return phase_offsets[node + 1] - phase_offsets[node]; }
};

/// Finds the junction structure of `m`. Triangles with out-of-range or repeated
/// node ids (which validate() reports) and triangles without a pair are left
/// out. Linear in the mesh size.
/// @param m the mesh
/// @return its phases at each node, triple curves and quadruple points
Junctions find_junctions(const NodeMesh& m);

} // namespace vm
