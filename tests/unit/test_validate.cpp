#include "fixtures.hpp"

#include "voronoimesh/mesh.hpp"
#include "voronoimesh/validate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace vm;

namespace {

/// True when some problem line starts with `kind` and contains `detail`.
bool reports(const ValidationReport& r, const std::string& kind, const std::string& detail = "") {
  for (const auto& p : r.problems)
    if (p.rfind(kind + ":", 0) == 0 && p.find(detail) != std::string::npos) return true;
  return false;
}

NodeMesh two_tets_sharing(const std::array<Vec3, 4>& second, int inside2 = 1, int outside2 = 0) {
  test::Builder b;
  test::add_tetrahedron(b, test::corner_tet(Vec3::Zero(), 1), 1, 0);
  test::add_tetrahedron(b, second, inside2, outside2);
  return b.mesh;
}

} // namespace

TEST(Validate, fixtures_are_valid) {
  for (const NodeMesh& m :
       {test::tetrahedron(), test::two_cubes(1), test::two_cubes(3), test::four_phase_point(), test::box_t_junction(2),
        test::box_t_junction(6), test::block_grains(2, 1), test::block_grains(3, 2)}) {
    const auto r = validate(m);
    EXPECT_TRUE(r.ok()) << r.summary();
    EXPECT_EQ(r.problem_count, 0u);
    const auto ri = validate(InterfaceMesh::from_node_mesh(m));
    EXPECT_TRUE(ri.ok()) << ri.summary();
  }
}

TEST(Validate, flipped_triangle_is_an_orientation_problem) {
  NodeMesh m = test::two_cubes(1);
  std::swap(m.triangles[3][0], m.triangles[3][1]);
  const auto r = validate(m);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(reports(r, "orientation", "triangles 3")) << r.summary();
  EXPECT_TRUE(reports(validate(InterfaceMesh::from_node_mesh(m)), "orientation"));
}

TEST(Validate, missing_triangle_leaves_an_open_boundary) {
  NodeMesh m = test::tetrahedron();
  auto hole = m.triangles.back();
  m.triangles.pop_back();
  m.pairs.pop_back();
  const auto r = validate(m);
  EXPECT_TRUE(reports(r, "open boundary", "phase 0")) << r.summary();
  EXPECT_TRUE(reports(r, "open boundary", "phase 1")) << r.summary();
  EXPECT_EQ(r.problem_count, 6u); // 3 edges x 2 phases
  std::sort(hole.begin(), hole.end());
  EXPECT_EQ(r.nodes, std::vector<int32_t>(hole.begin(), hole.end())); // the hole's rim
}

TEST(Validate, duplicate_triangle_is_reported_in_any_corner_order) {
  NodeMesh m = test::tetrahedron();
  auto t = m.triangles[1];
  m.triangles.push_back({t[2], t[1], t[0]});
  m.pairs.push_back(m.pairs[1]);
  const auto r = validate(m);
  EXPECT_TRUE(reports(r, "duplicate triangle", "triangles 1 4")) << r.summary();
}

TEST(Validate, tetrahedra_touching_at_a_vertex_are_a_non_manifold_node) {
  const NodeMesh m = two_tets_sharing(test::corner_tet(Vec3::Zero(), -1));
  const int32_t origin = int32_t(std::find(m.points.begin(), m.points.end(), Vec3::Zero()) - m.points.begin());
  const auto r = validate(m);
  const std::string at = " at node " + std::to_string(origin);
  EXPECT_TRUE(reports(r, "non-manifold node", "phase 1" + at + " has 2 separate fans")) << r.summary();
  EXPECT_TRUE(reports(r, "non-manifold node", "phase 0" + at)) << r.summary();
  EXPECT_EQ(r.problem_count, 2u) << r.summary();
  EXPECT_EQ(r.nodes, std::vector<int32_t>{origin});
  EXPECT_FALSE(reports(r, "orientation"));
  EXPECT_FALSE(reports(r, "open boundary"));
}

TEST(Validate, tetrahedra_touching_along_an_edge_are_a_non_manifold_edge) {
  const auto m = two_tets_sharing({Vec3(0, 0, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)});
  const auto r = validate(m);
  EXPECT_TRUE(reports(r, "non-manifold edge", "phase 1")) << r.summary();
  EXPECT_TRUE(reports(r, "junction", "phase 0 on 4 of them")) << r.summary();
  const auto ri = validate(InterfaceMesh::from_node_mesh(m));
  EXPECT_TRUE(reports(ri, "non-manifold edge")) << ri.summary();
}

TEST(Validate, junction_of_two_separate_cycles_is_reported) {
  // Phase 1 in 0 and phase 3 in 2 share an edge: every phase boundary is closed
  // and manifold, but the edge carries two cycles of pairs.
  const auto r = validate(two_tets_sharing({Vec3(0, 0, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)}, 3, 2));
  EXPECT_EQ(r.problem_count, 1u) << r.summary();
  EXPECT_TRUE(reports(r, "junction", "2 separate cycles of pairs")) << r.summary();
}

TEST(Validate, malformed_triangles_are_reported_not_crashed_on) {
  NodeMesh m = test::two_cubes(1);
  m.triangles[0] = {0, 0, 1};
  m.triangles[1][2] = 99;
  m.triangles[2][2] = -1;
  m.pairs[4] = {2, 1};
  m.pairs[5] = {-1, 1};
  const auto r = validate(m);
  EXPECT_TRUE(reports(r, "repeated node", "triangle 0 (0, 0, 1)")) << r.summary();
  EXPECT_TRUE(reports(r, "node out of range", "triangle 1")) << r.summary();
  EXPECT_TRUE(reports(r, "node out of range", "has node -1")) << r.summary();
  EXPECT_TRUE(reports(r, "bad pair", "triangle 4 has pair (2, 1)")) << r.summary();
  EXPECT_TRUE(reports(r, "bad pair", "triangle 5 has pair (-1, 1)")) << r.summary();
}

TEST(Validate, phase_ids_are_checked_against_the_names) {
  NodeMesh m = test::two_cubes(1);
  m.phase_names = {"outside", "left"}; // phase 2 has no name
  const auto r = validate(m);
  EXPECT_TRUE(reports(r, "bad pair", "has pair (1, 2) (need 0 <= p < q < 2)")) << r.summary();
  m.phase_names.push_back("right");
  EXPECT_TRUE(validate(m).ok());
}

TEST(Validate, zero_area_and_non_finite_triangles) {
  NodeMesh m = test::tetrahedron();
  m.points[3] = (m.points[0] + m.points[1]) / 2; // flattens the two faces on nodes 0, 1, 3
  auto r = validate(m);
  EXPECT_TRUE(reports(r, "zero area")) << r.summary();
  m = test::tetrahedron();
  m.points[2].y() = std::numeric_limits<double>::quiet_NaN();
  r = validate(m);
  EXPECT_TRUE(reports(r, "zero area", "non-finite coordinate")) << r.summary();
  // A thin but valid triangle is not zero-area.
  m = test::tetrahedron();
  m.points[3] = Vec3(0.5, 0.5, 1e-5);
  EXPECT_FALSE(reports(validate(m), "zero area"));
}

TEST(Validate, open_edges_are_allowed_only_on_the_domain_box) {
  NodeMesh m = test::box_t_junction(2);
  EXPECT_TRUE(validate(m).ok());
  m.domain.max.z() = 2; // the top edges are no longer on the box
  const auto r = validate(m);
  EXPECT_TRUE(reports(r, "open boundary", "not on the domain box")) << r.summary();
  // Only the top edges: 2 on x = 1/2 and 1 on y = 1/2, each open for both its phases.
  EXPECT_EQ(r.problem_count, 6u) << r.summary();
}

TEST(Validate, keeps_twenty_lines_and_counts_all) {
  NodeMesh m = test::tetrahedron();
  for (int i = 0; i < 30; ++i) {
    m.triangles.push_back({0, 0, 1});
    m.pairs.push_back({0, 1});
  }
  const auto r = validate(m);
  EXPECT_EQ(r.problems.size(), 20u);
  EXPECT_EQ(r.problem_count, 30u);
  EXPECT_NE(r.summary().find("... and 10 more problems"), std::string::npos);
}

TEST(Validate, stale_point_mirror_is_caught) {
  auto im = InterfaceMesh::from_node_mesh(test::tetrahedron());
  // No API moves points behind the mesh's back; emulate such a bug.
  auto& om = const_cast<OMesh&>(im.omesh());
  om.set_point(OMesh::VertexHandle(2), OMesh::Point(5, 5, 5));
  const auto r = validate(im);
  EXPECT_TRUE(reports(r, "stale point", "OpenMesh vertex 2")) << r.summary();
}
