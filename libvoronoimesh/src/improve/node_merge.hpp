#pragma once
/// @file improve/node_merge.hpp
/// Edge collapses done at the node level, in batches: merge nodes into others
/// on a NodeMesh, then find where the merged mesh fails (validation, turned or
/// crossing triangles) so that the collapses to blame can be dropped. Shared by
/// the junction-sliver collapse (improve/collapse.cpp) and the remesh pass
/// (improve/remesh.cpp).

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace vm::detail {

class CollapsePeers;
class CrossingIndex; // check/crossing_index.hpp
struct MeshPart;     // improve/mesh_part.hpp

/// `m` with every node b of `into` (into[b] = a, or -1) merged into its a:
/// triangles that lose a corner disappear. With `points`, the nodes of `out`
/// lie there (a merge target may move). With `close_folds`, two triangles at
/// a target that became one triangle turned both ways (a strip one triangle
/// wide between merged nodes) disappear too. Appends to `turned` the corners
/// of remaining triangles that would turn over, and sets `kept_triangles` to
/// the index in `m` of each triangle of `out` and, if given, `reshaped` to
/// whether each lost a merged corner or has a corner that moved.
void merge_nodes(const NodeMesh& m, const std::vector<int32_t>& into, NodeMesh& out, std::vector<int32_t>& turned,
                 std::vector<int32_t>& kept_triangles, const std::vector<Vec3>* points = nullptr,
                 bool close_folds = false, std::vector<uint8_t>* reshaped = nullptr);

/// The smallest quality of the triangles that change when the nodes `merged`
/// merge into a placed at `to` (those at a merged node, and at a if
/// `a_moves`), after the merge: 0 if one turns over; those with two corners
/// among a and the merged nodes vanish. With `before`, also their smallest
/// quality before it. For the remesh pass's NodeRings and the junction-sliver
/// collapse's InterfaceMesh alike.
template <class Mesh>
double quality_after_merges(const Mesh& mesh, std::span<const int32_t> merged, int32_t a, const Vec3& to,
                            bool a_moves, double* before = nullptr) {
  const auto& pos = mesh.positions();
  auto goes = [&](int32_t n) { return n == a || std::find(merged.begin(), merged.end(), n) != merged.end(); };
  double old_q = 1, new_q = 1;
  auto judge = [&](int32_t n) {
    mesh.for_each_triangle_at(n, [&](int32_t x, int32_t y) {
      const Vec3 &p = pos[size_t(n)], &px = pos[size_t(x)], &py = pos[size_t(y)];
      old_q = std::min(old_q, triangle_quality(p, px, py));
      if (goes(x) || goes(y)) return; // this triangle disappears
      const bool turned = (px - p).cross(py - p).dot((px - to).cross(py - to)) <= 0;
      new_q = turned ? 0 : std::min(new_q, triangle_quality(to, px, py));
    });
  };
  for (int32_t n : merged) judge(n);
  if (a_moves) judge(a); // else a's triangles stay as they are
  if (before) *before = old_q;
  return new_q;
}

/// quality_after_merges() of node b alone.
template <class Mesh>
double quality_after_merge(const Mesh& mesh, int32_t b, int32_t a, const Vec3& to, bool a_moves,
                           double* before = nullptr) {
  return quality_after_merges(mesh, std::span<const int32_t>(&b, 1), a, to, a_moves, before);
}

/// Drops nodes no triangle uses and renumbers the rest in order; appends the
/// old index of each kept node to `kept`.
void drop_unused_nodes(NodeMesh& m, std::vector<int32_t>& kept);

/// What a batch of merges must pass besides a valid mesh, and what helps to
/// check it: shared by find_merge_failures() and merge_passing().
struct MergeChecks {
  /// Fail merges after which a triangle at a target crosses another surface.
  bool guard_crossings = false;
  /// Fail merges after which a surface edge at a target folds (MeshStats::folds).
  bool refuse_surface_folds = false;
  /// Null, or phase functions whose kept points (PhaseField::kept_points(),
  /// improve/kept_points.hpp) a merge must not take out of their phase: the
  /// failure is at the merge's target.
  const PhaseField* kept = nullptr;
  /// In a distributed run, how the ranks agree (which rank answers for which
  /// target); null in one process.
  CollapsePeers* peers = nullptr;
  /// Null, or the guard's index up to date with the mesh before the merges
  /// (CrossingIndex::refresh(), CrossingGuard::index_for()), through which the
  /// crossings of the triangles at targets are found (the same pairs, found
  /// around them instead of in a search of the whole merged mesh).
  const CrossingIndex* index = nullptr;
  /// With `index`: the part of the index's mesh that the meshes checked are
  /// merged from (improve/mesh_part.hpp); null if they are merged from all of it.
  const MeshPart* part = nullptr;
};

/// Where `trial` (a mesh after merge_nodes() by `into`) fails `checks`: appends
/// the nodes of validation problems around merge targets and the nodes named
/// by the checks asked for (the corners of triangles at a target that cross a
/// triangle of another surface or fold, the target that takes a kept point
/// out of its phase). Returns false if it fails somewhere no node names (then
/// nothing in the batch can be trusted). `changed`: empty, or when `trial`
/// retries a batch whose last trial's failures were all reported, one flag per
/// node set where that trial differed or failed (the ends of the collapses
/// dropped since, the nodes reported): then only crossings with a triangle at a
/// flagged node are searched for, and only targets within two rings of one
/// validated again.
/// `before`: null, or the mesh `trial` was merged from (needed by the index and
/// the kept points). `reshaped`: empty, or merge_nodes()'s flags for `trial`
/// (without an index): then only pairs with a reshaped triangle are searched,
/// since two triangles as they were cannot have come to cross.
bool find_merge_failures(const NodeMesh& trial, const std::vector<int32_t>& into, const MergeChecks& checks,
                         std::vector<int32_t>& nodes, std::span<const uint8_t> changed = {},
                         const NodeMesh* before = nullptr, std::span<const uint8_t> reshaped = {});

/// Which collapses of a batch to drop for a failure at a node: (node id, index
/// of the collapse in the batch) pairs, sorted. A flat list, not a hash
/// multimap: the remesh pass blames each of its tens of thousands of
/// collapses on a dozen nodes or so, and building and freeing the multimap
/// cost half as much as checking the merge (the liver's first call).
using Blame = std::vector<std::pair<int64_t, int32_t>>;

/// Makes as many of the collapses `chosen` (b -> a, as node ids; no two share a
/// triangle) as pass, all at once: after each merge of the active ones, the
/// collapses blamed for a failing node (find_merge_failures()) are dropped and the
/// rest tried again (one or two whole-mesh checks, not one per collapse). A
/// failure that no collapse is blamed for makes none.
/// @param m              the mesh
/// @param merged         set to the merged mesh when anything was collapsed, else untouched (not `m`:
///                       the caller keeps both without copying `m`, a whole mesh of fresh pages a call)
/// @param chosen         the collapses {a, b} as node ids
/// @param blame          the indices in `chosen` of the collapses to drop for a failure at each node id, sorted
///                       (at least every collapse whose target's new ring the node is in, and the target)
/// @param checks         what the merged mesh must pass besides validation (find_merge_failures())
/// @param node_ids       the id of each node of `m`, increasing
/// @param kept_triangles set to the old index of each triangle of the merged mesh
/// @param moved_to       empty, or where each collapse's a goes (not finite: it stays)
/// @param made           if given, set to one flag per collapse of `chosen`: made or not
/// @param close_folds    merge_nodes()'s: for merges of whole faces (digon faces)
/// @return the number of collapses made (0: `merged` untouched)
size_t merge_passing(const NodeMesh& m, NodeMesh& merged, std::span<const std::pair<int64_t, int64_t>> chosen,
                     const Blame& blame, const MergeChecks& checks, std::span<const int64_t> node_ids,
                     std::vector<int32_t>& kept_triangles, std::span<const Vec3> moved_to = {},
                     std::vector<uint8_t>* made = nullptr, bool close_folds = false);

} // namespace vm::detail
