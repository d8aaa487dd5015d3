#pragma once
/// @file improve/edge_splits.hpp
/// The remesh pass's splits of long edges at their midpoints
/// (improve/remesh.cpp), on a NodeMesh.

#include "voronoimesh/mesh/node_mesh.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vm::detail {

/// Splits edges longer than this share of their target, and lets no collapse make one (their 4/3).
constexpr double kLongEdge = 4.0 / 3.0;

/// The triangles of a mesh before split_long_edges() cut them, with their
/// pairs and origins: with its nodes (the first ones after the splits), the mesh.
struct Unsplit {
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<PhasePair> pairs;
  std::vector<int32_t> origin;
};

/// Splits, in `m`, every edge longer than kLongEdge of the smaller target of
/// its nodes and with neither node `held` (one flag per node, extended for the
/// new ones; `parents` gets each new node's edge) at its midpoint (whose
/// target, appended to `target`, is the mean of its ends'), in every triangle
/// that has it; each triangle is cut by the pattern of its split edges (two
/// split edges: the shorter diagonal of the remaining quad). `origin` (one
/// entry per triangle) follows the triangles: an uncut one keeps its entry, the
/// pieces of a cut one get -1.
/// With `replaced`, the triangles, pairs and origins that the cut ones replace
/// are moved there (the nodes are only appended to). Returns the number of
/// edges split.
size_t split_long_edges(NodeMesh& m, std::vector<double>& target, std::vector<uint8_t>& held,
                        std::vector<std::array<int32_t, 2>>& parents, std::vector<int32_t>& origin,
                        Unsplit* replaced);

} // namespace vm::detail
