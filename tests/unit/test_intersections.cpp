#include "fixtures.hpp"

#include "check/embedded_fans.hpp"
#include "check/triangle_pair.hpp"

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/core/errors.hpp"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <utility>

using namespace vm;

namespace {

using Pair = std::array<int32_t, 2>;

/// A mesh of the given points and triangles (no phase data needed here).
NodeMesh soup(std::vector<Vec3> points, std::vector<std::array<int32_t, 3>> triangles) {
  NodeMesh m;
  m.points = std::move(points);
  m.triangles = std::move(triangles);
  m.pairs.assign(m.triangles.size(), PhasePair{0, 1});
  return m;
}

size_t count(const NodeMesh& m) { return find_self_intersections(m).count; }

/// Whether the two triangles, alone, intersect improperly.
bool pair_intersects(const NodeMesh& m, size_t t, size_t s) {
  return count(soup(m.points, {m.triangles[t], m.triangles[s]})) > 0;
}

/// Icosahedron subdivided `levels` times, on the unit sphere.
NodeMesh icosphere(int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> p{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                      {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int32_t, 3>> t{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                        {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                        {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                        {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (Vec3& v : p) v.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int32_t, int32_t>, int32_t> mid;
    auto middle = [&](int32_t a, int32_t b) {
      auto [it, added] = mid.try_emplace({std::min(a, b), std::max(a, b)}, int32_t(p.size()));
      if (added) p.push_back((p[size_t(a)] + p[size_t(b)]).normalized());
      return it->second;
    };
    std::vector<std::array<int32_t, 3>> next;
    for (const auto& [a, b, c] : t) {
      const int32_t ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    t = std::move(next);
  }
  return soup(std::move(p), std::move(t));
}

/// Splits triangle t at a point close to its first corner: (1 - 2 e) a + e b + e c.
void split_near_corner(NodeMesh& m, size_t t, double e) {
  const auto [a, b, c] = m.triangles[t];
  const Vec3 q = (1 - 2 * e) * m.points[size_t(a)] + e * m.points[size_t(b)] + e * m.points[size_t(c)];
  const auto p = int32_t(m.points.size());
  m.points.push_back(q);
  m.triangles[t] = {a, b, p};
  m.triangles.push_back({b, c, p});
  m.triangles.push_back({c, a, p});
  m.pairs.resize(m.triangles.size(), PhasePair{0, 1});
}

const Vec3 O(0, 0, 0), X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);

} // namespace

TEST(Intersections, closed_surfaces_and_junctions_of_the_fixtures_are_clean) {
  EXPECT_EQ(count(test::tetrahedron()), 0u);
  EXPECT_EQ(count(test::two_cubes(1)), 0u);
  EXPECT_EQ(count(test::two_cubes(4)), 0u);
  EXPECT_EQ(count(test::four_phase_point()), 0u);
  EXPECT_EQ(count(test::box_t_junction(6)), 0u);
  EXPECT_EQ(count(test::block_grains(3, 4)), 0u); // edges of 4 and corners of 6 surfaces
}

TEST(Intersections, disjoint_tetrahedra_are_clean) {
  test::Builder b;
  test::add_tetrahedron(b, test::corner_tet(O, 1), 1, 0);
  test::add_tetrahedron(b, test::corner_tet(Vec3(0.5, 0.5, 0.5), 1), 2, 0); // beyond the slanted face
  test::add_tetrahedron(b, test::corner_tet(Vec3(-0.1, -0.1, -0.1), -1), 3, 0);
  EXPECT_EQ(count(b.mesh), 0u);
}

TEST(Intersections, interpenetrating_tetrahedra_report_the_crossing_faces) {
  test::Builder b;
  test::add_tetrahedron(b, test::corner_tet(O, 1), 1, 0);
  // Apex inside the first tetrahedron, base far beyond its slanted face x+y+z = 1.
  test::add_tetrahedron(b, {Vec3(0.2, 0.2, 0.2), Vec3(2, 1, 1), Vec3(1, 2, 1), Vec3(1, 1, 2)}, 2, 0);
  // add_tetrahedron writes face i opposite corner i: face 0 is the slanted face
  // of the first, faces 5, 6, 7 hold the apex of the second, face 4 is its base.
  const IntersectionReport r = find_self_intersections(b.mesh);
  EXPECT_EQ(r.count, 3u);
  EXPECT_EQ(r.pairs, (std::vector<Pair>{{0, 5}, {0, 6}, {0, 7}}));
  EXPECT_FALSE(r.ok());
}

TEST(Intersections, shared_edge_fold_in_one_plane_is_reported) {
  // Plane z = 0: the second triangle lies on the same side of the shared edge OX.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.5, 0.25, 0)}, {{0, 1, 2}, {1, 0, 3}})), 1u);
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.5, -0.25, 0)}, {{0, 1, 2}, {1, 0, 3}})), 0u);
  // Exactly coplanar on the tilted plane x + y + z = 1 (only the exact stage can tell).
  const Vec3 q(0.25, 0.25, 0.5), r(0.75, 0.75, -0.5);
  EXPECT_EQ(count(soup({X, Y, Z, q}, {{0, 1, 2}, {1, 0, 3}})), 1u);
  EXPECT_EQ(count(soup({X, Y, Z, r}, {{0, 1, 2}, {1, 0, 3}})), 0u);
  // A fold by a non-zero angle, however small, is not an intersection.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.5, 0.25, 1e-20)}, {{0, 1, 2}, {1, 0, 3}})), 0u);
}

TEST(Intersections, junction_edge_with_three_fins_is_clean) {
  std::vector<Vec3> p{O, Z};
  std::vector<std::array<int32_t, 3>> t;
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * std::numbers::pi * k / 3;
    p.push_back(Vec3(std::cos(a), std::sin(a), 0.5));
    t.push_back({0, 1, int32_t(p.size() - 1)});
  }
  EXPECT_EQ(count(soup(p, t)), 0u);
  // A fourth fin in the plane of the first one, on its side: folded onto it.
  p.push_back(Vec3(0.5, 0, 0.5));
  t.push_back({1, 0, int32_t(p.size() - 1)});
  EXPECT_EQ(find_self_intersections(soup(p, t)).pairs, (std::vector<Pair>{{0, 3}}));
}

TEST(Intersections, fans_around_a_shared_vertex) {
  // A flat hexagonal fan and a pyramid-like cone around O: valid.
  std::vector<Vec3> p{O};
  std::vector<std::array<int32_t, 3>> flat, cone;
  for (int k = 0; k < 6; ++k) {
    const double a = k * std::numbers::pi / 3;
    p.push_back(Vec3(std::cos(a), std::sin(a), 0));
  }
  for (int32_t k = 0; k < 6; ++k) flat.push_back({0, 1 + k, 1 + (k + 1) % 6});
  EXPECT_EQ(count(soup(p, flat)), 0u);
  for (int k = 1; k <= 6; ++k) p.push_back(p[size_t(k)] + Vec3(0, 0, 0.3 * (k % 2 ? 1 : -1)));
  for (int32_t k = 0; k < 6; ++k) cone.push_back({0, 7 + k, 7 + (k + 1) % 6});
  EXPECT_EQ(count(soup(p, cone)), 0u);

  // Sharing only O, one inside the other's wedge in one plane: overlap.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(1, 1, 0), Vec3(2, 1, 0)}, {{0, 1, 2}, {0, 3, 4}})), 1u);
  // Sharing only O, wedges touching along a segment from O: overlap too.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(2, 0, 0), Vec3(1, -1, 0)}, {{0, 1, 2}, {0, 3, 4}})), 1u);
  EXPECT_EQ(count(soup({O, X, Y, Vec3(2, 0, 0), Vec3(1, -1, 1)}, {{0, 1, 2}, {0, 3, 4}})), 1u);
  // ...but wedges meeting at O only are fine, in one plane or not.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(-1, 0, 0), Vec3(0, -1, 0)}, {{0, 1, 2}, {0, 3, 4}})), 0u);
  EXPECT_EQ(count(soup({O, X, Y, Vec3(-1, 0, 0), Vec3(0, -1, 1)}, {{0, 1, 2}, {0, 3, 4}})), 0u);
  // Sharing only O, the opposite edge of the second pierces the first.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.3, 0.3, -1), Vec3(0.3, 0.3, 1)}, {{0, 1, 2}, {0, 3, 4}})), 1u);
  // Sharing only O, the second crosses the plane of the first only at O.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(-0.3, -0.3, -1), Vec3(-0.3, -0.3, 1)}, {{0, 1, 2}, {0, 3, 4}})), 0u);
}

TEST(Intersections, poking_through_near_an_edge_is_exact) {
  const double d = 1e-9;
  auto poke = [&](double y) {
    return soup({O, X, Y, Vec3(0.5, y, -1), Vec3(0.5, y, 1), Vec3(0.5, -1, 0)}, {{0, 1, 2}, {3, 4, 5}});
  };
  EXPECT_EQ(count(poke(d)), 1u);  // through the face, just inside the edge OX
  EXPECT_EQ(count(poke(0)), 1u);  // through the edge itself
  EXPECT_EQ(count(poke(-d)), 0u); // just past the edge
  EXPECT_EQ(count(poke(-1e-30)), 0u);
}

TEST(Intersections, touching_without_shared_nodes_is_reported) {
  // A corner of the second on the face of the first.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.25, 0.25, 0), Vec3(0, 0, 1), Vec3(1, 0, 1)}, {{0, 1, 2}, {3, 4, 5}})), 1u);
  // ...on an edge of the first, and on a corner of the first (distinct nodes).
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.5, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1)}, {{0, 1, 2}, {3, 4, 5}})), 1u);
  EXPECT_EQ(count(soup({O, X, Y, O, Vec3(0, 0, 1), Vec3(1, 0, 1)}, {{0, 1, 2}, {3, 4, 5}})), 1u);
  // Edges crossing at one point.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.5, -1, 1), Vec3(0.5, 1, -1), Vec3(0.5, 1, 1)}, {{0, 1, 2}, {3, 4, 5}})), 1u);
  // A hair above the face: not touching.
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.25, 0.25, 1e-15), Vec3(0, 0, 1), Vec3(1, 0, 1)}, {{0, 1, 2}, {3, 4, 5}})), 0u);
}

TEST(Intersections, duplicates_and_degenerate_triangles) {
  EXPECT_EQ(count(soup({O, X, Y}, {{0, 1, 2}, {2, 1, 0}})), 1u);
  // A collinear triangle across a face, and one lying on the shared edge only.
  const Vec3 below(0.2, 0.2, -1), above(0.2, 0.2, 1), between(0.2, 0.2, 0.5);
  EXPECT_EQ(count(soup({O, X, Y, below, above, between}, {{0, 1, 2}, {3, 4, 5}})), 1u);
  EXPECT_EQ(count(soup({O, X, Y, Vec3(0.5, 0, 0)}, {{0, 1, 2}, {1, 0, 3}})), 0u);
  // Collinear triangles both reaching beyond the shared edge OX on the same side.
  EXPECT_EQ(count(soup({O, X, Vec3(2, 0, 0), Vec3(3, 0, 0)}, {{0, 1, 2}, {1, 0, 3}})), 1u);
  EXPECT_EQ(count(soup({O, X, Vec3(2, 0, 0), Vec3(-1, 0, 0)}, {{0, 1, 2}, {1, 0, 3}})), 0u);
}

TEST(Intersections, tiny_triangles_beside_big_ones) {
  // Big triangles with a corner fanned out by a point 1e-6 away: valid.
  // (Only original triangles are split: splitting the thin pieces again can
  // round a new point across an edge, which the test then rightly reports.)
  NodeMesh m = icosphere(2);
  for (size_t t = 0, n = m.triangles.size(); t < n; t += 3) split_near_corner(m, t, 1e-6);
  EXPECT_EQ(count(m), 0u);
  NodeMesh flat = test::block_grains(2, 3);
  for (size_t t = 0, n = flat.triangles.size(); t < n; t += 3) split_near_corner(flat, t, 1e-6);
  EXPECT_EQ(count(flat), 0u);

  // A triangle of size 1e-6 just above a big one, then through it.
  const double s = 1e-6;
  auto tiny = [&](double z) {
    return soup({O, X, Y, Vec3(0.3, 0.3, z), Vec3(0.3 + s, 0.3, z + s), Vec3(0.3, 0.3 + s, z + s)},
                {{0, 1, 2}, {3, 4, 5}});
  };
  EXPECT_EQ(count(tiny(1e-7)), 0u);
  EXPECT_EQ(count(tiny(-1e-7)), 1u);
  EXPECT_EQ(count(tiny(0)), 1u);
}

TEST(Intersections, icosphere_is_clean_until_a_vertex_goes_through) {
  NodeMesh m = icosphere(4); // 5120 triangles
  EXPECT_EQ(count(m), 0u);
  const int32_t v = 0;
  m.points[size_t(v)] *= -1.5; // through the sphere and out on the opposite side
  const IntersectionReport r = find_self_intersections(m, 1000);
  EXPECT_GT(r.count, 0u);
  EXPECT_EQ(r.pairs.size(), r.count);
  for (const Pair& p : r.pairs) {
    auto holds = [&](int32_t t) {
      const auto& tri = m.triangles[size_t(t)];
      return tri[0] == v || tri[1] == v || tri[2] == v;
    };
    EXPECT_TRUE(holds(p[0]) || holds(p[1])) << p[0] << " " << p[1];
  }
}

TEST(Intersections, grid_agrees_with_all_pairs_on_a_random_soup) {
  // Triangles of sizes from 1e-3 to 2 (several grid levels), some sharing nodes.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Vec3> p;
  std::vector<std::array<int32_t, 3>> t;
  for (int i = 0; i < 150; ++i) {
    const double size = std::pow(10.0, -3 + 3.3 * unit(rng));
    const Vec3 c(unit(rng), unit(rng), unit(rng));
    std::array<int32_t, 3> tri;
    for (int32_t& id : tri) {
      if (!p.empty() && unit(rng) < 0.1) {
        id = int32_t(rng() % p.size());
      } else {
        id = int32_t(p.size());
        p.push_back(c + size * Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5));
      }
    }
    if (tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]) t.push_back(tri);
  }
  const NodeMesh m = soup(p, t);
  std::vector<Pair> expected;
  for (size_t i = 0; i < t.size(); ++i)
    for (size_t j = i + 1; j < t.size(); ++j)
      if (pair_intersects(m, i, j)) expected.push_back({int32_t(i), int32_t(j)});
  ASSERT_GT(expected.size(), 10u);
  const IntersectionReport all = find_self_intersections(m, expected.size() + 5);
  EXPECT_EQ(all.count, expected.size());
  EXPECT_EQ(all.pairs, expected);
  // Truncated lists keep the smallest pairs, and the count stays complete.
  const IntersectionReport few = find_self_intersections(m, 4);
  EXPECT_EQ(few.count, expected.size());
  EXPECT_EQ(few.pairs, std::vector<Pair>(expected.begin(), expected.begin() + 4));
  EXPECT_TRUE(find_self_intersections(m, 0).pairs.empty());
  // The same on one thread.
  tbb::task_arena one(1);
  one.execute([&] { EXPECT_EQ(find_self_intersections(m, 4).pairs, few.pairs); });
  // Flagging a few triangles: exactly the pairs with a flagged one (found on the
  // triangles near the flagged ones only), and with every triangle flagged, all.
  std::vector<uint8_t> flags(t.size(), 0);
  for (size_t i = 0; i < t.size(); i += 9) flags[i] = 1;
  std::vector<Pair> flagged;
  for (const Pair& q : expected)
    if (flags[size_t(q[0])] || flags[size_t(q[1])]) flagged.push_back(q);
  ASSERT_GT(flagged.size(), 2u);
  EXPECT_EQ(find_self_intersections(m, expected.size(), flags).pairs, flagged);
  EXPECT_EQ(find_self_intersections(m, expected.size(), std::vector<uint8_t>(t.size(), 1)).pairs, expected);
}

TEST(Intersections, pairs_in_a_node_star_are_tested_unless_the_star_is_certified) {
  // An icosphere whose nodes are shaken hard enough that many stars fold, some
  // triangles turn over and faces pass through each other: the check (which
  // leaves the pairs of certified stars untested) finds exactly the pairs the
  // exact test finds one by one.
  NodeMesh m = icosphere(2); // 320 triangles
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (Vec3& v : m.points)
    if (rng() % 3 == 0) v += 0.3 * Vec3(u(rng), u(rng), u(rng));
  std::vector<Pair> expected;
  for (size_t i = 0; i < m.triangles.size(); ++i)
    for (size_t j = i + 1; j < m.triangles.size(); ++j)
      if (detail::intersect_improperly(m.points, m.triangles[i], m.triangles[j]))
        expected.push_back({int32_t(i), int32_t(j)});
  // Crossings in stars and between faces apart, and stars certified and not.
  const size_t sharing = size_t(std::count_if(expected.begin(), expected.end(), [&](const Pair& q) {
    const auto& b = m.triangles[size_t(q[1])];
    return std::any_of(m.triangles[size_t(q[0])].begin(), m.triangles[size_t(q[0])].end(),
                       [&](int32_t x) { return std::find(b.begin(), b.end(), x) != b.end(); });
  }));
  ASSERT_GT(sharing, 5u);
  ASSERT_GT(expected.size(), sharing);
  const std::vector<uint8_t> stars = detail::embedded_stars(m.points, m.triangles);
  const auto certified = size_t(std::count(stars.begin(), stars.end(), 1));
  ASSERT_GT(certified, m.points.size() / 4);
  ASSERT_LT(certified, m.points.size());
  EXPECT_EQ(find_self_intersections(m, expected.size() + 1).pairs, expected);
  // A flat fan around its node twice, the second turn at half the radius:
  // each triangle overlaps the one a turn on (and touches its neighbours').
  std::vector<Vec3> p{O};
  std::vector<std::array<int32_t, 3>> twice;
  for (int k = 0; k < 10; ++k) {
    const double angle = k * 2 * std::numbers::pi / 5;
    p.push_back((k < 5 ? 1.0 : 0.5) * Vec3(std::cos(angle), std::sin(angle), 0));
  }
  for (int32_t k = 0; k < 10; ++k) twice.push_back({0, 1 + k, 1 + (k + 1) % 10});
  size_t overlapping = 0;
  for (size_t i = 0; i < twice.size(); ++i)
    for (size_t j = i + 1; j < twice.size(); ++j) overlapping += detail::intersect_improperly(p, twice[i], twice[j]);
  EXPECT_GE(overlapping, 10u);
  EXPECT_EQ(count(soup(p, twice)), overlapping);
}

TEST(Intersections, bad_node_ids_are_rejected) {
  EXPECT_THROW(find_self_intersections(soup({O, X, Y}, {{0, 1, 2}, {0, 1, 3}})), InvalidInput);
  // The first bad triangle is named, and its bad id (the whole mesh is scanned in parallel).
  try {
    find_self_intersections(soup({O, X, Y}, {{0, 1, 2}, {0, 1, 3}, {7, 1, 2}, {0, -1, 2}}));
    ADD_FAILURE() << "bad node ids accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1 has node id 3 out of range"), std::string::npos) << e.what();
  }
  EXPECT_THROW(find_self_intersections(soup({O, X, Vec3(NAN, 0, 0)}, {{0, 1, 2}})), InvalidInput);
  EXPECT_EQ(count(NodeMesh{}), 0u);
}
