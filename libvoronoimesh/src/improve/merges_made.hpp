#pragma once
/// @file improve/merges_made.hpp
/// A batch of node merges, chosen and checked on a NodeMesh copy, made on the
/// InterfaceMesh itself and numbered as swap-removal numbers
/// (docs/edits-in-place.md): each node and triangle that goes leaves its id to
/// the one with the highest id, highest removed id first; triangles that only
/// change corners keep theirs. One process edits in place
/// (InterfaceMesh::edit_in_place()). A part of a distributed mesh, and a batch
/// the edit declines, rebuild in that same numbering, so that every run makes
/// one mesh in one order (the passes break ties by ids).

#include "improve/collapse_peers.hpp"
#include "improve/mesh_part.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace vm::detail {

/// The renaming swap-removal makes of a numbering with gaps: each removed id,
/// highest first, passes to the live element with the highest id at that
/// time, unless none is above it (then it was the last and simply goes).
/// @param removed  the ids that go (any order, repeats allowed)
/// @param live_top at least the k highest live ids, k the number of distinct removed ids (all of them if
///                 fewer), any order, repeats allowed, none of them removed
/// @return (old id, new id) of each live element renamed, ascending by old id
std::vector<std::pair<int64_t, int64_t>> swap_removal_renames(std::vector<int64_t> removed,
                                                              std::vector<int64_t> live_top);

/// Makes on `mesh` the merges that turned `part` into `merged`, numbered by
/// swap-removal (see the file comment).
/// @param mesh           the mesh, edited
/// @param part           the part of `mesh` (or all of it) the merges were made on, as it was before them;
///                       each node that merges, and each target, with all its faces in it
/// @param merged         `part.mesh` merged (merge_nodes(): the same nodes, those merged away without a
///                       triangle; a target may have moved); consumed
/// @param kept_triangles the triangle of `part.mesh` each triangle of `merged` was
/// @param peers          the ranks of a distributed run, or null in one process
/// @param node_ids       the id of each node of `mesh`, increasing (one process: its index)
/// @param triangle_ids   the id of each triangle of `mesh`, increasing
/// @param kept           set to what the merges kept: in place, the nodes and triangles removed and the
///                       moves; rebuilt, the node and triangle of `mesh` before the merges each node and
///                       triangle of `mesh` is now, and their ids now
void make_merges(InterfaceMesh& mesh, const MeshPart& part, NodeMesh& merged, std::span<const int32_t> kept_triangles,
                 CollapsePeers* peers, std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids,
                 CollapseKept& kept);

} // namespace vm::detail
