#include "voronoimesh/mesh/omesh.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <unordered_map>

namespace vm {

void OMesh::unlink_edge(EdgeHandle e) {
  const HalfedgeHandle h0 = halfedge_handle(e, 0), h1 = halfedge_handle(e, 1);
  const VertexHandle v0 = to_vertex_handle(h0), v1 = to_vertex_handle(h1);
  const HalfedgeHandle next0 = next_halfedge_handle(h0), prev0 = prev_halfedge_handle(h0);
  const HalfedgeHandle next1 = next_halfedge_handle(h1), prev1 = prev_halfedge_handle(h1);
  // The boundary loops through h0 and h1 bypass them.
  set_next_halfedge_handle(prev0, next1);
  set_next_halfedge_handle(prev1, next0);
  // h1 leaves v0 and h0 leaves v1: a vertex whose outgoing halfedge goes takes
  // the next one around it, none where the loop came straight back.
  if (halfedge_handle(v0) == h1) set_halfedge_handle(v0, next0 == h1 ? HalfedgeHandle() : next0);
  if (halfedge_handle(v1) == h0) set_halfedge_handle(v1, next1 == h0 ? HalfedgeHandle() : next1);
}

void OMesh::fill_face_slot(int32_t f, int32_t last) {
  const FaceHandle to(f), from(last);
  face(to) = face(from);
  HalfedgeHandle h = halfedge_handle(to);
  if (h.is_valid()) // else a hole: no halfedge to tell
    for (int k = 0; k < 3; ++k, h = next_halfedge_handle(h)) set_face_handle(h, to);
  fprops_swap(unsigned(f), unsigned(last));
}

void OMesh::fill_hole(int32_t hole) {
  const auto last = int32_t(n_faces() - 1);
  fill_face_slot(hole, last);
  resize(n_vertices(), n_edges(), size_t(last));
}

void OMesh::fill_edge_slot(int32_t e, int32_t last) {
  edge(EdgeHandle(e)) = edge(EdgeHandle(last));
  const auto moved = [&](HalfedgeHandle h) {
    return h.idx() / 2 == last ? HalfedgeHandle(2 * e + h.idx() % 2) : h;
  };
  for (int k = 0; k < 2; ++k) {
    const HalfedgeHandle h(2 * e + k), was(2 * last + k);
    const HalfedgeHandle next = moved(next_halfedge_handle(h)), prev = moved(prev_halfedge_handle(h));
    set_next_halfedge_handle(h, next);
    set_next_halfedge_handle(prev, h);
    const FaceHandle f = face_handle(h);
    if (f.is_valid() && halfedge_handle(f) == was) set_halfedge_handle(f, h);
    const VertexHandle from = from_vertex_handle(h);
    if (halfedge_handle(from) == was) set_halfedge_handle(from, h);
  }
  eprops_swap(unsigned(e), unsigned(last));
  hprops_swap(unsigned(2 * e), unsigned(2 * last));
  hprops_swap(unsigned(2 * e + 1), unsigned(2 * last + 1));
}

void OMesh::fill_vertex_slot(int32_t v, int32_t last) {
  const VertexHandle to(v);
  vertex(to) = vertex(VertexHandle(last));
  for (const HalfedgeHandle h : voh_range(to)) set_vertex_handle(opposite_halfedge_handle(h), to);
  vprops_swap(unsigned(v), unsigned(last));
}

void OMesh::unlink_face(int32_t f, std::vector<int32_t>& dead_edges, std::vector<int32_t>& touched) {
  std::array<HalfedgeHandle, 3> sides;
  sides[0] = halfedge_handle(FaceHandle(f));
  sides[1] = next_halfedge_handle(sides[0]);
  sides[2] = next_halfedge_handle(sides[1]);
  for (const HalfedgeHandle h : sides) {
    set_face_handle(h, FaceHandle());
    touched.push_back(to_vertex_handle(h).idx());
  }
  // As delete_face(): an edge with no face left on either side goes.
  for (const HalfedgeHandle h : sides)
    if (is_boundary(opposite_halfedge_handle(h))) {
      unlink_edge(edge_handle(h));
      dead_edges.push_back(edge_handle(h).idx());
    }
}

void OMesh::remove_faces(std::span<const int32_t> faces, SlotMoves& moves, std::span<const int32_t> holes) {
  std::vector<int32_t> dead_edges, touched;
  for (const int32_t f : faces) unlink_face(f, dead_edges, touched);
  for (const int32_t f : holes) {
    unlink_face(f, dead_edges, touched);
    set_halfedge_handle(FaceHandle(f), HalfedgeHandle());
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  std::vector<int32_t> dead_vertices;
  for (const int32_t v : touched) {
    if (is_isolated(VertexHandle(v)))
      dead_vertices.push_back(v);
    else
      adjust_outgoing_halfedge(VertexHandle(v));
  }

  // Close up each kind from the highest removed index down: the last element
  // is then never one still to be removed.
  const auto close_up = [](std::vector<int32_t> removed, size_t count, std::vector<SlotMove>& made,
                           const std::function<void(int32_t, int32_t)>& fill) {
    std::sort(removed.begin(), removed.end(), std::greater<>());
    for (const int32_t slot : removed) {
      const auto last = int32_t(--count);
      if (slot != last) fill(slot, last);
      made.push_back({last, slot});
    }
    return count;
  };
  std::vector<int32_t> dead_faces(faces.begin(), faces.end());
  const size_t nf = close_up(std::move(dead_faces), n_faces(), moves.faces,
                             [this](int32_t f, int32_t last) { fill_face_slot(f, last); });
  const size_t ne = close_up(std::move(dead_edges), n_edges(), moves.edges,
                             [this](int32_t e, int32_t last) { fill_edge_slot(e, last); });
  const size_t nv = close_up(std::move(dead_vertices), n_vertices(), moves.vertices,
                             [this](int32_t v, int32_t last) { fill_vertex_slot(v, last); });
  resize(nv, ne, nf);
}

std::vector<std::pair<int32_t, int32_t>> moved_by(std::span<const SlotMove> moves) {
  // The index before of the element at each index the moves touched; the
  // element at `to` goes (or, where from == to, the last one does).
  std::unordered_map<int32_t, int32_t> was_at;
  for (const SlotMove& m : moves) {
    const auto at = was_at.find(m.from);
    const int32_t was = at != was_at.end() ? at->second : m.from;
    if (at != was_at.end()) was_at.erase(at);
    if (m.from != m.to) was_at[m.to] = was;
  }
  std::vector<std::pair<int32_t, int32_t>> moved;
  for (const auto& [now, was] : was_at)
    if (now != was) moved.emplace_back(was, now);
  std::sort(moved.begin(), moved.end());
  return moved;
}

} // namespace vm
