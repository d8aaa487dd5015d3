// InterfaceMesh::apply_edit() (mesh/interface_mesh_edit.cpp): the build of an
// edited mesh that carries over what did not change, in the OpenMesh arrays of
// the mesh it edits, must be the build from_node_mesh() makes, array for array,
// after flips have reordered fans, for collapses, splits, and edits that keep
// nothing or everything, and edit after edit in the same arrays.

#include "fixtures.hpp"
#include "same_build.hpp"

#include "improve/node_merge.hpp"

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/registry.hpp"
#include "voronoimesh/improve/remesh.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include <gtest/gtest.h>

#include <numeric>

namespace {

using namespace vm;

/// Seven Voronoi cells after a few iterations of the paper's passes: flips
/// have changed which faces each copy has, so the fans' first triangles are
/// no longer in the order their copies were numbered.
InterfaceMesh flipped_voronoi7() {
  const Scene scene = test::example_scene("voronoi7.json", 24);
  InterfaceMesh mesh = test::initial_mesh(scene);
  Pipeline::parse("smooth,project,clamp,flip", builtin_registry()).run(mesh, scene.field.get(), test::iterations(3));
  return mesh;
}

/// A copy of `mesh` with apply_edit() done.
InterfaceMesh edited_copy(const InterfaceMesh& mesh, const NodeMesh& m, std::span<const int32_t> triangle_was,
                          std::span<const int32_t> node_was) {
  InterfaceMesh copy = mesh;
  copy.apply_edit(m, triangle_was, node_was);
  return copy;
}

/// Expects the build of `edited` (unused nodes dropped here; its triangles
/// were `triangle_was` of `mesh`) from `mesh` to be from_node_mesh()'s.
void expect_edit_built_as_anew(const InterfaceMesh& mesh, NodeMesh edited, const std::vector<int32_t>& triangle_was) {
  std::vector<int32_t> node_was;
  detail::drop_unused_nodes(edited, node_was);
  EXPECT_EQ(test::build_difference(edited_copy(mesh, edited, triangle_was, node_was),
                                   InterfaceMesh::from_node_mesh(edited)),
            "");
}

TEST(InterfaceMeshEdit, collapses_and_splits_of_the_remesh_pass_build_as_anew) {
  InterfaceMesh mesh = flipped_voronoi7();
  const double rms = rms_edge_length(mesh);
  RemeshParams params;
  // Mostly collapses, then mostly splits; each call again changes a few
  // nodes only (the first of each changes most, and is built anew), each in
  // the arrays the call before left.
  for (double size : {1.6, 1.6, 0.7, 0.7}) {
    params.size = size;
    const RemeshStats done = remesh_edges(mesh, nullptr, rms, params);
    ASSERT_GT(done.collapses + done.splits, 0u) << size;
    test::expect_built_as_anew(mesh, "remesh size " + std::to_string(size));
  }
}

TEST(InterfaceMeshEdit, merging_junction_nodes_builds_as_anew) {
  const InterfaceMesh mesh = flipped_voronoi7();
  const NodeMesh before = mesh.to_node_mesh();
  // Every tenth triple-curve node merges into a neighbour on its curve (nodes
  // with two copies or more in a patch's fans, whose classes change most).
  std::vector<int32_t> into(before.num_nodes(), -1);
  std::vector<uint8_t> touched(before.num_nodes(), 0);
  size_t merges = 0;
  for (int32_t b = 0; b < int32_t(before.num_nodes()); b += 10) {
    if (junction_order(mesh, b) != 3 || touched[size_t(b)]) continue;
    for (int32_t a : mesh.neighbours(b))
      if (junction_order(mesh, a) >= 3 && mesh.constraints_within(b, a) && !touched[size_t(a)]) {
        into[size_t(b)] = a, ++merges;
        touched[size_t(b)] = touched[size_t(a)] = 1;
        for (int32_t w : mesh.neighbours(b)) touched[size_t(w)] = 1;
        for (int32_t w : mesh.neighbours(a)) touched[size_t(w)] = 1;
        break;
      }
  }
  ASSERT_GT(merges, 5u);
  NodeMesh merged;
  std::vector<int32_t> turned, triangle_was;
  detail::merge_nodes(before, into, merged, turned, triangle_was);
  expect_edit_built_as_anew(mesh, merged, triangle_was);
}

TEST(InterfaceMeshEdit, dropping_triangles_builds_as_anew) {
  // Holes in the surfaces: nodes around them lose triangles and nothing else.
  const InterfaceMesh mesh = flipped_voronoi7();
  const NodeMesh m = mesh.to_node_mesh();
  NodeMesh holed = m.empty_like();
  holed.points = m.points;
  std::vector<int32_t> triangle_was;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    if (t % 40 != 7) {
      holed.triangles.push_back(m.triangles[t]);
      holed.pairs.push_back(m.pairs[t]);
      triangle_was.push_back(int32_t(t));
    }
  expect_edit_built_as_anew(mesh, holed, triangle_was);
}

TEST(InterfaceMeshEdit, keeping_everything_or_nothing_builds_as_anew) {
  const InterfaceMesh mesh = flipped_voronoi7();
  const NodeMesh m = mesh.to_node_mesh();
  std::vector<int32_t> triangles(m.num_triangles()), nodes(m.num_nodes());
  std::iota(triangles.begin(), triangles.end(), 0);
  std::iota(nodes.begin(), nodes.end(), 0);
  const InterfaceMesh anew = InterfaceMesh::from_node_mesh(m);
  EXPECT_EQ(test::build_difference(edited_copy(mesh, m, triangles, nodes), anew), "");
  std::fill(triangles.begin(), triangles.end(), -1);
  std::fill(nodes.begin(), nodes.end(), -1);
  EXPECT_EQ(test::build_difference(edited_copy(mesh, m, triangles, nodes), anew), "");
  // Maps that do not describe an edit of the mesh (too short, out of order) build it anew too.
  EXPECT_EQ(test::build_difference(edited_copy(mesh, m, {}, {}), anew), "");
  std::iota(nodes.rbegin(), nodes.rend(), 0);
  EXPECT_EQ(test::build_difference(edited_copy(mesh, m, triangles, nodes), anew), "");
}

} // namespace
