/// @file mesh/interface_mesh_edit.cpp
/// InterfaceMesh::apply_edit(): the patch-split mesh of an edit of a mesh
/// (a batch of collapses, the remesh pass), built as from_node_mesh() builds
/// it but only where the edit changed something. A node whose triangles are
/// the same (renumbered) keeps its phases, its corner classes (in the order of
/// their first triangle now), the gluing of its edges and its neighbours; the
/// others, the nodes of triangles that went, came or changed, get them from
/// their triangles as from_node_mesh() does. After a few collapses on 500k
/// triangles that skips the whole-mesh node and edge tables, phases, classes
/// and rings, most of a build.

#include "voronoimesh/mesh/interface_mesh.hpp"

#include "core/parallel.hpp"
#include "mesh/patch_connectivity.hpp"
#include "mesh/topology.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <utility>

namespace vm {

namespace {

/// apply_edit() builds anew when more than one node in this many changed.
constexpr size_t kWholeBuildShare = 3;

/// The corner k of its face that halfedge h leaves (the halfedge from corner k
/// to corner k + 1): the face keeps the one from corner 2 to corner 0 (face_nodes()).
int corner_of(const OMesh& mesh, OMesh::HalfedgeHandle h) {
  const auto last = mesh.halfedge_handle(mesh.face_handle(h));
  return h == last ? 2 : mesh.next_halfedge_handle(last) == h ? 0 : 1;
}

/// The halfedges at node d in the triangles `ts` (its own), as (other node,
/// halfedge) sorted: the halfedges of each edge {d, x} together, ascending.
void halfedges_at(int32_t d, std::span<const int32_t> ts, const detail::Triangles& tris,
                  std::vector<std::pair<int32_t, int32_t>>& out) {
  out.clear();
  for (int32_t t : ts) {
    const auto& tri = tris[size_t(t)];
    const auto k = int32_t(std::find(tri.begin(), tri.end(), d) - tri.begin());
    out.emplace_back(tri[size_t((k + 1) % 3)], 3 * t + k);           // out of d
    out.emplace_back(tri[size_t((k + 2) % 3)], 3 * t + (k + 2) % 3); // into d
  }
  std::sort(out.begin(), out.end());
}

/// Calls f(x, halfedges) for each edge {d, x} of halfedges_at() output `at`.
template <class F> void for_each_edge(const std::vector<std::pair<int32_t, int32_t>>& at, std::vector<int32_t>& hs,
                                      F&& f) {
  for (size_t i = 0, end = 0; i < at.size(); i = end) {
    hs.clear();
    for (end = i; end < at.size() && at[end].first == at[i].first; ++end) hs.push_back(at[end].second);
    f(at[i].first, std::span<const int32_t>(hs));
  }
}

} // namespace

void InterfaceMesh::apply_edit(const NodeMesh& m, std::span<const int32_t> triangle_was,
                               std::span<const int32_t> node_was) {
  detail::check_node_mesh(m);
  const size_t nodes = m.points.size(), faces = m.triangles.size();
  const auto& tris = m.triangles;
  if (face_by_face_ || triangle_was.size() != faces || node_was.size() != nodes) return build(m);
  // This mesh's ids to the edit's. An id out of range or kept twice is no
  // edit of it; nodes out of order would leave the rings carried over unsorted.
  std::vector<int32_t> node_now(num_nodes(), -1), triangle_now(num_triangles(), -1);
  for (size_t n = 0, last = 0; n < nodes; ++n)
    if (const int32_t w = node_was[n]; w >= 0) {
      if (size_t(w) >= num_nodes() || size_t(w) < last) return build(m);
      node_now[size_t(w)] = int32_t(n);
      last = size_t(w) + 1;
    }
  for (size_t t = 0; t < faces; ++t)
    if (const int32_t w = triangle_was[t]; w >= 0) {
      if (size_t(w) >= num_triangles() || triangle_now[size_t(w)] >= 0) return build(m);
      triangle_now[size_t(w)] = int32_t(t);
    }

  // Dirty nodes: new ones, and the nodes (old and new) of every triangle that
  // is new, went, or has other nodes than it had.
  std::vector<uint8_t> changed(faces);
  detail::parallel_for_each_index(faces, [&](size_t t) {
    const int32_t w = triangle_was[t];
    bool differs = w < 0;
    for (int k = 0; k < 3 && !differs; ++k)
      differs = node_now[size_t(triangles_[size_t(w)][size_t(k)])] != tris[t][size_t(k)];
    changed[t] = differs;
  });
  std::vector<uint8_t> dirty(nodes, 0);
  auto dirty_old = [&](int32_t w) {
    for (int32_t v : triangles_[size_t(w)])
      if (node_now[size_t(v)] >= 0) dirty[size_t(node_now[size_t(v)])] = 1;
  };
  for (size_t n = 0; n < nodes; ++n) dirty[n] |= node_was[n] < 0;
  for (size_t t = 0; t < faces; ++t)
    if (changed[t]) {
      for (int32_t v : tris[t]) dirty[size_t(v)] = 1;
      if (triangle_was[t] >= 0) dirty_old(triangle_was[t]);
    }
  for (size_t w = 0; w < triangle_now.size(); ++w)
    if (triangle_now[w] < 0) dirty_old(int32_t(w));
  // Where most nodes changed, the whole-mesh tables are cheaper than going
  // node by node (the liver's first remesh call, nearly every node dirty:
  // 42 ms this way, 29 ms from_node_mesh()).
  if (kWholeBuildShare * size_t(std::count(dirty.begin(), dirty.end(), 1)) > nodes) return build(m);

  // The dirty nodes and their triangles (ascending, as node_triangles() has them).
  std::vector<int32_t> dirty_nodes, dirty_index(nodes, -1);
  for (size_t n = 0; n < nodes; ++n)
    if (dirty[n]) dirty_index[n] = int32_t(dirty_nodes.size()), dirty_nodes.push_back(int32_t(n));
  detail::NodeTriangles at_dirty;
  at_dirty.off.assign(dirty_nodes.size() + 1, 0);
  for (const auto& tri : tris)
    for (int32_t v : tri)
      if (dirty[size_t(v)]) ++at_dirty.off[size_t(dirty_index[size_t(v)]) + 1];
  for (size_t i = 0; i < dirty_nodes.size(); ++i) at_dirty.off[i + 1] += at_dirty.off[i];
  at_dirty.tri.resize(size_t(at_dirty.off.back()));
  {
    std::vector<int32_t> next(at_dirty.off.begin(), at_dirty.off.end() - 1);
    for (size_t t = 0; t < faces; ++t)
      for (int32_t v : tris[t])
        if (dirty[size_t(v)]) at_dirty.tri[size_t(next[size_t(dirty_index[size_t(v)])]++)] = int32_t(t);
  }

  // Glued partners: an edge at a dirty node from its triangles (each edge by
  // one end: a clean one's dirty end, else the lower), the others as this
  // mesh glues them (their triangles are all kept as they were), edge by edge.
  // Unglued edges at dirty nodes with more than one halfedge are kept: they
  // may join two vertices twice, which only add_face() links.
  std::vector<int32_t> partner(3 * faces, -1);
  tbb::enumerable_thread_specific<std::vector<std::vector<int32_t>>> unglued;
  detail::parallel_for(tbb::blocked_range<size_t>(0, dirty_nodes.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<std::pair<int32_t, int32_t>> at;
    std::vector<int32_t> hs;
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const int32_t d = dirty_nodes[i];
      halfedges_at(d, at_dirty.of(i), tris, at);
      for_each_edge(at, hs, [&](int32_t x, std::span<const int32_t> edge) {
        if (dirty[size_t(x)] && x < d) return; // x's
        if (detail::is_patch_interior(edge, tris, m.pairs))
          partner[size_t(edge[0])] = edge[1], partner[size_t(edge[1])] = edge[0];
        else if (edge.size() > 1)
          unglued.local().emplace_back(edge.begin(), edge.end());
      });
    }
  });
  std::atomic<bool> lost{false}; // a clean edge glued to a triangle that went: no edit of this mesh
  detail::parallel_for_each_index(mesh_->n_edges(), [&](size_t e) {
    const auto h = mesh_->halfedge_handle(OMesh::EdgeHandle(int(e)), 0), o = mesh_->opposite_halfedge_handle(h);
    if (mesh_->is_boundary(h) || mesh_->is_boundary(o)) return; // not glued
    const int32_t t = triangle_now[size_t(mesh_->face_handle(h).idx())];
    const int32_t s = triangle_now[size_t(mesh_->face_handle(o).idx())];
    const int k = corner_of(*mesh_, h);
    if (t < 0) return;
    if (dirty[size_t(tris[size_t(t)][size_t(k)])] || dirty[size_t(tris[size_t(t)][size_t((k + 1) % 3)])]) return;
    if (s < 0) {
      lost = true;
      return;
    }
    partner[3 * size_t(t) + size_t(k)] = 3 * s + corner_of(*mesh_, o);
    partner[3 * size_t(s) + size_t(corner_of(*mesh_, o))] = 3 * t + k;
  });
  if (lost) return build(m);

  // Corner classes: a dirty node's from its triangles; a clean node's are its
  // copies here, in the order of their first triangle now.
  InterfaceMesh im;
  std::vector<int32_t> copy_off(nodes + 1, 0);
  std::vector<int32_t> corner_at(at_dirty.tri.size()), class_at(at_dirty.tri.size());
  detail::parallel_for(tbb::blocked_range<size_t>(0, dirty_nodes.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<int32_t> parent;
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const auto first = size_t(at_dirty.off[i]);
      copy_off[size_t(dirty_nodes[i]) + 1] = detail::corner_classes_at(
          dirty_nodes[i], at_dirty.of(i), tris, partner, parent, &corner_at[first], &class_at[first]);
    }
  });
  std::vector<int32_t> class_of_copy(mesh_->n_vertices(), -1);
  detail::parallel_for_each_index(nodes, [&](size_t n) {
    if (dirty[n]) return;
    const auto copies_then = copies(node_was[n]);
    copy_off[n + 1] = int32_t(copies_then.size());
    if (copies_then.size() == 1) {
      class_of_copy[size_t(copies_then[0])] = 0;
      return;
    }
    std::vector<std::pair<int32_t, int32_t>> by_first; // (first triangle now, copy)
    for (int32_t c : copies_then) {
      int32_t first = std::numeric_limits<int32_t>::max();
      for (auto f : mesh_->vf_range(OMesh::VertexHandle(c))) first = std::min(first, triangle_now[size_t(f.idx())]);
      by_first.emplace_back(first, c);
    }
    std::sort(by_first.begin(), by_first.end());
    for (size_t i = 0; i < by_first.size(); ++i) class_of_copy[size_t(by_first[i].second)] = int32_t(i);
  });
  for (size_t n = 0; n < nodes; ++n) copy_off[n + 1] += copy_off[n];
  std::vector<int32_t> vertex_of_corner(3 * faces);
  detail::parallel_for_each_index(faces, [&](size_t t) {
    for (size_t k = 0; k < 3; ++k)
      if (const int32_t v = tris[t][k]; !dirty[size_t(v)])
        vertex_of_corner[3 * t + k] =
            copy_off[size_t(v)] + class_of_copy[size_t(triangle_copies_[size_t(triangle_was[t])][k])];
  });
  detail::parallel_for_each_index(dirty_nodes.size(), [&](size_t i) {
    for (auto j = size_t(at_dirty.off[i]); j < size_t(at_dirty.off[i + 1]); ++j)
      vertex_of_corner[size_t(corner_at[j])] = copy_off[size_t(dirty_nodes[i])] + class_at[j];
  });

  // Phase sets: a clean node's as here, a dirty one's from its triangles (the
  // first node with too many named, as from_node_mesh() would: clean ones
  // cannot have too many).
  const detail::NodePhases dirty_phases = detail::node_phases(at_dirty, m.pairs);
  for (size_t i = 0; i < dirty_nodes.size(); ++i)
    detail::check_phase_count(size_t(dirty_nodes[i]), dirty_phases.count(i));
  im.phases_.resize(nodes);
  detail::parallel_for_each_index(nodes, [&](size_t n) {
    im.phases_[n] =
        dirty[n] ? detail::phase_set(dirty_phases.of(size_t(dirty_index[n]))) : phases_[size_t(node_was[n])];
  });
  bool twice = false;
  for (const auto& edges : unglued)
    for (const auto& edge : edges) twice = twice || detail::joins_vertices_twice(edge, vertex_of_corner);

  // This mesh's OpenMesh arrays, read for the last time above, hold the new mesh.
  im.mesh_ = std::move(mesh_);
  im.node_ = node_;
  im.pair_ = pair_;
  im.link(m, copy_off, vertex_of_corner, partner, twice);

  // Rings: a clean node's neighbours are those it had, renumbered (in the same
  // order: what is kept keeps its order); a dirty one's from the new mesh.
  std::vector<uint32_t> sizes(nodes);
  detail::parallel_for_each_index(nodes, [&](size_t n) {
    sizes[n] = uint32_t(dirty[n] ? im.valence_of(n) : adj_.at(size_t(node_was[n])).size());
  });
  im.adj_.assign(sizes);
  detail::parallel_for_each_index(nodes, [&](size_t n) {
    if (dirty[n]) {
      im.adj_.truncate(n, im.ring_of(n, im.adj_.at(n).data()));
      return;
    }
    const auto then = adj_.at(size_t(node_was[n]));
    std::transform(then.begin(), then.end(), im.adj_.at(n).begin(), [&](int32_t w) { return node_now[size_t(w)]; });
  });
  im.triangles_ = tris;
  im.triangle_copies_.resize(faces);
  detail::parallel_for_each_index(faces, [&](size_t t) {
    for (size_t k = 0; k < 3; ++k) im.triangle_copies_[t][k] = vertex_of_corner[3 * t + k];
  });
  *this = std::move(im);
}

} // namespace vm
