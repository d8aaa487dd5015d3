#include "improve/flip_log.hpp"

#include <algorithm>

namespace vm::detail {

namespace {

/// Flips an interior edge of a triangle mesh, as OpenMesh's TriConnectivity::flip()
/// does (the same handles end in the same places), without its checks.
/// Debian's OpenMesh is built with assertions on, so its flip() asks
/// is_flip_ok() again, through calls into the library, every time: 3.7% of a
/// run on 1,000 grains at 128^3, where an undo alone flips each edge three
/// more times. flip_gain() has already asked what is_flip_ok() asks.
///
/// Edge {a, b} of triangles (b, a, c) and (a, b, d), halfedges a0: b -> a,
/// a1: a -> c, a2: c -> b and b0: a -> b, b1: b -> d, b2: d -> a, becomes edge
/// {c, d}: a0 turns into d -> c in the cycle a0, a2, b1 of the first face, b0
/// into c -> d in b0, b2, a1 of the second; each face starts at its turned
/// halfedge, and a and b, whose outgoing halfedge may have been one of them,
/// go out along a1 and b1.
void rotate_edge(OMesh& om, OMesh::EdgeHandle edge) {
  const auto a0 = om.halfedge_handle(edge, 0), b0 = om.halfedge_handle(edge, 1);
  const auto a1 = om.next_halfedge_handle(a0), a2 = om.next_halfedge_handle(a1);
  const auto b1 = om.next_halfedge_handle(b0), b2 = om.next_halfedge_handle(b1);
  const auto a = om.to_vertex_handle(a0), b = om.to_vertex_handle(b0);
  const auto c = om.to_vertex_handle(a1), d = om.to_vertex_handle(b1);
  const auto first = om.face_handle(a0), second = om.face_handle(b0);
  om.set_vertex_handle(a0, c);
  om.set_vertex_handle(b0, d);
  for (const auto& cycle : {std::array{a0, a2, b1}, std::array{b0, b2, a1}})
    for (size_t k = 0; k < 3; ++k) om.set_next_halfedge_handle(cycle[k], cycle[(k + 1) % 3]);
  om.set_face_handle(b1, first);
  om.set_face_handle(a1, second);
  om.set_halfedge_handle(first, a0);
  om.set_halfedge_handle(second, b0);
  if (om.halfedge_handle(a) == b0) om.set_halfedge_handle(a, a1);
  if (om.halfedge_handle(b) == a0) om.set_halfedge_handle(b, b1);
}

} // namespace

void FlipLog::flip(InterfaceMesh& mesh, OMesh::EdgeHandle edge, const std::array<int32_t, 4>& quad) {
  OMesh& om = mesh.omesh_for_topology();
  Handles h;
  for (int side = 0; side < 2; ++side) {
    const auto he = om.halfedge_handle(edge, side);
    h.faces[size_t(side)] = om.face_handle(he);
    h.face_first[size_t(side)] = om.halfedge_handle(h.faces[size_t(side)]);
    h.corners[size_t(2 * side)] = om.to_vertex_handle(he);
    h.corners[size_t(2 * side + 1)] = om.to_vertex_handle(om.next_halfedge_handle(he));
  }
  for (size_t c = 0; c < 4; ++c) h.corner_out[c] = om.halfedge_handle(h.corners[c]);
  rotate_edge(om, edge);
  edges_.push_back(edge.idx());
  quads_.push_back(quad);
  before_.push_back(h);
}

void FlipLog::with_dependents(std::vector<uint8_t>& undo, const std::vector<uint8_t>& undone,
                              size_t node_count) const {
  std::vector<uint8_t> touched(node_count, 0); // a node of a flip flagged so far
  for (size_t i = 0; i < quads_.size(); ++i) {
    if (undone[i]) continue;
    const auto& quad = quads_[i];
    undo[i] = undo[i] || std::any_of(quad.begin(), quad.end(), [&](int32_t n) { return touched[size_t(n)]; });
    if (undo[i])
      for (int32_t n : quad) touched[size_t(n)] = 1;
  }
}

void FlipLog::undo(InterfaceMesh& mesh, const std::vector<uint8_t>& which) {
  OMesh& om = mesh.omesh_for_topology();
  std::vector<int32_t> faces;
  for (size_t i = edges_.size(); i-- > 0;) {
    if (!which[i]) continue;
    const OMesh::EdgeHandle edge(edges_[i]);
    for (int k = 0; k < 3; ++k) rotate_edge(om, edge); // with the logged flip, four: the cycles as before
    const Handles& h = before_[i];
    for (size_t side = 0; side < 2; ++side) om.set_halfedge_handle(h.faces[side], h.face_first[side]);
    for (size_t c = 0; c < 4; ++c) om.set_halfedge_handle(h.corners[c], h.corner_out[c]);
    for (int32_t f : faces_of(i)) faces.push_back(f);
  }
  mesh.faces_changed(faces);
}

std::vector<int32_t> FlipLog::faces(size_t first) const {
  std::vector<int32_t> faces;
  faces.reserve(2 * (before_.size() - first));
  for (size_t i = first; i < before_.size(); ++i)
    for (int32_t f : faces_of(i)) faces.push_back(f);
  return faces;
}

} // namespace vm::detail
