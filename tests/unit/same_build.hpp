#pragma once
/// @file same_build.hpp
/// Whether two InterfaceMesh builds are the same in everything a pass can read:
/// OpenMesh's arrays (halfedges, vertices, faces, the node and pair of each)
/// and properties, each node's copies, neighbours, phases and box faces, the
/// triangles and their copies. InterfaceMesh::apply_edit() must build what
/// from_node_mesh() builds (in arrays it reuses, whose properties must not pile
/// up); the tests of the edits that use it compare with this.

#include "voronoimesh/mesh/interface_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace vm::test {

/// Empty when `a` and `b` are the same build, else the first difference.
inline std::string build_difference(const InterfaceMesh& a, const InterfaceMesh& b) {
  const OMesh &x = a.omesh(), &y = b.omesh();
  if (x.n_vertices() != y.n_vertices() || x.n_edges() != y.n_edges() || x.n_faces() != y.n_faces())
    return "element counts";
  if (x.n_vprops() != y.n_vprops() || x.n_hprops() != y.n_hprops() || x.n_eprops() != y.n_eprops() ||
      x.n_fprops() != y.n_fprops())
    return "property counts";
  for (size_t h = 0; h < x.n_halfedges(); ++h) {
    const auto hh = OMesh::HalfedgeHandle(int(h));
    if (x.to_vertex_handle(hh) != y.to_vertex_handle(hh) || x.next_halfedge_handle(hh) != y.next_halfedge_handle(hh) ||
        x.face_handle(hh) != y.face_handle(hh))
      return "halfedge " + std::to_string(h);
  }
  for (size_t v = 0; v < x.n_vertices(); ++v) {
    const auto vh = OMesh::VertexHandle(int(v));
    if (x.halfedge_handle(vh) != y.halfedge_handle(vh) || a.node(vh) != b.node(vh) || x.point(vh) != y.point(vh))
      return "vertex " + std::to_string(v);
  }
  for (size_t f = 0; f < x.n_faces(); ++f) {
    const auto fh = OMesh::FaceHandle(int(f));
    if (x.halfedge_handle(fh) != y.halfedge_handle(fh) || a.pair(fh) != b.pair(fh)) return "face " + std::to_string(f);
  }
  if (a.num_nodes() != b.num_nodes() || a.positions() != b.positions()) return "nodes";
  for (size_t n = 0; n < a.num_nodes(); ++n) {
    const auto node = int32_t(n);
    if (!std::ranges::equal(a.copies(node), b.copies(node)) ||
        !std::ranges::equal(a.neighbours(node), b.neighbours(node)) || a.phases()[n] != b.phases()[n] ||
        a.box_faces()[n] != b.box_faces()[n])
      return "node " + std::to_string(n);
  }
  if (a.triangles() != b.triangles() || a.triangle_copies() != b.triangle_copies()) return "triangles";
  return "";
}

/// Expects `mesh` to be what from_node_mesh() builds of its own node mesh.
inline void expect_built_as_anew(const InterfaceMesh& mesh, const std::string& what) {
  EXPECT_EQ(build_difference(mesh, InterfaceMesh::from_node_mesh(mesh.to_node_mesh())), "") << what;
}

} // namespace vm::test
