// Tests of the crossing guard (improve/guard.hpp): moves and flips that would push one
// surface through another are undone, on a hand-made move and on a scene where
// the unguarded pipeline does cross.

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/flip.hpp"
#include "voronoimesh/improve/guard.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/project.hpp"
#include "voronoimesh/mesh/triangle_quality.hpp"

#include "improve/crossing_windows.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <random>
#include <tuple>

namespace {

using namespace vm;

using test::initial_mesh;

/// A node of `m` on surface `a`-`b` only, and one on a different surface.
std::pair<int32_t, int32_t> nodes_on_two_surfaces(const InterfaceMesh& m) {
  int32_t first = -1;
  for (size_t v = 0; v < m.num_nodes(); ++v) {
    const PhaseSet& s = m.phases()[v];
    if (phase_count(s) != 2) continue;
    if (first < 0) first = int32_t(v);
    else if (m.phases()[size_t(first)] != s) return {first, int32_t(v)};
  }
  return {-1, -1};
}

TEST(Guard, undoes_exactly_the_move_that_would_cross_and_keeps_the_others) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  ASSERT_TRUE(find_self_intersections(mesh.to_node_mesh()).ok());
  const auto [v, w] = nodes_on_two_surfaces(mesh);
  ASSERT_GE(v, 0);
  const std::vector<Vec3> before = mesh.positions();
  // v jumps onto w (a surface node of another surface): its triangles would touch
  // w's. Another node, far from both, makes a tiny harmless move.
  std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
  delta[size_t(v)] = before[size_t(w)] - before[size_t(v)];
  int32_t far = -1;
  for (size_t u = 0; u < mesh.num_nodes() && far < 0; ++u)
    if ((before[u] - before[size_t(v)]).norm() > 0.3 && (before[u] - before[size_t(w)]).norm() > 0.3) far = int32_t(u);
  ASSERT_GE(far, 0);
  delta[size_t(far)] = Vec3(1e-6, 0, 0);

  // Unguarded, the move does make triangles intersect (so the test can fail).
  InterfaceMesh unguarded = mesh;
  unguarded.move_nodes(delta);
  ASSERT_GT(find_self_intersections(unguarded.to_node_mesh()).count, 0u);

  const GuardReport report = commit_without_crossings(mesh, delta);
  EXPECT_EQ(report.undone_nodes, 1u);
  EXPECT_EQ(mesh.positions()[size_t(v)], before[size_t(v)]); // bit for bit
  EXPECT_TRUE(delta[size_t(v)].isZero(0));
  EXPECT_EQ(mesh.positions()[size_t(far)], before[size_t(far)] + Vec3(1e-6, 0, 0));
  EXPECT_TRUE(find_self_intersections(mesh.to_node_mesh()).ok());
}

// Two triangles cross after a move: the one whose corner moved farther goes
// back, and the other's move stays (putting both back froze a flat face of the
// CT-like volume for a whole run: a node below it kept jumping through). A slab
// 0.1 thick: a node of its lower face rises 0.08, the node of its upper face
// above it sinks 0.03. Either move alone is safe, both cross.
TEST(Guard, puts_back_the_farther_mover_of_a_crossing_pair_and_keeps_the_other) {
  const Scene slab = parse_scene(R"({"phases": [{"kind": "plane", "point": [0.5, 0.5, 0.45], "normal": [0, 0, -1]},
      {"kind": "constant", "value": 0}, {"kind": "plane", "point": [0.5, 0.5, 0.55], "normal": [0, 0, 1]}]})",
                                 "inline");
  InterfaceMesh mesh = test::initial_mesh(slab);
  const std::vector<Vec3> before = mesh.positions();
  auto nearest_on = [&](const Vec3& at) {
    int32_t best = -1;
    for (size_t n = 0; n < mesh.num_nodes(); ++n)
      if (phase_count(mesh.phases()[n]) == 2 && std::abs(before[n].z() - at.z()) < 1e-9 &&
          (best < 0 || (before[n] - at).norm() < (before[size_t(best)] - at).norm()))
        best = int32_t(n);
    return best;
  };
  const int32_t low = nearest_on({0.5, 0.5, 0.45});
  ASSERT_GE(low, 0);
  const int32_t high = nearest_on({before[size_t(low)].x(), before[size_t(low)].y(), 0.55});
  ASSERT_GE(high, 0);
  ASSERT_LT((before[size_t(high)] - before[size_t(low)]).head<2>().norm(), 1e-9); // right above it
  std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
  delta[size_t(low)] = Vec3(0, 0, 0.08);
  delta[size_t(high)] = Vec3(0, 0, -0.03);
  for (const int32_t alone : {low, high}) {
    InterfaceMesh moved = mesh;
    std::vector<Vec3> one(mesh.num_nodes(), Vec3::Zero());
    one[size_t(alone)] = delta[size_t(alone)];
    moved.move_nodes(one);
    ASSERT_TRUE(find_self_intersections(moved.to_node_mesh()).ok());
  }
  InterfaceMesh both = mesh;
  both.move_nodes(delta);
  ASSERT_GT(find_self_intersections(both.to_node_mesh()).count, 0u);

  const GuardReport report = commit_without_crossings(mesh, delta);
  EXPECT_EQ(report.undone_nodes, 1u);
  EXPECT_EQ(mesh.positions()[size_t(low)], before[size_t(low)]);
  EXPECT_EQ(mesh.positions()[size_t(high)], before[size_t(high)] + Vec3(0, 0, -0.03));
  EXPECT_TRUE(find_self_intersections(mesh.to_node_mesh()).ok());
}

// The quality floor (the pipeline passes the worst quality an iteration starts
// with): a move that leaves a triangle below it is undone, unless it brings a
// node that is visibly off its surface (over 2% of the triangle's longest edge;
// here about 10%) at least halfway to it: accuracy before shape. Floor 1 puts
// every moved triangle below it, so only the approaching move may stay.
TEST(Guard, quality_floor_undoes_moves_that_spoil_the_worst_triangle_unless_they_approach_the_surface) {
  const Scene scene = test::example_scene("four_spheres.json", 16);
  InterfaceMesh mesh = initial_mesh(scene);
  const PhaseField& field = *scene.field;
  // Two surface nodes far apart, each off its surface after snapping.
  int32_t v = -1, u = -1;
  for (size_t n = 0; n < mesh.num_nodes() && u < 0; ++n) {
    const bool off = phase_count(mesh.phases()[n]) == 2 &&
                     node_projection_step(mesh, field, int32_t(n), mesh.positions()[n]).norm() > 0.1 * scene.grid.h();
    if (!off) continue;
    if (v < 0) v = int32_t(n);
    else if ((mesh.positions()[n] - mesh.positions()[size_t(v)]).norm() > 0.3) u = int32_t(n);
  }
  ASSERT_GE(u, 0);
  const std::vector<Vec3> before = mesh.positions();
  std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
  // v: its projection step, which takes it (almost) onto its surface; u: a
  // small move across its own step, which leaves it as far from its surface.
  const Vec3 step_u = node_projection_step(mesh, field, u, before[size_t(u)]);
  delta[size_t(v)] = node_projection_step(mesh, field, v, before[size_t(v)]);
  delta[size_t(u)] = 0.01 * step_u.unitOrthogonal() * step_u.norm();

  InterfaceMesh without_floor = mesh;
  std::vector<Vec3> free_delta = delta;
  EXPECT_EQ(commit_without_crossings(without_floor, free_delta, &field).undone_nodes, 0u);

  const GuardReport report = CrossingGuard().commit(mesh, delta, &field, {}, 1.0);
  EXPECT_EQ(report.undone_nodes, 1u);
  EXPECT_EQ(mesh.positions()[size_t(u)], before[size_t(u)]); // bit for bit
  EXPECT_EQ(mesh.positions()[size_t(v)], without_floor.positions()[size_t(v)]);
  // Without the field nothing tells an approaching move apart: both are undone.
  InterfaceMesh blind = initial_mesh(scene);
  std::vector<Vec3> blind_delta = free_delta;
  EXPECT_EQ(CrossingGuard().commit(blind, blind_delta, nullptr, {}, 1.0).undone_nodes, 2u);
}

// A triple-curve node's eq. 4 step closes about a third of the way per
// iteration, so its moves never halve it: the floor lets such a move through
// when it leaves at most 0.9 of the step and every triangle below the floor at
// q 0.4 or better, without remembering it for the floor pass. Here a third of
// each node's step, with floor 1 (every moved triangle below it).
TEST(Guard, quality_floor_lets_curve_nodes_approach_their_curve_down_to_q_0_4) {
  const Scene scene = test::example_scene("four_spheres.json", 16);
  const PhaseField& field = *scene.field;
  const InterfaceMesh start = initial_mesh(scene);
  // The least quality of n's triangles once n has moved to x.
  auto worst_at = [&](int32_t n, const Vec3& x) {
    double worst = 1;
    for (int32_t f : start.faces_at(std::span<const int32_t>(&n, 1))) {
      std::array<Vec3, 3> p;
      for (int k = 0; k < 3; ++k) {
        const int32_t c = start.triangles()[size_t(f)][size_t(k)];
        p[size_t(k)] = c == n ? x : start.positions()[size_t(c)];
      }
      worst = std::min(worst, triangle_quality(p[0], p[1], p[2]));
    }
    return worst;
  };
  int32_t fine = -1, spoilt = -1; // curve nodes visibly off whose move leaves q >= 0.45, < 0.35
  for (size_t n = 0; n < start.num_nodes(); ++n) {
    if (phase_count(start.phases()[n]) != 3 || start.box_faces()[n]) continue;
    const Vec3 step = node_projection_step(start, field, int32_t(n), start.positions()[n]);
    if (step.norm() < 0.1 * scene.grid.h()) continue;
    const double worst = worst_at(int32_t(n), start.positions()[n] + step / 3);
    if (fine < 0 && worst >= 0.45) fine = int32_t(n);
    if (spoilt < 0 && worst < 0.35) spoilt = int32_t(n);
  }
  ASSERT_GE(fine, 0);
  ASSERT_GE(spoilt, 0);
  for (const auto& [n, fraction, goes] : {std::tuple{fine, 1.0 / 3, true}, std::tuple{fine, 0.05, false},
                                          std::tuple{spoilt, 1.0 / 3, false}}) {
    SCOPED_TRACE(testing::Message() << "node " << n << ", a fraction " << fraction << " of its step");
    InterfaceMesh mesh = start;
    CrossingGuard guard;
    std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
    delta[size_t(n)] = fraction * node_projection_step(mesh, field, n, start.positions()[size_t(n)]);
    EXPECT_EQ(guard.commit(mesh, delta, &field, {}, 1.0).undone_nodes, goes ? 0u : 1u);
    EXPECT_EQ(mesh.positions()[size_t(n)] != start.positions()[size_t(n)], goes);
    EXPECT_TRUE(guard.floor_exception_nodes().empty());
  }
}

// The floor pass takes back the moves the floor let through where they left a
// triangle below the floor (improve/guard.hpp, floor_exception_reverts()): the
// guard remembers the node that closed in on its surface, where it was and where
// it went, and offers the move back only while one of its triangles is below the
// floor it is given (here 1: every triangle; 0: none), forgetting it either way.
TEST(Guard, a_move_the_floor_let_through_can_be_taken_back) {
  const Scene scene = test::example_scene("four_spheres.json", 16);
  const PhaseField& field = *scene.field;
  const InterfaceMesh start = initial_mesh(scene);
  int32_t v = -1; // a surface node visibly off its surface
  for (size_t n = 0; n < start.num_nodes() && v < 0; ++n)
    if (phase_count(start.phases()[n]) == 2 &&
        node_projection_step(start, field, int32_t(n), start.positions()[n]).norm() > 0.1 * scene.grid.h())
      v = int32_t(n);
  ASSERT_GE(v, 0);
  for (const double floor_now : {0.0, 1.0}) {
    SCOPED_TRACE(floor_now);
    InterfaceMesh mesh = start;
    CrossingGuard guard;
    std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
    delta[size_t(v)] = node_projection_step(mesh, field, v, start.positions()[size_t(v)]);
    ASSERT_EQ(guard.commit(mesh, delta, &field, {}, 1.0).undone_nodes, 0u); // let through
    ASSERT_NE(mesh.positions()[size_t(v)], start.positions()[size_t(v)]);
    std::vector<Vec3> back(mesh.num_nodes(), Vec3::Zero());
    guard.floor_exception_reverts(mesh, floor_now, back);
    for (size_t n = 0; n < back.size(); ++n)
      if (n != size_t(v)) EXPECT_EQ(back[n], Vec3::Zero()) << "node " << n;
    if (floor_now == 0) {
      EXPECT_EQ(back[size_t(v)], Vec3::Zero()); // no triangle below the floor: the move stays
      continue;
    }
    EXPECT_LT((mesh.positions()[size_t(v)] + back[size_t(v)] - start.positions()[size_t(v)]).norm(), 1e-12);
    // Offered once: the guard forgot it.
    std::vector<Vec3> again(mesh.num_nodes(), Vec3::Zero());
    guard.floor_exception_reverts(mesh, floor_now, again);
    EXPECT_EQ(again[size_t(v)], Vec3::Zero());
    // Committed with the floor holding for every move (here no floor: the
    // taking back only restores triangles the node had before).
    EXPECT_EQ(guard.commit(mesh, back, &field, {}, 0.0, true).undone_nodes, 0u);
    EXPECT_LT((mesh.positions()[size_t(v)] - start.positions()[size_t(v)]).norm(), 1e-12);
  }
}

// In a pipeline with the floor pass, the flip pass leaves the triangles at a
// node the floor let through as they are (FlipParams::keep_triangles_at: their
// edges and the edges across from the node are banned for the call), so that
// the floor pass can put the node back among the triangles it left: flipped,
// the way back could leave one below the floor, and the guard would refuse it
// (the liver, iteration 5). The other triangles flip as ever.
TEST(Guard, flips_leave_the_triangles_of_a_node_the_floor_let_through_alone) {
  const Scene scene = test::example_scene("four_spheres.json", 16);
  const PhaseField& field = *scene.field;
  const InterfaceMesh start = initial_mesh(scene);
  FlipParams params;
  params.collapse_below = 0; // no renumbering: triangles compare by their nodes
  auto triangles_at = [](const InterfaceMesh& m, int32_t v) {
    std::vector<std::array<int32_t, 3>> at;
    for (auto t : m.triangles())
      if (std::find(t.begin(), t.end(), v) != t.end()) {
        std::sort(t.begin(), t.end());
        at.push_back(t);
      }
    std::sort(at.begin(), at.end());
    return at;
  };
  // A surface node visibly off its surface whose triangles a flip pass changes.
  int32_t v = -1;
  InterfaceMesh moved, flipped_freely;
  for (size_t n = 0; n < start.num_nodes() && v < 0; ++n) {
    if (phase_count(start.phases()[n]) != 2 ||
        node_projection_step(start, field, int32_t(n), start.positions()[n]).norm() <= 0.1 * scene.grid.h())
      continue;
    moved = start;
    std::vector<Vec3> delta(moved.num_nodes(), Vec3::Zero());
    delta[n] = node_projection_step(moved, field, int32_t(n), start.positions()[n]);
    ASSERT_EQ(commit_without_crossings(moved, delta, &field).undone_nodes, 0u);
    flipped_freely = moved;
    flip_edges(flipped_freely, params);
    if (triangles_at(flipped_freely, int32_t(n)) != triangles_at(moved, int32_t(n))) v = int32_t(n);
  }
  ASSERT_GE(v, 0);
  InterfaceMesh mesh = start;
  CrossingGuard guard;
  std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
  delta[size_t(v)] = node_projection_step(mesh, field, v, start.positions()[size_t(v)]);
  ASSERT_EQ(guard.commit(mesh, delta, &field, {}, 1.0).undone_nodes, 0u); // let through the floor
  const std::vector<int32_t> let_through = guard.floor_exception_nodes();
  ASSERT_EQ(let_through, std::vector<int32_t>{v});
  ASSERT_EQ(mesh.positions(), moved.positions());
  const auto before = triangles_at(mesh, v);
  FlipParams keeping = params;
  keeping.guard = &guard;
  keeping.keep_triangles_at = let_through;
  const FlipStats stats = flip_edges(mesh, keeping);
  EXPECT_EQ(triangles_at(mesh, v), before);
  EXPECT_GT(stats.flips, 0u);
  EXPECT_TRUE(validate(mesh.to_node_mesh()).ok());
  // Once no longer kept, the node's triangles flip again.
  keeping.keep_triangles_at = {};
  flip_edges(mesh, keeping);
  EXPECT_NE(triangles_at(mesh, v), before);
}

// Eight large overlapping spheres at a coarse grid: phases thinner than an edge
// between clusters of quadruple points (found by scripts/stress_improve.py).
constexpr const char* kCrowdedSpheres = R"({"grid": 32, "phases": [{"kind": "constant", "value": 0},
  {"kind": "sphere", "center": [0.2469, 0.2893, 0.6135], "radius": 0.3492},
  {"kind": "sphere", "center": [0.2969, 0.2291, 0.7920], "radius": 0.2334},
  {"kind": "sphere", "center": [0.4435, 0.3424, 0.5564], "radius": 0.3066},
  {"kind": "sphere", "center": [0.4734, 0.4531, 0.2334], "radius": 0.3290},
  {"kind": "sphere", "center": [0.2196, 0.4961, 0.7031], "radius": 0.1326},
  {"kind": "sphere", "center": [0.6390, 0.7699, 0.5782], "radius": 0.2970},
  {"kind": "sphere", "center": [0.2640, 0.4607, 0.2895], "radius": 0.3112},
  {"kind": "sphere", "center": [0.3769, 0.4719, 0.7996], "radius": 0.3131}]})";

// In a distributed run the ranks agree on each round's undone moves (improve/guard.hpp):
// a node another rank puts back (here the harmless far move, added by the
// hook as another rank's culprit would be) is put back here too, the rounds go
// on while any rank undoes something, and the hook sees every round.
TEST(Guard, undoes_the_moves_the_other_ranks_undo) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  const auto [v, w] = nodes_on_two_surfaces(mesh);
  ASSERT_GE(v, 0);
  const std::vector<Vec3> before = mesh.positions();
  std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
  delta[size_t(v)] = before[size_t(w)] - before[size_t(v)];
  const int32_t far = int32_t(mesh.num_nodes()) - 1 == v ? 0 : int32_t(mesh.num_nodes()) - 1;
  delta[size_t(far)] = Vec3(1e-6, 0, 0);
  std::vector<std::vector<int32_t>> rounds;
  const GuardReport report = commit_without_crossings(mesh, delta, nullptr, [&](std::vector<int32_t>& undone) {
    rounds.push_back(undone);
    if (rounds.size() == 1) undone.push_back(far); // "another rank's" culprit, in the first round
    return !undone.empty();
  });
  EXPECT_EQ(rounds.size(), 2u);                         // the round that undid something, then the clean one
  EXPECT_EQ(rounds[0], std::vector<int32_t>{v});        // this rank's own culprit
  EXPECT_TRUE(rounds[1].empty());
  EXPECT_EQ(report.undone_nodes, 2u);
  EXPECT_EQ(mesh.positions()[size_t(far)], before[size_t(far)]);
  EXPECT_TRUE(delta[size_t(far)].isZero(0));
  EXPECT_EQ(mesh.positions()[size_t(v)], before[size_t(v)]);
}

TEST(Guard, the_default_pipeline_never_crosses_where_the_unguarded_one_does) {
  const Scene scene = parse_scene(kCrowdedSpheres, "crowded spheres");
  const Pipeline pipeline = Pipeline::parse(kDefaultPipeline, builtin_registry());
  for (bool guard : {false, true}) {
    SCOPED_TRACE(guard ? "guarded" : "unguarded");
    InterfaceMesh mesh = initial_mesh(scene);
    size_t worst = 0, undone = 0;
    RunOptions run;
    run.iterations = 20;
    run.guard_crossings = guard;
    run.observer = [&](const IterationReport& r, const InterfaceMesh& m) {
      worst = std::max(worst, find_self_intersections(m.to_node_mesh()).count);
      undone += r.undone_moves;
    };
    pipeline.run(mesh, scene.field.get(), run);
    EXPECT_TRUE(validate(mesh.to_node_mesh()).ok());
    if (guard) {
      EXPECT_EQ(worst, 0u);
      EXPECT_GT(undone, 0u); // the guard had work to do
    } else {
      EXPECT_GT(worst, 0u); // the scene is hard enough to test the guard
    }
  }
}

/// The mesh `pipeline` makes of `scene` in `iterations`, with crossings looked
/// for every `every` iterations (RunOptions::check_crossings_every), on
/// `threads` threads; `reports` gets what the observer heard.
InterfaceMesh run_checking_every(const Scene& scene, const Pipeline& pipeline, int iterations, int every,
                                 std::vector<IterationReport>& reports, int threads = 2) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  InterfaceMesh mesh = initial_mesh(scene);
  RunOptions run;
  run.iterations = iterations;
  run.check_crossings_every = every;
  run.observer = [&](const IterationReport& r, const InterfaceMesh&) { reports.push_back(r); };
  pipeline.run(mesh, scene.field.get(), run);
  return mesh;
}

/// True when the two meshes have the same triangles and the same node positions, bit for bit.
bool same_mesh(const InterfaceMesh& a, const InterfaceMesh& b) {
  return a.positions() == b.positions() && a.triangles() == b.triangles();
}

// Where the guard never finds a crossing, looking for them once every few
// iterations leaves the mesh of looking in every one, bit for bit.
TEST(Guard, checking_every_few_iterations_where_nothing_crosses_makes_the_same_mesh) {
  const Scene scene = test::example_scene("voronoi7.json", 24);
  const Pipeline pipeline = Pipeline::parse(kDefaultPipeline, builtin_registry());
  std::vector<IterationReport> each, windowed;
  const InterfaceMesh checked_each = run_checking_every(scene, pipeline, 12, 1, each);
  const InterfaceMesh checked_every_4 = run_checking_every(scene, pipeline, 12, 4, windowed);
  EXPECT_TRUE(same_mesh(checked_each, checked_every_4));
  EXPECT_TRUE(std::none_of(each.begin(), each.end(), [](const IterationReport& r) { return r.crossings_deferred; }));
  // Windows of 4 after two quiet iterations, none found crossed: 3-6, 7-10, 11-12.
  ASSERT_EQ(windowed.size(), 13u);
  for (const IterationReport& r : windowed) {
    EXPECT_EQ(r.crossings_deferred, r.iteration >= 3) << r.iteration;
    EXPECT_FALSE(r.runs_again) << r.iteration;
  }
}

// A window whose end finds a crossing (30 Voronoi cells at grid 32, where
// the guard finds a few late in the run) runs again from its start with every
// move and flip checked: the mesh never keeps a crossing, and it does not
// depend on the thread count. With the paper's passes and with the scenes'
// default pipeline, whose remesh pass and collapses renumber the mesh the
// guard's index follows.
TEST(Guard, a_window_that_ends_crossed_runs_again_checked) {
  const Scene scene = test::example_scene("voronoi30.json", 32);
  for (const char* spec : {kDefaultPipeline, kScenePipeline}) {
    SCOPED_TRACE(spec);
    const Pipeline pipeline = Pipeline::parse(spec, builtin_registry());
    std::vector<IterationReport> reports, on_one_thread;
    const InterfaceMesh mesh = run_checking_every(scene, pipeline, 30, 3, reports);
    EXPECT_TRUE(validate(mesh.to_node_mesh()).ok());
    EXPECT_EQ(find_self_intersections(mesh.to_node_mesh()).count, 0u);
    const auto again =
        std::find_if(reports.begin(), reports.end(), [](const IterationReport& r) { return r.runs_again; });
    ASSERT_NE(again, reports.end()) << "no window ended crossed: the scene no longer tests the way back";
    // The window's iterations are heard again, each checked.
    const auto next = again + 1;
    ASSERT_NE(next, reports.end());
    EXPECT_LT(next->iteration, again->iteration);
    EXPECT_FALSE(next->crossings_deferred);
    EXPECT_EQ(reports.back().iteration, 30);
    // After each window that ended crossed, the next opens only after twice as
    // many checked iterations in a row as the last one needed (2, then 4, ...).
    // A lower bound only: the reports do not say which checked iterations found
    // a crossing, so this holds here with the doubling taken out too; the rule
    // itself is tested in windows_wait_twice_as_long_after_each_that_ended_crossed.
    size_t needed = 2, checked_in_a_row = 0;
    for (const IterationReport& r : reports) {
      if (r.iteration == 0) continue;
      if (r.crossings_deferred && checked_in_a_row > 0) EXPECT_GE(checked_in_a_row, needed) << r.iteration;
      checked_in_a_row = r.crossings_deferred ? 0 : checked_in_a_row + 1;
      if (r.runs_again) needed *= 2;
    }
    EXPECT_TRUE(same_mesh(mesh, run_checking_every(scene, pipeline, 30, 3, on_one_thread, 1)));
  }
}

// Windows open after two checked iterations in a row in which the guard found
// no crossing, and after each window that ended crossed, after twice as many
// (4, then 8): where crossings keep coming, few iterations run twice.
TEST(Guard, windows_wait_twice_as_long_after_each_that_ended_crossed) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(12));
  InterfaceMesh crossed = mesh; // a node of one surface moved onto a node of another
  const auto [v, w] = nodes_on_two_surfaces(mesh);
  ASSERT_GE(v, 0);
  std::vector<Vec3> jump(mesh.num_nodes(), Vec3::Zero());
  jump[size_t(v)] = mesh.positions()[size_t(w)] - mesh.positions()[size_t(v)];
  crossed.move_nodes(jump);
  CrossingGuard guard;
  const RunOptions options;
  detail::RunState state{detail::Convergence(options, 0, 0, 1), 0, 0};
  detail::CrossingWindows windows(3);
  // Runs iterations from `it` on, each finding a crossing if `finds` says so,
  // until one ends a window; returns the first iteration of that window.
  auto run_until_a_window_ends = [&](int& it, auto finds) {
    for (int first = 0;; ++it) {
      windows.before(it, mesh, state, guard);
      if (windows.is_open() && first == 0) first = it;
      if (!windows.is_open() && finds(it)) EXPECT_FALSE(guard.crossings(crossed, {}).empty());
      if (windows.after(it, 100, guard)) return first;
    }
  };
  auto never = [](int) { return false; };
  int it = 1;
  EXPECT_EQ(run_until_a_window_ends(it, never), 3); // after iterations 1 and 2
  EXPECT_EQ(it, 5);
  windows.close(true, it, mesh, state, guard); // crossed: back to before iteration 3
  EXPECT_EQ(it, 2);
  ++it;
  EXPECT_EQ(run_until_a_window_ends(it, never), 7); // after four: 3, 4, 5, 6
  windows.close(true, it, mesh, state, guard);
  ++it;
  // Eight now, counted anew after a crossing the guard found (iteration 8).
  EXPECT_EQ(run_until_a_window_ends(it, [](int i) { return i == 8; }), 17);
  windows.close(false, it, mesh, state, guard);
  EXPECT_FALSE(guard.defers_crossings());
  ++it;
  EXPECT_EQ(run_until_a_window_ends(it, never), 20); // after a clean window, the next at once
}

// The flip pass's first check may cost time in its flips alone only if the
// guard looked at the mesh as the flips found it: every change of positions
// or triangles gives the mesh a version the guard has not seen.
TEST(Guard, knows_whether_it_saw_the_mesh_as_it_is) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  CrossingGuard guard;
  EXPECT_FALSE(guard.checked_at(mesh.version())); // it saw no mesh yet
  const std::vector<uint8_t> all(mesh.num_triangles(), 1);
  guard.crossings(mesh, all);
  const uint64_t seen = mesh.version();
  EXPECT_TRUE(guard.checked_at(seen));
  const InterfaceMesh copy = mesh; // the same mesh: the same version
  EXPECT_EQ(copy.version(), seen);
  EXPECT_NE(InterfaceMesh::from_node_mesh(mesh.to_node_mesh()).version(), seen); // built anew
  auto changes_version = [&](const char* what, auto&& change) {
    SCOPED_TRACE(what);
    const uint64_t before = mesh.version();
    change();
    EXPECT_NE(mesh.version(), before);
    EXPECT_FALSE(guard.checked_at(mesh.version()));
  };
  changes_version("no move at all", [&] { mesh.move_nodes(std::vector<Vec3>(mesh.num_nodes(), Vec3::Zero())); });
  EXPECT_TRUE(guard.checked_at(seen)); // what it saw is still what it saw
  changes_version("a node placed", [&] {
    const int32_t n = 0;
    const Vec3 p = mesh.positions()[0];
    mesh.place_nodes(std::span(&n, 1), std::span(&p, 1));
  });
  changes_version("the mesh handed out for flips", [&] { mesh.omesh_for_topology(); });
  changes_version("faces changed", [&] { mesh.faces_changed(std::vector<int32_t>{0}); });
  changes_version("topology changed", [&] { mesh.topology_changed(); });
  changes_version("an edit", [&] {
    mesh.apply_edit(mesh.to_node_mesh(), test::identity(mesh.num_triangles()), test::identity(mesh.num_nodes()));
  });
  guard.crossings(mesh, all);
  EXPECT_TRUE(guard.checked_at(mesh.version()));
  // Its index files the renumbered at its next check.
  guard.renumbered(mesh, test::identity(mesh.num_triangles()), test::identity(mesh.num_nodes()));
  EXPECT_FALSE(guard.checked_at(mesh.version()));
}

// A guard that checked the mesh before the flips checks only the flipped faces
// first: the flip pass then keeps and undoes the same flips as with a guard
// that checks the whole mesh, on a mesh rough enough for flips to cross.
TEST(Guard, flips_checked_from_a_seen_mesh_are_those_a_whole_check_keeps) {
  InterfaceMesh rough = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> delta(rough.num_nodes());
  for (Vec3& d : delta) d = 0.45 / 16 * Vec3(u(rng), u(rng), u(rng));
  rough.move_nodes(delta);
  FlipParams params;
  params.collapse_below = 0;
  CrossingGuard seen;
  const std::vector<uint8_t> all(rough.num_triangles(), 1);
  for (int call = 0; call < 3; ++call) seen.crossings(rough, all); // until it keeps an index
  ASSERT_NE(seen.index_for(rough), nullptr);
  ASSERT_TRUE(seen.checked_at(rough.version()));
  auto flipped = [&](CrossingGuard* guard, bool guarded) {
    InterfaceMesh mesh = rough;
    FlipParams p = params;
    p.guard = guard;
    p.guard_crossings = guarded;
    flip_edges(mesh, p);
    return mesh.to_node_mesh().triangles;
  };
  const auto from_seen = flipped(&seen, true), whole = flipped(nullptr, true), unguarded = flipped(nullptr, false);
  EXPECT_EQ(from_seen, whole);
  EXPECT_NE(whole, unguarded); // the guard had flips to undo
}

} // namespace
