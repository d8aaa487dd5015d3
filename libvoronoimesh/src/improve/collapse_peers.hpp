#pragma once
/// @file improve/collapse_peers.hpp
/// How the collapses of a distributed run agree across ranks
/// (mpi/improve_part.cpp), as flip_peers.hpp does for flips. One process
/// passes no peers. Nodes travel as ids (a distributed run's global vertex ids;
/// in one process the node indices themselves), which order nodes alike.

#include "voronoimesh/improve/collapse.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// A junction sliver that could be collapsed: its quality, its triangle's id,
/// the edge b -> a it would collapse (a = -1: none allowed), the nodes a
/// collapse claims (a, b and their rings), as ids, and where a goes (not
/// finite: a stays).
struct SliverCollapse {
  double quality;
  int64_t triangle;
  int64_t a, b;
  std::vector<int64_t> claims;
  Vec3 to = Vec3::Constant(NAN);
};

class CollapsePeers {
public:
  virtual ~CollapsePeers() = default;
  /// True when this rank answers for node n: its slivers (by lowest corner),
  /// the validation around it as a collapse target, its failures.
  virtual bool answers_for(int32_t n) = 0;
  /// Every rank's slivers.
  virtual std::vector<SliverCollapse> all(const std::vector<SliverCollapse>& mine) = 0;
  /// Every rank's node ids, once each.
  virtual std::vector<int64_t> all(const std::vector<int64_t>& mine) = 0;
  /// True when any rank's `mine` is.
  virtual bool any(bool mine) = 0;
};

/// What a collapse kept of the mesh, to follow its nodes and triangles
/// (make_merges(), improve/merges_made.hpp). Made in place (one process): the
/// nodes and triangles removed and how the others moved, sparse (a whole map
/// of a 1M-triangle mesh cost more than the edit). Rebuilt: the old index of
/// each node and each triangle of the edited mesh, and in a distributed run
/// their ids now.
struct CollapseKept {
  bool in_place = false;
  std::vector<int32_t> removed_nodes, removed_triangles; ///< in place: old ids, ascending
  EditMoves moves;                                       ///< in place: the edit's moves
  std::vector<int32_t> nodes, triangles;                 ///< rebuilt: the old index of each
  std::vector<int64_t> node_ids, triangle_ids;           ///< rebuilt: the ids now
};

/// collapse_junction_slivers() agreed across ranks: `node_ids` and
/// `triangle_ids` give this rank's nodes and triangles their ids. It numbers
/// what it keeps as one process does (make_merges()), and reports in `kept`
/// what it kept and the ids they have now.
size_t collapse_junction_slivers(InterfaceMesh& mesh, const CollapseParams& params, CollapsePeers& peers,
                                 std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids,
                                 CollapseKept& kept);

} // namespace vm::detail
