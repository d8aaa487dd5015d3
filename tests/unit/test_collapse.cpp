// Collapsing junction slivers (improve/collapse.hpp): triangles that no flip may mend
// because their short edge lies along a junction.

#include "fixtures.hpp"

#include "improve/node_merge.hpp"

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/improve/collapse.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using namespace vm;

/// Three fins meeting along a triple line on the x axis, in the box
/// [0,3]x[-1,1]x[-1,1]: phase 0 for angles (in the y-z plane) in (-30, 90)
/// degrees, 1 in (90, 210), 2 in (210, 330). The line's nodes sit at `line_x`;
/// each fin has a row of nodes halfway out (surface nodes, but for the two on
/// the box) and a row at its end on the box, both at x = 0..3. Pairs and
/// orientations follow from which phase lies on each side.
NodeMesh three_fins(const std::vector<double>& line_x) {
  NodeMesh m;
  m.domain = {Vec3(0, -1, -1), Vec3(3, 1, 1)};
  std::vector<int32_t> line;
  for (double x : line_x) {
    line.push_back(int32_t(m.points.size()));
    m.points.push_back(Vec3(x, 0, 0));
  }
  const double pi = std::acos(-1.0);
  auto phase_at = [&](const Vec3& p) {
    double a = std::atan2(p.z(), p.y());
    if (a < -pi / 6) a += 2 * pi; // now in [-30, 330) degrees
    return a < pi / 2 ? 0 : a < 7 * pi / 6 ? 1 : 2;
  };
  // Triangles between two rows of nodes ordered by x, advancing along the row
  // whose next node comes first.
  auto strip = [&](const std::vector<int32_t>& a, const std::vector<int32_t>& b) {
    size_t i = 0, j = 0;
    while (i + 1 < a.size() || j + 1 < b.size()) {
      const bool advance_a =
          j + 1 == b.size() || (i + 1 < a.size() && m.points[size_t(a[i + 1])].x() < m.points[size_t(b[j + 1])].x());
      std::array<int32_t, 3> t = advance_a ? std::array{a[i], a[i + 1], b[j]} : std::array{a[i], b[j + 1], b[j]};
      advance_a ? ++i : ++j;
      const Vec3 &p = m.points[size_t(t[0])], &q = m.points[size_t(t[1])], &r = m.points[size_t(t[2])];
      const Vec3 n = (q - p).cross(r - p).normalized(), centre = (p + q + r) / 3;
      const int front = phase_at(centre + 1e-3 * n), back = phase_at(centre - 1e-3 * n);
      if (front < back) std::swap(t[1], t[2]); // the normal must point into the higher phase
      m.triangles.push_back(t);
      m.pairs.push_back({std::min(front, back), std::max(front, back)});
    }
  };
  for (double angle : {pi / 2, 7 * pi / 6, 11 * pi / 6}) {
    // Along (cos, sin) in the y-z plane, scaled to end on the box.
    const double reach = 1 / std::max(std::abs(std::cos(angle)), std::abs(std::sin(angle)));
    std::vector<int32_t> middle, end;
    for (int x = 0; x <= 3; ++x) {
      middle.push_back(int32_t(m.points.size()));
      m.points.push_back(Vec3(x, 0.5 * reach * std::cos(angle), 0.5 * reach * std::sin(angle)));
      end.push_back(int32_t(m.points.size()));
      m.points.push_back(Vec3(x, reach * std::cos(angle), reach * std::sin(angle)));
    }
    strip(line, middle);
    strip(middle, end);
  }
  return m;
}

double worst_quality(const NodeMesh& m) {
  double worst = 1;
  for (const auto& t : m.triangles)
    worst = std::min(worst, triangle_quality(m.points[size_t(t[0])], m.points[size_t(t[1])], m.points[size_t(t[2])]));
  return worst;
}

TEST(Collapse, the_fixture_is_valid_and_well_shaped_without_bunched_nodes) {
  const NodeMesh m = three_fins({0, 1, 2, 3});
  const ValidationReport report = validate(m);
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_GT(worst_quality(m), 0.3);
}

// Two nodes 1e-4 apart on a triple curve: each fin has a sliver whose short
// edge lies along the curve and whose third corner is a surface node (halfway
// out, at x = 1). One collapse along the curve removes all three.
TEST(Collapse, nodes_bunched_on_a_triple_curve_are_merged) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(three_fins({0, 1, 1.0001, 2, 3}));
  ASSERT_TRUE(validate(mesh.to_node_mesh()).ok());
  ASSERT_LT(worst_quality(mesh.to_node_mesh()), 1e-3);
  EXPECT_EQ(collapse_junction_slivers(mesh), 1u);
  const NodeMesh after = mesh.to_node_mesh();
  const ValidationReport report = validate(after);
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_EQ(after.num_nodes(), 4u + 3 * 8u);
  EXPECT_GT(worst_quality(after), 0.05);
}

TEST(Collapse, collapses_nothing_when_off_or_without_slivers) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(three_fins({0, 1, 1.0001, 2, 3}));
  CollapseParams off;
  off.below_quality = 0;
  EXPECT_EQ(collapse_junction_slivers(mesh, off), 0u);
  InterfaceMesh fine = InterfaceMesh::from_node_mesh(three_fins({0, 1, 2, 3}));
  EXPECT_EQ(collapse_junction_slivers(fine), 0u);
}

// A closed surface: an octahedron whose lower apex sits just under its waist.
// Merging the upper apex into a waist corner flattens the top into the waist's
// plane: no triangle turns over and the surface stays valid, but across the
// waist it turns back by 174 degrees onto the low bottom, a fold.
TEST(Collapse, a_merge_that_folds_a_surface_fails_when_folds_are_refused) {
  NodeMesh m;
  m.domain = {Vec3(-2, -2, -2), Vec3(2, 2, 2)};
  m.points = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -0.1)};
  const int32_t px = 0, nx = 1, py = 2, ny = 3, top = 4, bottom = 5;
  m.triangles = {{px, py, top}, {py, nx, top}, {nx, ny, top}, {ny, px, top},
                 {py, px, bottom}, {nx, py, bottom}, {ny, nx, bottom}, {px, ny, bottom}};
  m.pairs.assign(m.triangles.size(), PhasePair{0, 1});
  ASSERT_TRUE(validate(m).ok()) << validate(m).summary();
  ASSERT_EQ(count_folds(m), 0u);
  std::vector<int32_t> into(m.num_nodes(), -1), turned, kept;
  into[size_t(top)] = px;
  NodeMesh trial;
  detail::merge_nodes(m, into, trial, turned, kept);
  ASSERT_TRUE(turned.empty());
  NodeMesh compacted = trial; // the merged-away apex stays behind, a node of no triangle
  std::vector<int32_t> kept_nodes;
  detail::drop_unused_nodes(compacted, kept_nodes);
  ASSERT_TRUE(validate(compacted).ok()) << validate(compacted).summary();
  ASSERT_GT(count_folds(trial), 0u);
  std::vector<int32_t> failed;
  EXPECT_TRUE(detail::find_merge_failures(trial, into, {}, failed));
  EXPECT_TRUE(failed.empty());
  EXPECT_TRUE(detail::find_merge_failures(trial, into, {.refuse_surface_folds = true}, failed));
  EXPECT_NE(std::find(failed.begin(), failed.end(), px), failed.end());
}

// The initial mesh of 30 Voronoi cells at grid 32 has thousands of junction
// triangles below q 0.5: one call makes an eighth as many collapses as it has
// candidates (a fixed 64 left most slivers of big meshes standing), and none
// that folds a surface at the nodes it keeps.
TEST(Collapse, a_call_with_many_candidates_makes_more_than_64_and_folds_no_surface) {
  InterfaceMesh mesh = test::initial_mesh(test::example_scene("voronoi30.json", 32));
  const size_t folds_before = count_folds(mesh.to_node_mesh());
  CollapseParams params;
  params.below_quality = 0.5;
  EXPECT_GT(collapse_junction_slivers(mesh, params), 64u);
  const NodeMesh after = mesh.to_node_mesh();
  const ValidationReport report = validate(after);
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_LE(count_folds(after), folds_before);
}

} // namespace
