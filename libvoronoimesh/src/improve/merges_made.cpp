/// @file improve/merges_made.cpp
/// make_merges(): a batch of merges in place, or rebuilt in the numbering an
/// edit in place makes.

#include "improve/merges_made.hpp"

#include "core/indices_where.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <functional>
#include <numeric>
#include <set>

namespace vm::detail {

std::vector<std::pair<int64_t, int64_t>> swap_removal_renames(std::vector<int64_t> removed,
                                                              std::vector<int64_t> live_top) {
  std::sort(removed.begin(), removed.end(), std::greater<>());
  removed.erase(std::unique(removed.begin(), removed.end()), removed.end());
  // (id now, id at first) of the live elements that may take a removed id;
  // one renamed may be renamed again by a lower removed id.
  std::set<std::pair<int64_t, int64_t>> live;
  for (const int64_t id : live_top) live.emplace(id, id);
  for (const int64_t gone : removed) {
    if (live.empty() || std::prev(live.end())->first < gone) continue;
    const int64_t first = std::prev(live.end())->second;
    live.erase(std::prev(live.end()));
    live.emplace(gone, first);
  }
  std::vector<std::pair<int64_t, int64_t>> renames;
  for (const auto& [now, first] : live)
    if (now != first) renames.emplace_back(first, now);
  std::sort(renames.begin(), renames.end());
  return renames;
}

namespace {

/// What a batch of merges removes, in the whole mesh's numbers: the triangles
/// of the part none of `merged` was, and the nodes no triangle uses any more
/// (of the part's nodes no triangle of `merged` uses, those with no face
/// outside the part).
struct Removed {
  std::vector<int32_t> triangles, nodes;
};

Removed removed_by(const InterfaceMesh& mesh, const MeshPart& part, const NodeMesh& merged,
                   std::span<const int32_t> kept_triangles) {
  const NodeMesh& before = part.mesh;
  std::vector<uint8_t> kept(before.num_triangles(), 0), used(before.num_nodes(), 0);
  parallel_for_each_index(kept_triangles.size(), [&](size_t t) {
    kept[size_t(kept_triangles[t])] = 1;
    for (const int32_t v : merged.triangles[t])
      std::atomic_ref<uint8_t>(used[size_t(v)]).store(1, std::memory_order_relaxed);
  });
  // Looked up face by face: std::includes walks the part's faces up to the
  // node's last, so a batch of many merges on a large part was quadratic (a
  // quarter of the voxel-faithful closed liver's 90 s improvement).
  auto all_faces_in_part = [&](int32_t n) {
    if (part.is_whole) return true;
    const int32_t whole = part.whole_node(n);
    const std::vector<int32_t> faces = mesh.faces_at(std::span(&whole, 1));
    return std::all_of(faces.begin(), faces.end(), [&](int32_t f) {
      return std::binary_search(part.triangles.begin(), part.triangles.end(), f);
    });
  };
  Removed r;
  indices_where(before.num_triangles(), [&](size_t t) { return !kept[t]; }, r.triangles);
  for (int32_t& t : r.triangles) t = part.whole_triangle(t);
  for (const int32_t n : indices_where(before.num_nodes(), [&](size_t n) { return !used[n]; }))
    if (all_faces_in_part(n)) r.nodes.push_back(part.whole_node(n));
  return r;
}

/// The merges as one edit in place; false where edit_in_place() declines.
bool made_in_place(InterfaceMesh& mesh, const MeshPart& part, const NodeMesh& merged,
                   std::span<const int32_t> kept_triangles, const Removed& removed, CollapseKept& kept) {
  const NodeMesh& before = part.mesh;
  LocalEdit edit;
  edit.removed_faces = removed.triangles;
  indices_where(merged.num_triangles(),
                [&](size_t t) { return merged.triangles[t] != before.triangles[size_t(kept_triangles[t])]; },
                edit.rewritten_faces); // still merged's indices
  for (int32_t& t : edit.rewritten_faces) {
    const auto& tri = merged.triangles[size_t(t)];
    edit.added.push_back({part.whole_node(tri[0]), part.whole_node(tri[1]), part.whole_node(tri[2])});
    edit.added_pairs.push_back(merged.pairs[size_t(t)]);
    t = part.whole_triangle(kept_triangles[size_t(t)]);
  }
  edit.removed_nodes = removed.nodes;
  auto placed = [&](size_t n) { return merged.points[n] != before.points[n]; };
  for (const int32_t n : indices_where(before.num_nodes(), placed)) {
    edit.placed_nodes.push_back(part.whole_node(n));
    edit.placed_at.push_back(merged.points[size_t(n)]);
  }
  EditMoves moves;
  if (!mesh.edit_in_place(edit, moves)) return false;
  kept = CollapseKept{};
  kept.in_place = true;
  kept.removed_nodes = removed.nodes;
  kept.removed_triangles = removed.triangles;
  kept.moves = std::move(moves);
  return true;
}

/// The new id of each of `kept` (indices into `ids`, increasing) after the
/// removal of `removed`, agreed with the peers; appended to `new_ids`.
void ids_after_removal(std::span<const int64_t> ids, const std::vector<int32_t>& removed,
                       const std::vector<int32_t>& kept, CollapsePeers* peers, std::vector<int64_t>& new_ids) {
  std::vector<int64_t> gone;
  for (const int32_t e : removed) gone.push_back(ids[size_t(e)]); // ascending, as `removed`
  if (peers) gone = peers->all(gone);                             // sorted, once each
  // This part's highest live ids. A far edge of a window may hold a node or
  // triangle another rank's merge removed (the merge's other end outside the
  // window): it is not live anywhere else, so not here either.
  std::vector<int64_t> top;
  for (auto e = kept.rbegin(); e != kept.rend() && top.size() < gone.size(); ++e)
    if (const int64_t id = ids[size_t(*e)]; !std::binary_search(gone.begin(), gone.end(), id)) top.push_back(id);
  if (peers) top = peers->all(top);
  const std::vector<std::pair<int64_t, int64_t>> renames = swap_removal_renames(std::move(gone), std::move(top));
  for (const int32_t e : kept) {
    const int64_t id = ids[size_t(e)];
    const auto it = std::lower_bound(renames.begin(), renames.end(), std::pair{id, INT64_MIN});
    new_ids.push_back(it != renames.end() && it->first == id ? it->second : id);
  }
}

/// The order that sorts `ids` ascending.
std::vector<int32_t> ascending(const std::vector<int64_t>& ids) {
  std::vector<int32_t> order(ids.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int32_t x, int32_t y) { return ids[size_t(x)] < ids[size_t(y)]; });
  return order;
}

/// The merges by a rebuild of `merged` in the order of the ids swap-removal gives.
void made_by_rebuild(InterfaceMesh& mesh, const NodeMesh& before, NodeMesh& merged,
                     std::span<const int32_t> kept_triangles, const Removed& removed, CollapsePeers* peers,
                     std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids, CollapseKept& kept) {
  std::vector<int32_t> live_nodes;
  const auto& gone = removed.nodes; // ascending
  indices_where(
      before.num_nodes(), [&](size_t n) { return !std::binary_search(gone.begin(), gone.end(), int32_t(n)); },
      live_nodes);
  std::vector<int64_t> node_id, triangle_id;
  ids_after_removal(node_ids, removed.nodes, live_nodes, peers, node_id);
  // Triangles in the order of `before` (kept_triangles ascends).
  ids_after_removal(triangle_ids, removed.triangles, std::vector<int32_t>(kept_triangles.begin(), kept_triangles.end()),
                    peers, triangle_id);
  const std::vector<int32_t> node_order = ascending(node_id), triangle_order = ascending(triangle_id);
  std::vector<int32_t> node_now(before.num_nodes(), -1);
  for (size_t i = 0; i < node_order.size(); ++i) node_now[size_t(live_nodes[size_t(node_order[i])])] = int32_t(i);
  NodeMesh out = std::move(merged);
  std::vector<Vec3> points(node_order.size());
  std::vector<std::array<int32_t, 3>> triangles(triangle_order.size());
  std::vector<PhasePair> pairs(triangle_order.size());
  kept = {};
  for (size_t i = 0; i < node_order.size(); ++i) {
    const int32_t old = live_nodes[size_t(node_order[i])];
    points[i] = out.points[size_t(old)];
    kept.nodes.push_back(old);
    kept.node_ids.push_back(node_id[size_t(node_order[i])]);
  }
  for (size_t i = 0; i < triangle_order.size(); ++i) {
    const auto t = size_t(triangle_order[i]);
    for (size_t k = 0; k < 3; ++k) triangles[i][k] = node_now[size_t(out.triangles[t][k])];
    pairs[i] = out.pairs[t];
    kept.triangles.push_back(kept_triangles[t]);
    kept.triangle_ids.push_back(triangle_id[t]);
  }
  out.points = std::move(points);
  out.triangles = std::move(triangles);
  out.pairs = std::move(pairs);
  mesh.apply_edit(out, kept.triangles, kept.nodes);
}

} // namespace

void make_merges(InterfaceMesh& mesh, const MeshPart& part, NodeMesh& merged, std::span<const int32_t> kept_triangles,
                 CollapsePeers* peers, std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids,
                 CollapseKept& kept) {
  const Removed removed = removed_by(mesh, part, merged, kept_triangles);
  if (!peers && made_in_place(mesh, part, merged, kept_triangles, removed, kept)) return;
  if (part.is_whole) {
    made_by_rebuild(mesh, part.mesh, merged, kept_triangles, removed, peers, node_ids, triangle_ids, kept);
    return;
  }
  const NodeMesh before = mesh.to_node_mesh(); // the edit declined: the mesh is as it was
  NodeMesh whole;
  std::vector<int32_t> whole_kept;
  put_back(part, merged, kept_triangles, before, whole, whole_kept);
  made_by_rebuild(mesh, before, whole, whole_kept, removed, peers, node_ids, triangle_ids, kept);
}

} // namespace vm::detail
