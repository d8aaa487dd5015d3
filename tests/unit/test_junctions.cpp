// Tests of find_junctions(): node phase sets, triple curves and quadruple points.

#include "fixtures.hpp"

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/mesh/junctions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

using namespace vm;

namespace {

/// Triangles on each node-edge {a < b}.
std::map<std::pair<int32_t, int32_t>, int> edge_uses(const NodeMesh& m) {
  std::map<std::pair<int32_t, int32_t>, int> uses;
  for (const auto& t : m.triangles)
    for (size_t k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  return uses;
}

/// The union of the pairs of the triangles around each node.
std::vector<std::set<int32_t>> phases_by_brute_force(const NodeMesh& m) {
  std::vector<std::set<int32_t>> phases(m.num_nodes());
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int32_t v : m.triangles[t]) phases[size_t(v)].insert(m.pairs[t].begin(), m.pairs[t].end());
  return phases;
}

/// Every junction edge lies on exactly one curve, every curve edge is a junction edge.
void expect_curves_cover_junction_edges(const NodeMesh& m, const Junctions& j) {
  std::map<std::pair<int32_t, int32_t>, int> on_curves;
  for (const TripleCurve& c : j.curves)
    for (size_t i = 0; i < c.num_edges(); ++i)
      ++on_curves[{std::min(c.nodes[i], c.nodes[i + 1]), std::max(c.nodes[i], c.nodes[i + 1])}];
  size_t junction_edges = 0;
  for (const auto& [edge, uses] : edge_uses(m)) {
    if (uses < 3) {
      EXPECT_EQ(on_curves.count(edge), 0u) << "edge " << edge.first << "-" << edge.second << " is no junction";
      continue;
    }
    ++junction_edges;
    EXPECT_EQ(on_curves[edge], 1) << "junction edge " << edge.first << "-" << edge.second;
  }
  EXPECT_EQ(on_curves.size(), junction_edges);
}

} // namespace

TEST(Junctions, four_spheres_have_ten_triple_curves_between_five_quadruple_points) {
  const NodeMesh m = test::four_spheres();
  const Junctions j = find_junctions(m);
  const auto brute = phases_by_brute_force(m);
  for (size_t n = 0; n < m.num_nodes(); ++n) {
    const auto at = j.phases_at(n);
    EXPECT_EQ(std::set<int32_t>(at.begin(), at.end()), brute[n]) << "node " << n;
    EXPECT_TRUE(std::is_sorted(at.begin(), at.end()));
    EXPECT_EQ(size_t(j.order(n)), brute[n].size());
  }
  ASSERT_EQ(j.quadruple_points.size(), 5u);
  for (int32_t q : j.quadruple_points) EXPECT_EQ(j.order(size_t(q)), 4);
  ASSERT_EQ(j.curves.size(), 10u);
  std::set<std::vector<int32_t>> triples;
  for (const TripleCurve& c : j.curves) {
    EXPECT_EQ(c.phases.size(), 3u);
    triples.insert(c.phases);
    EXPECT_FALSE(c.closed());
    EXPECT_LT(c.nodes.front(), c.nodes.back());
    // Both ends are quadruple points; every node between them is on three phases, the curve's.
    for (int32_t end : {c.nodes.front(), c.nodes.back()})
      EXPECT_TRUE(std::binary_search(j.quadruple_points.begin(), j.quadruple_points.end(), end));
    for (size_t i = 1; i + 1 < c.nodes.size(); ++i) {
      const auto at = j.phases_at(size_t(c.nodes[i]));
      EXPECT_EQ(std::vector<int32_t>(at.begin(), at.end()), c.phases);
    }
  }
  EXPECT_EQ(triples.size(), 10u) << "the 10 triples of 5 phases, one curve each";
  EXPECT_TRUE(std::is_sorted(j.curves.begin(), j.curves.end(),
                             [](const TripleCurve& a, const TripleCurve& b) { return a.phases < b.phases; }));
  expect_curves_cover_junction_edges(m, j);
  const MeshStats s = compute_stats(m);
  EXPECT_EQ(s.triple_curves, j.curves.size());
  EXPECT_EQ(s.quadruple_points, j.quadruple_points.size());
}

TEST(Junctions, closed_curve_starts_at_its_smallest_node) {
  for (int n : {1, 3}) {
    const NodeMesh m = test::two_cubes(n);
    const Junctions j = find_junctions(m);
    ASSERT_EQ(j.curves.size(), 1u);
    const TripleCurve& c = j.curves[0];
    EXPECT_EQ(c.phases, (std::vector<int32_t>{0, 1, 2}));
    EXPECT_TRUE(c.closed());
    EXPECT_EQ(c.num_edges(), size_t(4 * n)) << "the square around x = 1";
    EXPECT_EQ(c.nodes.front(), *std::min_element(c.nodes.begin(), c.nodes.end()));
    EXPECT_LT(c.nodes[1], c.nodes[c.nodes.size() - 2]) << "runs towards the smaller neighbour";
    EXPECT_TRUE(j.quadruple_points.empty());
    expect_curves_cover_junction_edges(m, j);
  }
}

TEST(Junctions, curve_ending_on_the_box) {
  const NodeMesh m = test::box_t_junction(4);
  const Junctions j = find_junctions(m);
  ASSERT_EQ(j.curves.size(), 1u);
  const TripleCurve& c = j.curves[0];
  EXPECT_FALSE(c.closed());
  EXPECT_EQ(c.num_edges(), 4u);
  EXPECT_EQ(m.points[size_t(c.nodes.front())].z() + m.points[size_t(c.nodes.back())].z(), 1.0) << "z = 0 to z = 1";
  EXPECT_EQ(j.order(size_t(c.nodes.front())), 3);
  EXPECT_TRUE(j.quadruple_points.empty());
}

TEST(Junctions, four_phase_point_has_single_edge_curves) {
  const NodeMesh m = test::four_phase_point();
  const Junctions j = find_junctions(m);
  EXPECT_EQ(j.quadruple_points.size(), 5u);
  ASSERT_EQ(j.curves.size(), 10u);
  for (const TripleCurve& c : j.curves) EXPECT_EQ(c.num_edges(), 1u);
  expect_curves_cover_junction_edges(m, j);
}

TEST(Junctions, do_not_depend_on_the_triangle_order) {
  NodeMesh m = test::four_spheres();
  const Junctions j = find_junctions(m);
  std::reverse(m.triangles.begin(), m.triangles.end());
  std::reverse(m.pairs.begin(), m.pairs.end());
  for (auto& t : m.triangles) std::rotate(t.begin(), t.begin() + 1, t.end());
  const Junctions k = find_junctions(m);
  EXPECT_EQ(k.phase_offsets, j.phase_offsets);
  EXPECT_EQ(k.phase_ids, j.phase_ids);
  EXPECT_EQ(k.quadruple_points, j.quadruple_points);
  ASSERT_EQ(k.curves.size(), j.curves.size());
  for (size_t c = 0; c < j.curves.size(); ++c) EXPECT_EQ(k.curves[c].nodes, j.curves[c].nodes) << "curve " << c;
}

TEST(Junctions, malformed_triangles_are_left_out) {
  NodeMesh m = test::tetrahedron();
  m.triangles.push_back({0, 0, 1});
  m.triangles.push_back({0, 1, 99});
  m.pairs.push_back({0, 2});
  const Junctions j = find_junctions(m);
  for (size_t n = 0; n < m.num_nodes(); ++n) EXPECT_EQ(j.order(n), 2);
  EXPECT_TRUE(j.curves.empty());
}
