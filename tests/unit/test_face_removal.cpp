// OMesh::remove_faces(): swap-removal of faces, and of the edges and vertices
// they leave alone, checked against the mesh it was made from.
#include "fixtures.hpp"

#include "voronoimesh/mesh/interface_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <sstream>
#include <string>

using namespace vm;
using namespace vm::test;
using VH = OMesh::VertexHandle;
using HH = OMesh::HalfedgeHandle;
using FH = OMesh::FaceHandle;

namespace {

/// The first broken link of a halfedge mesh whose faces are triangles, vertices
/// with more than one boundary gap allowed; "" when there is none.
std::string broken_link(const OMesh& om) {
  std::ostringstream why;
  for (size_t i = 0; i < om.n_halfedges(); ++i) {
    const HH h{int(i)};
    const HH next = om.next_halfedge_handle(h), prev = om.prev_halfedge_handle(h);
    if (!next.is_valid() || size_t(next.idx()) >= om.n_halfedges() || om.prev_halfedge_handle(next) != h)
      why << "halfedge " << i << ": next does not lead back";
    else if (!prev.is_valid() || size_t(prev.idx()) >= om.n_halfedges() || om.next_halfedge_handle(prev) != h)
      why << "halfedge " << i << ": prev does not lead back";
    else if (om.to_vertex_handle(h) != om.from_vertex_handle(next))
      why << "halfedge " << i << ": next does not start where it ends";
    else if (om.face_handle(next) != om.face_handle(h))
      why << "halfedge " << i << ": next in another face";
    else if (size_t(om.to_vertex_handle(h).idx()) >= om.n_vertices())
      why << "halfedge " << i << ": vertex out of range";
    if (!why.str().empty()) return why.str();
  }
  for (auto e : om.edges())
    if (om.is_boundary(om.halfedge_handle(e, 0)) && om.is_boundary(om.halfedge_handle(e, 1)))
      return "edge " + std::to_string(e.idx()) + " without a face";
  for (auto f : om.faces()) {
    const HH h = om.halfedge_handle(f);
    if (om.face_handle(h) != f) return "face " + std::to_string(f.idx()) + ": its halfedge is not its own";
    if (om.next_halfedge_handle(om.next_halfedge_handle(om.next_halfedge_handle(h))) != h)
      return "face " + std::to_string(f.idx()) + " is not a triangle";
  }
  // Every outgoing halfedge is met once going round its vertex, and a vertex
  // with a boundary names a boundary halfedge.
  size_t outgoing = 0;
  for (auto v : om.vertices()) {
    const HH first = om.halfedge_handle(v);
    if (!first.is_valid()) return "vertex " + std::to_string(v.idx()) + " is isolated";
    if (om.from_vertex_handle(first) != v) return "vertex " + std::to_string(v.idx()) + ": halfedge not outgoing";
    bool boundary = false;
    for (auto h : om.voh_range(v)) {
      if (om.from_vertex_handle(h) != v || ++outgoing > om.n_halfedges()) return "vertex " + std::to_string(v.idx()) + ": ring broken";
      boundary |= om.is_boundary(h);
    }
    if (boundary && !om.is_boundary(first)) return "vertex " + std::to_string(v.idx()) + ": boundary not named";
  }
  if (outgoing != om.n_halfedges()) return "rings do not cover every halfedge";
  return "";
}

/// Removes `gone` from a copy of `before` and expects what is left to be
/// `before` without them: each kept face on the same vertices (followed
/// through the moves), glued to the same kept faces, its properties along;
/// every vertex and edge kept that a kept face uses, and no other.
void expect_removed(const OMesh& before, const std::vector<int32_t>& gone) {
  OMesh om = before;
  SlotMoves moves;
  om.remove_faces(gone, moves);
  ASSERT_EQ(broken_link(om), "");
  const std::vector<int32_t> face_was = replayed(before.n_faces(), moves.faces);
  const std::vector<int32_t> vertex_was = replayed(before.n_vertices(), moves.vertices);
  ASSERT_EQ(face_was.size(), om.n_faces());
  ASSERT_EQ(vertex_was.size(), om.n_vertices());
  ASSERT_EQ(om.n_faces(), before.n_faces() - gone.size());

  std::vector<char> kept_face(before.n_faces(), 1);
  for (int32_t f : gone) kept_face[size_t(f)] = 0;
  std::vector<char> used_vertex(before.n_vertices(), 0), used_edge(before.n_edges(), 0);
  OpenMesh::FPropHandleT<OpenMesh::Vec2s> pair_before, pair_after;
  ASSERT_TRUE(before.get_property_handle(pair_before, "pair"));
  ASSERT_TRUE(om.get_property_handle(pair_after, "pair"));
  for (auto f : om.faces()) {
    const FH was(face_was[size_t(f.idx())]);
    ASSERT_TRUE(kept_face[size_t(was.idx())]) << "face " << f.idx() << " was removed";
    EXPECT_EQ(om.property(pair_after, f), before.property(pair_before, was));
    HH h = om.halfedge_handle(f), w = before.halfedge_handle(was);
    for (int k = 0; k < 3; ++k, h = om.next_halfedge_handle(h), w = before.next_halfedge_handle(w)) {
      const VH v_was = before.to_vertex_handle(w);
      EXPECT_EQ(vertex_was[size_t(om.to_vertex_handle(h).idx())], v_was.idx()) << "face " << f.idx();
      EXPECT_EQ(om.point(om.to_vertex_handle(h)), before.point(v_was));
      used_vertex[size_t(v_was.idx())] = 1;
      used_edge[size_t(before.edge_handle(w).idx())] = 1;
      const FH across_was = before.opposite_face_handle(w);
      const FH across = om.opposite_face_handle(h);
      if (across_was.is_valid() && kept_face[size_t(across_was.idx())]) {
        ASSERT_TRUE(across.is_valid()) << "face " << f.idx() << " lost a neighbour";
        EXPECT_EQ(face_was[size_t(across.idx())], across_was.idx());
      } else {
        EXPECT_FALSE(across.is_valid()) << "face " << f.idx() << " glued to a removed face";
      }
    }
  }
  EXPECT_EQ(om.n_vertices(), size_t(std::count(used_vertex.begin(), used_vertex.end(), 1)));
  EXPECT_EQ(om.n_edges(), size_t(std::count(used_edge.begin(), used_edge.end(), 1)));
}

std::vector<int32_t> random_faces(size_t n, double share, std::mt19937& rng) {
  std::vector<int32_t> all = identity(n);
  std::shuffle(all.begin(), all.end(), rng);
  all.resize(size_t(double(n) * share));
  return all;
}

std::vector<NodeMesh> meshes() {
  return {two_cubes(3), four_phase_point(), box_t_junction(4), block_grains(3, 2), four_spheres(12)};
}

} // namespace

TEST(FaceRemoval, leaves_the_faces_kept_on_the_same_vertices_and_neighbours) {
  std::mt19937 rng(7);
  for (const NodeMesh& m : meshes()) {
    const InterfaceMesh im = InterfaceMesh::from_node_mesh(m);
    ASSERT_EQ(broken_link(im.omesh()), "");
    for (double share : {0.0, 0.01, 0.1, 0.5, 0.9, 1.0})
      for (int trial = 0; trial < 3; ++trial) {
        SCOPED_TRACE(testing::Message() << m.triangles.size() << " triangles, share " << share);
        expect_removed(im.omesh(), random_faces(im.num_triangles(), share, rng));
      }
  }
}

TEST(FaceRemoval, of_every_face_at_some_nodes_leaves_holes_that_add_face_closes) {
  // The local rebuild of an edit (docs/edits-in-place.md): every face at a
  // few nodes goes and comes back through add_face(), on new vertices where
  // the old ones went, glued as before.
  std::mt19937 rng(11);
  for (const NodeMesh& m : meshes()) {
    const InterfaceMesh im = InterfaceMesh::from_node_mesh(m);
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<int32_t> nodes;
      for (int k = 0; k < 3; ++k) nodes.push_back(int32_t(rng() % im.num_nodes()));
      const std::vector<int32_t> gone = im.faces_at(nodes);
      SCOPED_TRACE(testing::Message() << m.triangles.size() << " triangles, " << gone.size() << " removed");
      expect_removed(im.omesh(), gone);

      OMesh om = im.omesh();
      SlotMoves moves;
      om.remove_faces(gone, moves);
      const std::vector<int32_t> vertex_was = replayed(im.omesh().n_vertices(), moves.vertices);
      std::vector<VH> vertex_now(im.omesh().n_vertices());
      for (size_t v = 0; v < vertex_was.size(); ++v) vertex_now[size_t(vertex_was[v])] = VH(int(v));
      for (int32_t f : gone) {
        std::vector<VH> corners;
        for (auto v : im.omesh().fv_range(FH(f))) {
          if (!vertex_now[size_t(v.idx())].is_valid()) vertex_now[size_t(v.idx())] = om.add_vertex(im.omesh().point(v));
          corners.push_back(vertex_now[size_t(v.idx())]);
        }
        ASSERT_TRUE(om.add_face(corners).is_valid()) << "face " << f;
      }
      ASSERT_EQ(broken_link(om), "");
      EXPECT_EQ(om.n_faces(), im.omesh().n_faces());
      EXPECT_EQ(om.n_edges(), im.omesh().n_edges());
      EXPECT_EQ(om.n_vertices(), im.omesh().n_vertices());
    }
  }
}
