#include "improve/flip_log.hpp"

namespace vm::detail {

void FlipLog::flip(InterfaceMesh& mesh, OMesh::EdgeHandle edge, const std::array<int32_t, 2>& nodes) {
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
  om.flip(edge);
  edges_.push_back(edge.idx());
  nodes_.push_back(nodes);
  before_.push_back(h);
}

void FlipLog::undo(InterfaceMesh& mesh) {
  OMesh& om = mesh.omesh_for_topology();
  for (size_t i = edges_.size(); i-- > 0;) {
    const OMesh::EdgeHandle edge(edges_[i]);
    for (int k = 0; k < 3; ++k) om.flip(edge); // with the logged flip, four: the cycles as before
    const Handles& h = before_[i];
    for (size_t side = 0; side < 2; ++side) om.set_halfedge_handle(h.faces[side], h.face_first[side]);
    for (size_t c = 0; c < 4; ++c) om.set_halfedge_handle(h.corners[c], h.corner_out[c]);
  }
  mesh.faces_changed(faces());
  edges_.clear();
  nodes_.clear();
  before_.clear();
}

std::vector<int32_t> FlipLog::faces() const {
  std::vector<int32_t> faces;
  faces.reserve(2 * before_.size());
  for (const Handles& h : before_)
    for (const auto f : h.faces) faces.push_back(f.idx());
  return faces;
}

} // namespace vm::detail
