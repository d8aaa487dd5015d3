// The kept crossing index (check/crossing_index.hpp) against the whole-mesh
// check it replaces in the guard (find_self_intersections), through moves large
// enough to fold fans and push surfaces through each other, flips, dropped
// triangles with renumbering, and thread counts; and the fan certificates
// (check/embedded_fans.hpp) on fans made to fail each of their conditions.

#include "check/crossing_index.hpp"
#include "check/embedded_fans.hpp"
#include "improve/merges_made.hpp"
#include "improve/mesh_part.hpp"
#include "improve/node_merge.hpp"
#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/improve/flip.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

namespace {

using namespace vm;
using detail::BoxPair;
using detail::CrossingIndex;
using detail::Triangle;

/// What the guard asked before: every crossing pair with an involved triangle.
std::vector<BoxPair> reference(std::span<const Vec3> points, std::span<const Triangle> triangles,
                               std::span<const uint8_t> involved) {
  NodeMesh m;
  m.points.assign(points.begin(), points.end());
  m.triangles.assign(triangles.begin(), triangles.end());
  return find_self_intersections(m, std::numeric_limits<size_t>::max(), involved).pairs;
}

/// Moves `count` random nodes by up to `reach` each.
void shake(std::vector<Vec3>& points, std::mt19937_64& rng, size_t count, double reach) {
  std::uniform_int_distribution<size_t> node(0, points.size() - 1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (size_t i = 0; i < count; ++i) points[node(rng)] += reach * Vec3(u(rng), u(rng), u(rng));
}

std::vector<uint8_t> random_flags(std::mt19937_64& rng, size_t n, double share) {
  std::bernoulli_distribution pick(share);
  std::vector<uint8_t> flags(n);
  for (auto& f : flags) f = pick(rng);
  return flags;
}

TEST(CrossingIndex, finds_what_the_whole_mesh_check_finds_as_the_mesh_moves_and_flips) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  const double h = 1.0 / 16;
  std::mt19937_64 rng(17);
  CrossingIndex index;
  size_t crossing_checks = 0, folded_fans_found = 0, kept = 0;
  for (int step = 0; step < 24; ++step) {
    // Mostly small moves (the index keeps its filing), now and then large ones
    // that fold fans and cross surfaces; flips change triangles' nodes and fans.
    std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
    std::vector<Vec3> moved = mesh.positions();
    shake(moved, rng, step % 4 == 3 ? 40 : mesh.num_nodes() / 3, step % 4 == 3 ? 0.8 * h : 0.02 * h);
    for (size_t n = 0; n < delta.size(); ++n) delta[n] = moved[n] - mesh.positions()[n];
    mesh.move_nodes(delta);
    if (step % 5 == 4) {
      FlipParams no_guard;
      no_guard.guard_crossings = false;
      no_guard.collapse_below = 0;
      flip_edges(mesh, no_guard);
    }
    const std::vector<uint8_t> involved =
        step % 3 == 0 ? std::vector<uint8_t>{} : random_flags(rng, mesh.num_triangles(), step % 3 == 1 ? 0.9 : 0.02);
    const auto found = index.crossings(mesh.positions(), mesh.triangles(), involved, mesh.triangle_copies());
    const auto expected = reference(mesh.positions(), mesh.triangles(), involved);
    ASSERT_EQ(found, expected) << "step " << step;
    // Built or mended, every list is what a search through the cells finds.
    if (index.indexed()) EXPECT_TRUE(index.lists_unlike_search().empty()) << "step " << step;
    crossing_checks += !expected.empty();
    kept += index.indexed() && !index.rebuilt();
    for (const auto& [t, s] : expected) {
      const auto &a = mesh.triangle_copies()[size_t(t)], &b = mesh.triangle_copies()[size_t(s)];
      folded_fans_found += std::any_of(a.begin(), a.end(), [&](int32_t c) { return std::count(b.begin(), b.end(), c); });
    }
  }
  // The test has teeth: crossings were there to find, some inside one fan (the
  // pairs the certificates skip when they hold), and the index was kept.
  EXPECT_GE(crossing_checks, 4u);
  EXPECT_GT(folded_fans_found, 0u);
  EXPECT_GE(kept, 12u);
}

TEST(CrossingIndex, carries_over_a_renumbering_without_starting_again) {
  const NodeMesh m = test::four_spheres(16);
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(m);
  CrossingIndex index;
  std::mt19937_64 rng(3);
  std::vector<Vec3> points = mesh.positions();
  std::vector<Triangle> triangles = mesh.triangles(), fans = mesh.triangle_copies();
  // One-off checks until the mesh has held still for two calls; then an index.
  for (int call = 0; call < 3; ++call) {
    index.crossings(points, triangles, {}, fans);
    EXPECT_EQ(index.indexed(), call == 2) << call;
  }
  // Drop every seventh triangle and the nodes no triangle uses any more, then
  // merge two neighbouring nodes; ids shrink as a collapse renumbers them.
  std::vector<int32_t> old_triangle, old_node;
  std::vector<Triangle> kept_triangles, kept_fans;
  for (size_t t = 0; t < triangles.size(); ++t)
    if (t % 7 != 0) old_triangle.push_back(int32_t(t)), kept_triangles.push_back(triangles[t]), kept_fans.push_back(fans[t]);
  std::vector<int32_t> new_node(points.size(), -1);
  for (const Triangle& tri : kept_triangles)
    for (int32_t v : tri) new_node[size_t(v)] = 0;
  std::vector<Vec3> kept_points;
  for (size_t n = 0; n < points.size(); ++n)
    if (new_node[n] == 0) new_node[n] = int32_t(kept_points.size()), old_node.push_back(int32_t(n)), kept_points.push_back(points[n]);
  for (Triangle& tri : kept_triangles)
    for (int32_t& v : tri) v = new_node[size_t(v)];
  index.renumber(old_triangle, old_node, kept_fans);
  kept_triangles[5][0] = kept_triangles[5][1] == 0 ? 1 : 0; // a triangle that changed nodes: filed again
  shake(kept_points, rng, 30, 0.8 / 16);
  const auto found = index.crossings(kept_points, kept_triangles, {}, kept_fans);
  EXPECT_TRUE(index.indexed());
  EXPECT_FALSE(index.rebuilt());
  EXPECT_GE(index.refiled(), 1u);
  EXPECT_EQ(found, reference(kept_points, kept_triangles, {}));
  EXPECT_FALSE(found.empty()); // the shake made crossings to find
}

// A trial of edits (nodes moved, or merged into neighbours as collapses do)
// checked through the index of the mesh before it must find the pairs a
// search of the whole trial finds with the edited triangles involved.
TEST(CrossingIndex, checks_a_trial_of_edits_as_a_search_of_the_whole_trial_would) {
  const NodeMesh before = test::four_spheres(16);
  const InterfaceMesh mesh = InterfaceMesh::from_node_mesh(before);
  CrossingIndex index;
  for (int call = 0; call < 3; ++call) index.crossings(before.points, before.triangles, {}, mesh.triangle_copies());
  ASSERT_TRUE(index.refresh(before.points, before.triangles, mesh.triangle_copies()));
  std::mt19937_64 rng(29);
  size_t crossings = 0;
  for (int trial_number = 0; trial_number < 12; ++trial_number) {
    // A random few nodes merge into a neighbour, or move about a cell.
    const bool merge = trial_number % 2 == 0;
    std::vector<int32_t> into(before.num_nodes(), -1);
    std::vector<Vec3> points = before.points;
    std::uniform_int_distribution<size_t> pick(0, before.num_triangles() - 1);
    std::vector<uint8_t> edited(before.num_nodes(), 0);
    for (int e = 0; e < 12; ++e) {
      const Triangle& tri = before.triangles[pick(rng)];
      if (edited[size_t(tri[0])] || edited[size_t(tri[1])]) continue;
      edited[size_t(tri[0])] = edited[size_t(tri[1])] = 1;
      if (merge) into[size_t(tri[1])] = tri[0];
      else points[size_t(tri[0])] += Vec3(0.05, -0.04, 0.03) * double(1 + e % 3);
    }
    NodeMesh trial;
    std::vector<int32_t> turned, kept;
    detail::merge_nodes(before, into, trial, turned, kept, &points);
    // Involved: the trial's triangles at an edited node (a merge target or a moved node).
    std::vector<uint8_t> involved(trial.num_triangles(), 0);
    std::vector<CrossingIndex::TrialTriangle> extra;
    std::vector<int32_t> extra_id, left_out;
    for (size_t t = 0; t < trial.num_triangles(); ++t)
      for (int32_t v : trial.triangles[t]) involved[t] |= edited[size_t(v)];
    for (size_t t = 0; t < trial.num_triangles(); ++t)
      if (const Triangle& tri = trial.triangles[t]; involved[t]) {
        extra.push_back({tri, {points[size_t(tri[0])], points[size_t(tri[1])], points[size_t(tri[2])]}});
        extra_id.push_back(int32_t(t));
      }
    for (size_t t = 0; t < before.num_triangles(); ++t)
      if (std::any_of(before.triangles[t].begin(), before.triangles[t].end(),
                      [&](int32_t v) { return edited[size_t(v)]; }))
        left_out.push_back(int32_t(t));
    std::vector<int32_t> trial_of(before.num_triangles(), -1);
    for (size_t t = 0; t < kept.size(); ++t) trial_of[size_t(kept[t])] = int32_t(t);
    const auto found = index.crossings_with(before.points, before.triangles, extra, left_out);
    std::vector<BoxPair> pairs;
    for (const auto& [e, s] : found.with_mesh) pairs.push_back({extra_id[size_t(e)], trial_of[size_t(s)]});
    for (const auto& [e, f] : found.among_extra) pairs.push_back({extra_id[size_t(e)], extra_id[size_t(f)]});
    for (auto& p : pairs) p = {std::min(p[0], p[1]), std::max(p[0], p[1])};
    std::sort(pairs.begin(), pairs.end());
    EXPECT_EQ(pairs, reference(trial.points, trial.triangles, involved)) << "trial " << trial_number;
    crossings += pairs.size();
  }
  EXPECT_GT(crossings, 0u); // the moves made crossings to find
}

// A remesh call rebuilds the mesh with some triangles and nodes kept (in
// order), some gone and some new (renumber()'s -1): the index files the new
// ones and keeps the rest.
TEST(CrossingIndex, carries_over_a_rebuild_with_new_triangles_and_nodes) {
  const InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  CrossingIndex index;
  for (int call = 0; call < 3; ++call) index.crossings(mesh.positions(), mesh.triangles(), {}, mesh.triangle_copies());
  ASSERT_TRUE(index.indexed());
  // Every eleventh triangle is cut in three at a new node at its centroid, and
  // every thirteenth dropped (its nodes stay, used by its neighbours).
  NodeMesh m = mesh.to_node_mesh();
  NodeMesh cut = m.empty_like();
  cut.points = m.points;
  std::vector<int32_t> old_triangle, old_node(m.num_nodes());
  std::iota(old_node.begin(), old_node.end(), 0);
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const Triangle& tri = m.triangles[t];
    if (t % 13 == 5) continue;
    if (t % 11 != 3) {
      cut.triangles.push_back(tri), cut.pairs.push_back(m.pairs[t]), old_triangle.push_back(int32_t(t));
      continue;
    }
    const auto c = int32_t(cut.points.size());
    cut.points.push_back((m.points[size_t(tri[0])] + m.points[size_t(tri[1])] + m.points[size_t(tri[2])]) / 3);
    old_node.push_back(-1);
    for (int k = 0; k < 3; ++k) {
      cut.triangles.push_back({tri[size_t(k)], tri[size_t((k + 1) % 3)], c});
      cut.pairs.push_back(m.pairs[t]);
      old_triangle.push_back(-1);
    }
  }
  const InterfaceMesh rebuilt = InterfaceMesh::from_node_mesh(cut);
  index.renumber(old_triangle, old_node, rebuilt.triangle_copies());
  const auto made = size_t(std::count(old_triangle.begin(), old_triangle.end(), -1));
  std::mt19937_64 rng(5);
  std::vector<Vec3> points = rebuilt.positions();
  for (int call = 0; call < 3; ++call) {
    shake(points, rng, call == 0 ? 30 : 10, 0.8 / 16);
    const auto found = index.crossings(points, rebuilt.triangles(), {}, rebuilt.triangle_copies());
    EXPECT_TRUE(index.indexed()) << call;
    EXPECT_FALSE(index.rebuilt()) << call;
    if (call == 0) EXPECT_GE(index.refiled(), made);
    EXPECT_EQ(found, reference(points, rebuilt.triangles(), {})) << call;
    if (call == 0) EXPECT_FALSE(found.empty()); // the shake made crossings to find
  }
}

// Random merges made in place as the collapses make them (make_merges() from
// the part at the merges): the index, told only what the edit removed and
// moved, keeps its lists right and answers as the whole-mesh check does,
// without building anew.
TEST(CrossingIndex, carries_over_merges_made_in_place_told_sparsely) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  CrossingIndex index;
  for (int call = 0; call < 3; ++call) index.crossings(mesh.positions(), mesh.triangles(), {}, mesh.triangle_copies());
  ASSERT_TRUE(index.indexed());
  std::mt19937_64 rng(23);
  size_t merges = 0;
  for (int batch = 0; batch < 4; ++batch) {
    // b into a neighbour a on all of b's constraints, no two merges sharing a ring.
    std::vector<int32_t> into(mesh.num_nodes(), -1), seeds;
    std::vector<uint8_t> claimed(mesh.num_nodes(), 0);
    for (int draw = 0; draw < 60; ++draw) {
      const auto b = int32_t(rng() % mesh.num_nodes());
      const auto ring = mesh.neighbours(b);
      const int32_t a = ring[rng() % ring.size()];
      std::vector<int32_t> around(ring.begin(), ring.end());
      around.insert(around.end(), mesh.neighbours(a).begin(), mesh.neighbours(a).end());
      if (!mesh.constraints_within(b, a) || std::any_of(around.begin(), around.end(), [&](int32_t w) {
            return claimed[size_t(w)];
          }))
        continue;
      into[size_t(b)] = a;
      for (int32_t w : around) claimed[size_t(w)] = 1, seeds.push_back(w);
      ++merges;
    }
    const detail::MeshPart part = detail::part_at(mesh, seeds);
    std::vector<int32_t> part_into(part.mesh.num_nodes(), -1), turned, kept_triangles;
    for (size_t n = 0; n < part.nodes.size(); ++n)
      if (const int32_t a = into[size_t(part.nodes[n])]; a >= 0) part_into[n] = part.part_node(a);
    NodeMesh merged;
    detail::merge_nodes(part.mesh, part_into, merged, turned, kept_triangles);
    const auto node_ids = test::identity<int64_t>(mesh.num_nodes());
    const auto triangle_ids = test::identity<int64_t>(mesh.num_triangles());
    detail::CollapseKept kept;
    detail::make_merges(mesh, part, merged, kept_triangles, nullptr, node_ids, triangle_ids, kept);
    ASSERT_TRUE(kept.in_place) << batch;
    index.renumber_after_removal(kept.removed_triangles, moved_by(kept.moves.faces));
    EXPECT_TRUE(index.lists_unlike_search().empty()) << batch;
    std::vector<Vec3> points = mesh.positions();
    shake(points, rng, 20, 0.8 / 16);
    const auto found = index.crossings(points, mesh.triangles(), {}, mesh.triangle_copies());
    EXPECT_TRUE(index.indexed()) << batch;
    EXPECT_FALSE(index.rebuilt()) << batch;
    EXPECT_GT(index.refiled(), 0u) << batch; // the renamed triangles and those at moved nodes
    EXPECT_EQ(found, reference(points, mesh.triangles(), {})) << batch;
    EXPECT_TRUE(index.lists_unlike_search().empty()) << batch;
  }
  EXPECT_GT(merges, 40u);
}

// The guard's commit moves many nodes, then puts back, round by round, the
// nodes of what crosses: after the first round only those moved, and the
// index, told so, mends and searches from their triangles alone; likewise for
// the faces a flip changed.
TEST(CrossingIndex, answers_after_local_changes_as_the_whole_mesh_check_does) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  CrossingIndex index;
  for (int call = 0; call < 3; ++call) index.crossings(mesh.positions(), mesh.triangles(), {}, mesh.triangle_copies());
  ASSERT_TRUE(index.indexed());
  const std::vector<Vec3> before = mesh.positions();
  std::vector<Vec3> points = before;
  std::mt19937_64 rng(23);
  shake(points, rng, mesh.num_nodes() / 3, 0.02 / 16);
  shake(points, rng, 60, 0.8 / 16);
  const auto& triangles = mesh.triangles();
  auto at = [&](const std::vector<uint8_t>& nodes) {
    std::vector<uint8_t> flags(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t)
      for (int32_t v : triangles[t]) flags[t] |= nodes[size_t(v)];
    return flags;
  };
  std::vector<uint8_t> changed(points.size());
  for (size_t n = 0; n < points.size(); ++n) changed[n] = points[n] != before[n];
  std::vector<uint8_t> involved = at(changed);
  std::vector<BoxPair> found = index.crossings(points, triangles, involved, mesh.triangle_copies());
  ASSERT_EQ(found, reference(points, triangles, involved));
  ASSERT_FALSE(found.empty()); // the shake made crossings to put back
  size_t rounds = 0, refiled = 0, found_later = 0;
  while (!found.empty()) {
    // One corner of each crossing pair goes back (half way in odd rounds, so
    // that a node may take more than one round, as the guard's may not).
    std::fill(changed.begin(), changed.end(), 0);
    for (const auto& pair : found) {
      const int32_t n = triangles[size_t(pair[rounds % 2])][rounds % 3];
      points[size_t(n)] = rounds % 2 ? Vec3(0.5 * (points[size_t(n)] + before[size_t(n)])) : before[size_t(n)];
      changed[size_t(n)] = 1;
    }
    involved = at(changed);
    found = index.crossings_after_changes(points, triangles, involved, mesh.triangle_copies());
    ASSERT_EQ(found, reference(points, triangles, involved)) << "round " << rounds;
    EXPECT_TRUE(index.indexed());
    EXPECT_FALSE(index.rebuilt());
    EXPECT_TRUE(index.lists_unlike_search().empty()) << "round " << rounds;
    refiled += index.refiled();
    found_later += !found.empty();
    ASSERT_LT(++rounds, 40u);
  }
  // The test has teeth: triangles left their filing boxes and were filed
  // again, and later rounds still had crossings to find.
  EXPECT_GT(refiled, 0u);
  EXPECT_GT(found_later, 0u);
  // After it, a whole check agrees that nothing crosses.
  EXPECT_EQ(index.crossings(points, triangles, {}, mesh.triangle_copies()), reference(points, triangles, {}));

  // Flips change the nodes of the faces they flip and of no other (as between
  // the flip pass's repairs): told which, the index files those again.
  std::vector<Vec3> delta(points.size());
  for (size_t n = 0; n < points.size(); ++n) delta[n] = points[n] - mesh.positions()[n];
  mesh.move_nodes(delta);
  index.crossings(mesh.positions(), mesh.triangles(), {}, mesh.triangle_copies());
  const std::vector<Triangle> unflipped = mesh.triangles();
  FlipParams no_guard;
  no_guard.guard_crossings = false;
  no_guard.collapse_below = 0;
  ASSERT_GT(flip_edges(mesh, no_guard).flips, 0u);
  ASSERT_EQ(mesh.num_triangles(), unflipped.size());
  std::vector<uint8_t> flipped(unflipped.size());
  for (size_t t = 0; t < flipped.size(); ++t) flipped[t] = mesh.triangles()[t] != unflipped[t];
  const auto after_flips = index.crossings_after_changes(mesh.positions(), mesh.triangles(), flipped, mesh.triangle_copies());
  EXPECT_EQ(after_flips, reference(mesh.positions(), mesh.triangles(), flipped));
  EXPECT_GT(index.refiled(), 0u);
  EXPECT_FALSE(index.rebuilt());
  EXPECT_TRUE(index.lists_unlike_search().empty());
}

TEST(CrossingIndex, answers_alike_for_any_thread_count) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  std::vector<Vec3> points = mesh.positions();
  std::mt19937_64 rng(9);
  shake(points, rng, 300, 0.5 / 16);
  std::vector<std::vector<BoxPair>> found;
  for (int threads : {1, 2, 4}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    CrossingIndex index;
    found.push_back(index.crossings(points, mesh.triangles(), {}, mesh.triangle_copies()));
  }
  ASSERT_FALSE(found[0].empty());
  EXPECT_EQ(found[1], found[0]);
  EXPECT_EQ(found[2], found[0]);
}

TEST(CornerFans, kept_up_to_date_through_flips_as_if_built_anew) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  detail::CornerFans kept;
  kept.build(mesh.triangles(), mesh.triangle_copies());
  const std::vector<Triangle> triangles_before = mesh.triangles(), fans_before = mesh.triangle_copies();
  std::vector<Vec3> points = mesh.positions();
  std::mt19937_64 rng(4);
  shake(points, rng, mesh.num_nodes(), 0.3 / 16); // rough, so that many edges flip
  std::vector<Vec3> delta(points.size());
  for (size_t n = 0; n < points.size(); ++n) delta[n] = points[n] - mesh.positions()[n];
  mesh.move_nodes(delta);
  FlipParams params;
  params.guard_crossings = false;
  params.collapse_below = 0;
  ASSERT_GT(flip_edges(mesh, params).flips, 50u);
  std::vector<int32_t> changed;
  std::vector<Triangle> old_fans;
  for (size_t t = 0; t < mesh.num_triangles(); ++t)
    if (mesh.triangles()[t] != triangles_before[t] || mesh.triangle_copies()[t] != fans_before[t])
      changed.push_back(int32_t(t)), old_fans.push_back(fans_before[t]);
  kept.update(changed, old_fans, mesh.triangles(), mesh.triangle_copies());
  detail::CornerFans anew;
  anew.build(mesh.triangles(), mesh.triangle_copies());
  ASSERT_EQ(kept.count(), anew.count());
  size_t chained = 0;
  for (size_t f = 0; f < anew.count(); ++f) {
    // The same corners in the same chain, up to where a closed chain starts.
    std::vector<int32_t> a(kept.corners(f).begin(), kept.corners(f).end()), b(anew.corners(f).begin(), anew.corners(f).end());
    ASSERT_EQ(kept.chained(f), anew.chained(f)) << "fan " << f;
    ASSERT_EQ(kept.closed(f), anew.closed(f)) << "fan " << f;
    ASSERT_EQ(kept.node(f), anew.node(f));
    if (anew.closed(f) && !a.empty()) std::rotate(a.begin(), std::find(a.begin(), a.end(), b[0]), a.end());
    EXPECT_EQ(a, b) << "fan " << f;
    chained += anew.chained(f);
  }
  EXPECT_EQ(chained, anew.count()); // every fan of a valid mesh is one chain
}

// ---------------------------------------------------------------------------
// Fan certificates on hand-made fans around node 0 at the origin.

struct Fan {
  std::vector<Vec3> points{Vec3::Zero()};
  std::vector<Triangle> triangles, corner_fans;
  /// Adds triangle (0, a, b) with its corner at node 0 in fan 0 and its other
  /// corners in fans of their own.
  void add(int32_t a, int32_t b) {
    triangles.push_back({0, a, b});
    const auto t = int32_t(triangles.size());
    corner_fans.push_back({0, 2 * t, 2 * t + 1});
  }
  bool embedded() const {
    detail::CornerFans fans;
    fans.build(triangles, corner_fans);
    return detail::FanCertificates(points, triangles, fans).embedded(0);
  }
  /// Node 0's star, all its triangles, certified without fan ids.
  bool star_embedded() const { return detail::embedded_stars(points, triangles)[0] == 1; }
  /// Both certificates, which must agree: node 0's triangles are its one fan.
  bool certified() const {
    EXPECT_EQ(embedded(), star_embedded());
    return embedded();
  }
};

/// A fan of `m` triangles around the origin, its ring at heights z(i),
/// turning `turns` times around; `closed` joins the last corner to the first.
Fan ring_fan(int m, double turns, bool closed, const std::function<double(int)>& z = [](int) { return 0.0; }) {
  Fan fan;
  const int corners = closed ? m : m + 1;
  for (int i = 0; i < corners; ++i) {
    const double angle = 2 * std::numbers::pi * turns * i / m;
    fan.points.push_back({std::cos(angle), std::sin(angle), z(i)});
  }
  for (int i = 0; i < m; ++i) fan.add(1 + i, 1 + (closed ? (i + 1) % m : i + 1));
  return fan;
}

TEST(FanCertificates, certify_flat_and_wavy_fans_that_go_once_around) {
  EXPECT_TRUE(ring_fan(6, 1, true).certified());
  EXPECT_TRUE(ring_fan(7, 1, true, [](int i) { return 0.4 * std::sin(2.0 * i); }).certified());
  EXPECT_TRUE(ring_fan(5, 0.9, false).certified()); // open, nine tenths of a turn
}

TEST(FanCertificates, refuse_fans_that_fold_wrap_or_break) {
  // A closed chain around twice: every triangle turns the same way, but each
  // sector overlaps another one.
  EXPECT_FALSE(ring_fan(10, 2, true).certified());
  // An open chain of more than one turn overlaps itself.
  EXPECT_FALSE(ring_fan(7, 1.2, false).certified());
  // One triangle folded back over its neighbour.
  Fan folded = ring_fan(6, 1, true);
  folded.points[3] = {0.9, 0.2, 0.05};
  EXPECT_FALSE(folded.certified());
  // A triangle standing on edge (seen along every axis it is a line or turns
  // against the others) is not certified.
  Fan standing = ring_fan(6, 1, true);
  standing.points[2] = {0, 0, 1};
  standing.points[3] = {0, 0, 2};
  EXPECT_FALSE(standing.certified());
  // Two separate wedges around one node: no single chain.
  Fan broken;
  broken.points = {Vec3::Zero(), {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {-1, -1, 0}};
  broken.add(1, 2);
  broken.add(3, 5);
  EXPECT_FALSE(broken.certified());
}

TEST(FanCertificates, stars_of_nodes_where_surfaces_meet_are_not_certified) {
  // Three fins on the edge from node 0 to node 1 (a triple curve): neither end
  // of the edge has one fan. The fins' outer corners have one triangle each,
  // an open fan of one sector, certified.
  const std::vector<Vec3> points{Vec3::Zero(), {0, 0, 1}, {1, 0, 0.5}, {-0.5, 0.8, 0.5}, {-0.5, -0.8, 0.5}};
  const std::vector<Triangle> fins{{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};
  EXPECT_EQ(detail::embedded_stars(points, fins), (std::vector<uint8_t>{0, 0, 1, 1, 1}));
  // Two closed fans sharing only their node (two cones tip to tip).
  Fan upper = ring_fan(5, 1, true, [](int) { return 1.0; });
  const Fan lower = ring_fan(5, 1, true, [](int) { return -1.0; });
  const auto shift = int32_t(upper.points.size() - 1);
  upper.points.insert(upper.points.end(), lower.points.begin() + 1, lower.points.end());
  for (const Triangle& t : lower.triangles) upper.triangles.push_back({0, t[1] + shift, t[2] + shift});
  EXPECT_FALSE(upper.star_embedded());
  // A duplicate of one triangle, either way round, makes no fan.
  for (const Triangle dup : {Triangle{0, 1, 2}, Triangle{0, 2, 1}}) {
    Fan twice = ring_fan(6, 1, true);
    twice.triangles.push_back(dup);
    EXPECT_FALSE(twice.star_embedded());
  }
}

// Where most triangles change between calls, mending an index costs more than
// checking anew: the calls are one-off checks, with the same answers, until
// the mesh settles; a large change drops the index again.
TEST(CrossingIndex, keeps_no_index_while_the_mesh_changes_much) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  CrossingIndex index;
  std::mt19937_64 rng(5);
  std::vector<Vec3> points = mesh.positions();
  const std::vector<Triangle> triangles = mesh.triangles(), fans = mesh.triangle_copies();
  auto check = [&] {
    EXPECT_EQ(index.crossings(points, triangles, {}, fans), reference(points, triangles, {}));
    return index.indexed();
  };
  for (int call = 0; call < 3; ++call) {
    shake(points, rng, points.size(), 0.3 / 16); // every node, by a good part of an edge
    EXPECT_FALSE(check()) << call;
  }
  EXPECT_FALSE(check()); // one call without change: not settled yet
  EXPECT_TRUE(check());  // two: the index is built
  shake(points, rng, 10, 0.01 / 16);
  EXPECT_TRUE(check()); // small changes are mended
  shake(points, rng, points.size() / 8, 1.0 / 16);
  EXPECT_TRUE(check()); // so are changes of more than a sixth (a flip pass on a large mesh), up to half
  EXPECT_GT(6 * index.refiled(), triangles.size());
  shake(points, rng, points.size(), 1.0 / 16);
  EXPECT_FALSE(check()); // a change of most triangles drops it
}

} // namespace
