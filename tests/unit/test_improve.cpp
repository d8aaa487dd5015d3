// Tests of mesh improvement (paper sect. 4.2-4.3): after every iteration the mesh
// stays valid, uninverted and free of self-intersections; nodes end on their
// surfaces, curves and points; results do not depend on the thread count.

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/clamp.hpp"
#include "voronoimesh/improve/flip.hpp"
#include "voronoimesh/improve/offsets.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/project.hpp"
#include "voronoimesh/mesh/junctions.hpp"

#include "fixtures.hpp"
#include "mesh_checks.hpp"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <tuple>

namespace {

using namespace vm;

Scene example(const std::string& name, int grid) { return test::example_scene(name, grid); }

using test::initial_mesh;
using test::iterations;

// Checked in every iteration on the shipped scenes at their own grid, run as its
// two halves: after the moving passes (smooth, project, clamp) no triangle has
// turned over (the clamping guarantee; topology is unchanged there, so faces can
// be followed by index) and nothing intersects; after the flips (and collapses)
// the topology is valid, nothing intersects, and every normal points from its
// first phase into its second in the closed-form field.
// (On the 30-seed scene, whose quadruple points lie closer than a grid cell,
// tiny triangles at junctions used to stand across their surface in iterations
// 1-3; the guard now undoes the moves and flips that would do that.)
TEST(Improve, every_iteration_keeps_the_mesh_valid_uninverted_and_unintersected) {
  const PassRegistry registry = builtin_registry();
  const Pipeline moving = Pipeline::parse("smooth,project,clamp", registry);
  const Pipeline flips = Pipeline::parse("flip", registry);
  for (const char* name : {"four_spheres.json", "voronoi30.json", "split_sphere.json"}) {
    SCOPED_TRACE(name);
    Scene scene = example(name, 64);
    InterfaceMesh mesh = initial_mesh(scene);
    for (int it = 1; it <= 20; ++it) {
      const std::vector<Vec3> before = test::face_normals(mesh);
      moving.run(mesh, scene.field.get(), iterations(1));
      const std::vector<Vec3> after = test::face_normals(mesh);
      EXPECT_EQ(test::turned_faces(before, after), 0u) << "iteration " << it;
      EXPECT_EQ(find_self_intersections(mesh.to_node_mesh()).count, 0u) << "iteration " << it << ", after moving";

      flips.run(mesh, scene.field.get(), iterations(1));
      const NodeMesh m = mesh.to_node_mesh();
      ValidationReport report = validate(m);
      ASSERT_TRUE(report.ok()) << "iteration " << it << "\n" << report.summary();
      EXPECT_EQ(test::inverted_triangles(m, *scene.field), 0u) << "iteration " << it;
      EXPECT_EQ(find_self_intersections(m).count, 0u) << "iteration " << it << ", after flipping";
    }
  }
}

/// Distances of all nodes from their closed-form interface, in units of h, sorted.
std::vector<double> distances_in_h(const InterfaceMesh& m, const PhaseField& f, double h) {
  std::vector<double> d;
  for (size_t v = 0; v < m.num_nodes(); ++v) {
    const PhaseSet& s = m.phases()[v];
    const Vec3& x = m.positions()[v];
    double worst = 0;
    for (int i = 0; i < phase_count(s); ++i)
      for (int j = i + 1; j < phase_count(s); ++j) {
        const Vec3 g = f.gradient(s[size_t(i)], x) - f.gradient(s[size_t(j)], x);
        if (g.norm() > 0.1)
          worst = std::max(worst, std::abs(f.value(s[size_t(i)], x) - f.value(s[size_t(j)], x)) / g.norm());
      }
    d.push_back(worst / h);
  }
  std::sort(d.begin(), d.end());
  return d;
}

// After 20 iterations nodes lie on their surfaces, curves and points: every node
// within 0.05 h on the four spheres; 99% of them on the 30-seed scene and the
// split sphere, whose worst nodes (near quadruple points closer than a cell, and
// on the sphere's sharp rim) are still up to 0.14 h off (issue 3 notes). With
// the scenes' default pipeline (remesh first) the worst few are farther: on 30
// seeds a quadruple point 0.22 h and a curve node on the box 0.28 h off, on the
// split sphere three rim nodes 0.15 h off, held where moving them would lower
// the worst triangle (docs/algorithm.md, known gaps).
TEST(Improve, nodes_end_on_their_surfaces_curves_and_points) {
  const PassRegistry registry = builtin_registry();
  for (const auto& [pipeline, worst] : {std::pair{kDefaultPipeline, 0.14}, std::pair{kScenePipeline, 0.3}})
    for (const char* name : {"four_spheres.json", "voronoi30.json", "split_sphere.json"}) {
      SCOPED_TRACE(std::string(name) + ", " + pipeline);
      Scene scene = example(name, 64);
      InterfaceMesh mesh = initial_mesh(scene);
      Pipeline::parse(pipeline, registry).run(mesh, scene.field.get(), iterations(20));
      const std::vector<double> d = distances_in_h(mesh, *scene.field, scene.grid.h());
      EXPECT_LT(d[d.size() * 99 / 100], 0.05);
      // The bounds docs/algorithm.md gives, which may only shrink.
      if (std::string(name) == "four_spheres.json") EXPECT_LT(d.back(), 0.05);
      else EXPECT_LT(d.back(), worst) << "worst node " << d.back() << " h off";
    }
}

/// Eight spheres apart in the outside phase (no three overlapping): triple
/// curves are circles where two sphere surfaces meet.
constexpr const char* kEightSpheres = R"({"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": 40, "phases": [
  {"name": "outside", "kind": "constant", "value": 0},
  {"name": "s1", "kind": "sphere", "center": [0.740, 0.304, 0.713], "radius": 0.141},
  {"name": "s2", "kind": "sphere", "center": [0.559, 0.285, 0.335], "radius": 0.150},
  {"name": "s3", "kind": "sphere", "center": [0.742, 0.580, 0.203], "radius": 0.137},
  {"name": "s4", "kind": "sphere", "center": [0.417, 0.562, 0.435], "radius": 0.161},
  {"name": "s5", "kind": "sphere", "center": [0.568, 0.360, 0.586], "radius": 0.161},
  {"name": "s6", "kind": "sphere", "center": [0.211, 0.224, 0.767], "radius": 0.125},
  {"name": "s7", "kind": "sphere", "center": [0.465, 0.239, 0.306], "radius": 0.167},
  {"name": "s8", "kind": "sphere", "center": [0.706, 0.755, 0.722], "radius": 0.164}]})";

/// Root mean square and largest distance of the triple-curve nodes inside the
/// box from their closed-form curve, in units of h: how far eq. 4, iterated
/// until it stops moving, takes each (to first order the distance to the curve).
std::pair<double, double> curve_offsets_in_h(const InterfaceMesh& m, const PhaseField& f, double h) {
  double sum = 0, worst = 0;
  size_t count = 0;
  for (size_t v = 0; v < m.num_nodes(); ++v) {
    const PhaseSet& s = m.phases()[v];
    if (phase_count(s) != 3 || m.box_faces()[v]) continue;
    const std::array<int32_t, 3> phases{s[0], s[1], s[2]};
    Vec3 on_curve = m.positions()[v];
    for (int step = 0; step < 100; ++step) on_curve += projection_step(f, on_curve, phases, ProjectParams{});
    const double d = (on_curve - m.positions()[v]).norm() / h;
    sum += d * d, worst = std::max(worst, d), ++count;
  }
  return {std::sqrt(sum / double(count)), worst};
}

/// Four balls (x, y, z, radius) in the unit box over an outside phase, grid 48:
/// a scene of bench/junction_scenes.sh's kind.
Scene four_balls(const std::array<std::array<double, 4>, 4>& balls, const char* name) {
  std::string json = R"({"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": 48, "phases": [)"
                     R"({"name": "outside", "kind": "constant", "value": 0})";
  for (size_t i = 0; i < balls.size(); ++i) {
    char ball[160];
    std::snprintf(ball, sizeof ball, R"(, {"name": "ball%zu", "kind": "sphere", "center": [%g, %g, %g], "radius": %g})",
                  i, balls[i][0], balls[i][1], balls[i][2], balls[i][3]);
    json += ball;
  }
  return parse_scene(json + "]}", name);
}

// Triple curves converge onto the closed-form curves and stay there. The
// paper's half-Laplacian on a curve node pulls it toward the curve's centre of
// curvature; projection undid only part of that each iteration, so curve nodes
// sat 0.07-0.12 h RMS (up to 0.45 h) off their circles, worse after 60
// iterations than after 5, while surface nodes converged to 1e-4 h. Forces on
// curve nodes are now kept along the curve (improve/smooth.hpp): measured
// 0.0014 h RMS (max 0.008 h) after 20 iterations, below 1e-4 h after 60.
TEST(Improve, triple_curve_nodes_converge_onto_their_curves) {
  const Scene scene = parse_scene(kEightSpheres, "eight spheres");
  const double h = scene.grid.h();
  // With remesh first (the scenes' default) three curve nodes stay 0.016-0.025
  // h off, beside the mesh's worst triangle: moving them on would lower it, and
  // the quality floor lets offsets below 0.02 of an edge stand (improve/guard.cpp).
  for (const auto& [name, worst] : {std::pair{kDefaultPipeline, 0.01}, std::pair{kScenePipeline, 0.03}}) {
    SCOPED_TRACE(name);
    InterfaceMesh mesh = initial_mesh(scene);
    const Pipeline pipeline = Pipeline::parse(name, builtin_registry());
    pipeline.run(mesh, scene.field.get(), iterations(20));
    const auto [rms20, worst20] = curve_offsets_in_h(mesh, *scene.field, h);
    std::printf("%s: triple-curve nodes off their curve: 20 iterations %.5f h RMS, max %.5f h\n", name, rms20,
                worst20);
    EXPECT_LT(rms20, 0.01);
    EXPECT_LT(worst20, 0.05);
    pipeline.run(mesh, scene.field.get(), iterations(40));
    const auto [rms60, worst60] = curve_offsets_in_h(mesh, *scene.field, h);
    std::printf("%s: triple-curve nodes off their curve: 60 iterations %.5f h RMS, max %.5f h\n", name, rms60,
                worst60);
    EXPECT_LE(rms60, rms20);
    EXPECT_LT(worst60, worst);
  }
}

// The quality floor no longer holds triple-curve nodes off their curves for a
// triangle that stays at q 0.4 or better (improve/guard.cpp): eq. 4 takes a
// curve node a third of the way per iteration, so its moves never halved its
// step, which was the floor's only way through. On this scene of four random
// balls (bench/junction_scenes.sh's balls_5), 20 iterations: a curve node
// stayed 0.60 h off (0.064 h RMS over the curves), the worst triangle at q
// 0.522 beside it; released, every curve node ends within 0.031 h (0.0026 h
// RMS), and min q is 0.658.
TEST(Improve, the_quality_floor_lets_curve_nodes_reach_their_curves) {
  const Scene scene = four_balls({{{0.6512, 0.4396, 0.6163, 0.2927},
                                   {0.4249, 0.6073, 0.4339, 0.1746},
                                   {0.4393, 0.6005, 0.359, 0.2489},
                                   {0.4405, 0.3676, 0.472, 0.208}}},
                                 "balls_5");
  InterfaceMesh mesh = initial_mesh(scene);
  Pipeline::parse(kScenePipeline, builtin_registry()).run(mesh, scene.field.get(), iterations(20));
  const auto [rms, worst] = curve_offsets_in_h(mesh, *scene.field, scene.grid.h());
  std::printf("balls_5: triple-curve nodes off their curve %.4f h RMS, max %.4f h; min q %.3f\n", rms, worst,
              quality_summary(mesh).first);
  EXPECT_LT(worst, 0.05); // issue 18's bar
  EXPECT_GT(quality_summary(mesh).first, 0.6);
  EXPECT_TRUE(validate(mesh).ok());
}

// Quadruple points reach their closed-form place. Four random balls (the
// fourth of bench/junction_scenes.sh's): eq. 4's mean of the pairs' steps left
// the point of the outside, ball0, ball2 and ball3 0.59 h off after 20 iterations
// and after 60, though the balls meet at 87-131 degrees there; the scenes'
// default takes the least-squares step at points and puts every point there.
TEST(Improve, quadruple_points_reach_their_place_under_the_scene_default) {
  const Scene scene = four_balls({{{0.6916, 0.4825, 0.5875, 0.2602},
                                   {0.386, 0.3312, 0.5411, 0.1683},
                                   {0.4529, 0.6559, 0.6489, 0.1678},
                                   {0.3329, 0.389, 0.6312, 0.1537}}},
                                 "four balls");
  const double h = scene.grid.h();
  const std::string least_squares = "project:least_squares_from=4", default_spec = kScenePipeline;
  const std::string eq4 =
      std::string(default_spec).replace(default_spec.find(least_squares), least_squares.size(), "project");
  ASSERT_NE(default_spec.find(least_squares), std::string::npos);
  for (const std::string& spec : {eq4, default_spec}) {
    SCOPED_TRACE(spec);
    InterfaceMesh mesh = initial_mesh(scene);
    Pipeline::parse(spec, builtin_registry()).run(mesh, scene.field.get(), iterations(20));
    const NodeOffsets points = interface_offsets(mesh.to_node_mesh(), *scene.field)[2];
    std::printf("%s: %zu points, farthest %.3g h off\n", spec.c_str(), points.nodes, points.max / h);
    ASSERT_EQ(points.nodes, 4u);
    if (spec == eq4) EXPECT_GT(points.max / h, 0.3); // where eq. 4 stalls
    else EXPECT_LT(points.max / h, 0.01);
  }
}

// More iterations do not hurt: each iteration's commit undoes the moves that
// would leave a triangle below the worst quality the iteration started with
// (unless the move brings its node at least halfway to its surface or curve,
// tested in test_guard.cpp), and flips only raise their pair's smaller quality,
// ears aside. Before the floor, min q after 50 iterations was below that after
// 20 on the four spheres (0.423 against 0.469).
TEST(Improve, fifty_iterations_leave_the_worst_triangle_no_worse_than_twenty) {
  const Pipeline pipeline = Pipeline::parse(kDefaultPipeline, builtin_registry());
  for (const auto& [name, grid] : {std::pair{"four_spheres.json", 64}, std::pair{"voronoi7.json", 44}}) {
    SCOPED_TRACE(name);
    const Scene scene = example(name, grid);
    InterfaceMesh mesh = initial_mesh(scene);
    pipeline.run(mesh, scene.field.get(), iterations(20));
    const double after20 = quality_summary(mesh).first;
    pipeline.run(mesh, scene.field.get(), iterations(30));
    const double after50 = quality_summary(mesh).first;
    std::printf("%s: min q %.3f after 20 iterations, %.3f after 50\n", name, after20, after50);
    EXPECT_GE(after50, after20);
  }
}

// The floor pass: a move that brings a node onto its interface goes through the
// quality floor (Guard, quality_floor_...), and could leave the iteration's
// worst triangle worse than it began; the floor pass, last in the remeshing
// pipelines, takes such moves back then. Thirty cells at grid 64 lost the worst
// triangle in two iterations without it (0.393 at the end), in none with it
// (0.487). The remesh pass (iterations 1-3) may still lower it: it changes
// triangles, not moves (here 0.407 -> 0.406 in iteration 3, since the default
// takes the least-squares step at quadruple points), so only the iterations
// after it count. A triple-curve node far off its curve may take the worst
// triangle down to q 0.4 (improve/guard.hpp): here from 0.433 to 0.406 in
// iteration 5, a fall that does not count (without the floor pass it falls on
// to 0.372 in iteration 6).
TEST(Improve, the_floor_pass_keeps_the_worst_triangle_from_getting_worse) {
  const Scene scene = example("voronoi30.json", 64);
  constexpr int kRemeshLast = 3; // the remesh pass's default `last`
  constexpr double kCurveNodesMayTakeItTo = 0.4;
  const std::string with_floor = kScenePipeline;
  ASSERT_TRUE(with_floor.ends_with(",floor"));
  const std::string without_floor = with_floor.substr(0, with_floor.size() - 6);
  for (const std::string& spec : {without_floor, with_floor}) {
    SCOPED_TRACE(spec);
    InterfaceMesh mesh = initial_mesh(scene);
    RunOptions run = iterations(20);
    int drops = 0;
    double previous = 0;
    run.observer = [&](const IterationReport& r, const InterfaceMesh&) {
      if (r.iteration > kRemeshLast && r.min_quality < std::min(previous, kCurveNodesMayTakeItTo)) ++drops;
      previous = r.min_quality;
    };
    Pipeline::parse(spec, builtin_registry()).run(mesh, scene.field.get(), run);
    std::printf("%s: min q %.3f, fell in %d iterations\n", spec.c_str(), previous, drops);
    if (spec == with_floor) EXPECT_EQ(drops, 0);
    else EXPECT_GT(drops, 0); // what the floor pass is for
  }
}

// A triangle at a quadruple point with its two edges on two curves is a
// corner triangle, not an ear (whose three corners lie on one curve): flipping
// it only moved it beside the next corner node, where it was an "ear" again
// and flipped back, every round of every iteration. On the 30-seed scene such
// pairs kept min q at 0.064 after 20 iterations (0.237 with ear flips limited
// to ears below q 0.05, which was then the better choice); with corner
// triangles left alone, flipping every ear is the better one (0.246).
TEST(Improve, corner_triangles_are_no_ears_and_do_not_flip_back_and_forth) {
  const Scene scene = example("voronoi30.json", 64);
  const PassRegistry registry = builtin_registry();
  double worst[2];
  for (int limited = 0; limited < 2; ++limited) {
    InterfaceMesh mesh = initial_mesh(scene);
    Pipeline::parse(limited ? "smooth,project,clamp,flip:ear_below=0.05" : kDefaultPipeline, registry)
        .run(mesh, scene.field.get(), iterations(20));
    worst[limited] = quality_summary(mesh).first;
  }
  std::printf("voronoi30, 20 iterations: min q %.3f (every ear flips), %.3f (ears below 0.05)\n", worst[0], worst[1]);
  EXPECT_GT(worst[0], 0.2);
  EXPECT_GE(worst[0], worst[1]);
}

// The flip pass's collapses (improve/collapse.hpp) on the 30 seeds, whose
// quadruple points lie closer than a cell at these grids. At grid 48 two of
// them sit 0.02 h apart and every triangle between them was a sliver (min q
// 0.065): they now merge into one point of five phases. At grid 32, collapses
// at q 0.15 once traded slivers for worse ones (min q 0.007); a collapse must
// now leave every triangle it changes better than the sliver.
TEST(Improve, collapses_merge_close_quadruple_points_and_never_trade_a_sliver_for_a_worse_one) {
  for (const auto& [grid, merged, floor] : {std::tuple{48, true, 0.15}, std::tuple{32, false, 0.05}}) {
    SCOPED_TRACE(grid);
    const Scene scene = example("voronoi30.json", grid);
    InterfaceMesh mesh = initial_mesh(scene);
    Pipeline::parse(kDefaultPipeline, builtin_registry()).run(mesh, scene.field.get(), iterations(20));
    const NodeMesh m = mesh.to_node_mesh();
    EXPECT_TRUE(validate(m).ok()) << validate(m).summary();
    EXPECT_TRUE(find_self_intersections(m).ok());
    const Junctions j = find_junctions(m);
    const bool five = std::any_of(j.quadruple_points.begin(), j.quadruple_points.end(),
                                  [&](int32_t q) { return j.order(size_t(q)) > 4; });
    std::printf("voronoi30 at grid %d: min q %.3f, a point of five phases: %d\n", grid,
                quality_summary(mesh).first, int(five));
    if (merged) EXPECT_TRUE(five);
    EXPECT_GT(quality_summary(mesh).first, floor);
  }
}

// After collapse_last the flip pass collapses the slivers near the worst only
// in batches: in the run's last iteration and every collapse_every before it
// (every iteration where the last is not known); between batches only those
// worse than the floor, which a floor of 0 leaves none of. The created mesh has
// junction slivers below the 0.01 a batch takes with that floor.
TEST(Improve, late_sliver_collapses_come_in_batches_that_end_the_run) {
  const Scene scene = example("voronoi30.json", 48);
  const Pipeline flip = Pipeline::parse("flip:collapse_last=5:collapse_every=5", builtin_registry());
  const auto passes = flip.make_passes();
  auto collapses_in = [&](int iteration, int last) {
    InterfaceMesh mesh = initial_mesh(scene);
    const size_t before = mesh.num_triangles();
    PassContext context(mesh, scene.field.get());
    context.iteration = iteration;
    context.iterations = last;
    context.quality_floor = 0;
    flip.iterate(context, passes);
    return mesh.num_triangles() < before;
  };
  EXPECT_TRUE(collapses_in(5, 20));   // up to collapse_last: every iteration
  EXPECT_FALSE(collapses_in(7, 20));  // 13 before the last
  EXPECT_TRUE(collapses_in(10, 20));  // 10 before it
  EXPECT_FALSE(collapses_in(19, 20));
  EXPECT_TRUE(collapses_in(20, 20));  // the last
  EXPECT_TRUE(collapses_in(23, 23));
  EXPECT_TRUE(collapses_in(7, 0));    // the last not known
}

// Quadruple points are not moved by forces, only projected onto the exact point
// where their four phases tie: they converge there and stay.
TEST(Improve, quadruple_points_stay_put) {
  Scene scene = example("four_spheres.json", 64);
  InterfaceMesh mesh = initial_mesh(scene);
  const Pipeline pipeline = Pipeline::parse(kDefaultPipeline, builtin_registry());
  auto quadruple_positions = [&] {
    std::vector<Vec3> out;
    for (size_t v = 0; v < mesh.num_nodes(); ++v)
      if (phase_count(mesh.phases()[v]) >= 4) out.push_back(mesh.positions()[v]);
    return out;
  };
  pipeline.run(mesh, scene.field.get(), iterations(10));
  const std::vector<Vec3> after10 = quadruple_positions();
  ASSERT_EQ(after10.size(), 5u);
  pipeline.run(mesh, scene.field.get(), iterations(10));
  const std::vector<Vec3> after20 = quadruple_positions();
  const double h = scene.grid.h();
  for (size_t q = 0; q < after10.size(); ++q) EXPECT_LT((after20[q] - after10[q]).norm(), 1e-2 * h);
}

TEST(Improve, paper_pipeline_reaches_the_quality_aim_on_the_four_spheres) {
  Scene scene = example("four_spheres.json", 64);
  InterfaceMesh mesh = initial_mesh(scene);
  Pipeline::parse(kDefaultPipeline, builtin_registry()).run(mesh, scene.field.get(), iterations(20));
  const MeshStats s = compute_stats(mesh.to_node_mesh());
  EXPECT_GE(s.min_quality, 0.3);
  EXPECT_GT(s.mean_quality, 0.9);
  EXPECT_LT(double(s.below_half), 0.005 * double(s.triangles));
  EXPECT_EQ(s.surfaces, 10u);
  EXPECT_EQ(s.triple_curves, 10u);
  EXPECT_EQ(s.quadruple_points, 5u);
}

// The paper's pipeline, and the scenes' default (remesh, collapses, and the
// polish pass from iteration 6).
TEST(Improve, output_is_identical_for_any_thread_count) {
  Scene scene = example("voronoi30.json", 32);
  for (const char* pipeline : {kDefaultPipeline, kScenePipeline}) {
    NodeMesh reference;
    for (int threads : {1, 2, 8}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
      InterfaceMesh mesh = initial_mesh(scene);
      Pipeline::parse(pipeline, builtin_registry()).run(mesh, scene.field.get(), iterations(8));
      NodeMesh m = mesh.to_node_mesh();
      if (threads == 1) {
        reference = m;
        continue;
      }
      EXPECT_EQ(m.points, reference.points) << pipeline << ", " << threads << " threads";
      EXPECT_EQ(m.triangles, reference.triangles) << pipeline << ", " << threads << " threads";
      EXPECT_EQ(m.pairs, reference.pairs) << pipeline << ", " << threads << " threads";
    }
  }
}

// A distributed run improves parts of the mesh built afresh, whose triangles
// come in another order (so OpenMesh numbers edges and orients halfedges
// differently); the result may depend only on the nodes and triangles
// themselves. Checked here with every triangle in reverse order: the same
// positions bit for bit and the same triangles.
TEST(Improve, result_does_not_depend_on_the_order_of_the_triangles) {
  Scene scene = example("voronoi30.json", 32);
  const NodeMesh created = test::created_mesh(scene);
  NodeMesh reversed = created;
  std::reverse(reversed.triangles.begin(), reversed.triangles.end());
  std::reverse(reversed.pairs.begin(), reversed.pairs.end());
  auto improved = [&](const NodeMesh& m) {
    InterfaceMesh mesh = InterfaceMesh::from_node_mesh(m);
    Pipeline::parse(kDefaultPipeline, builtin_registry()).run(mesh, scene.field.get(), iterations(8));
    return mesh.to_node_mesh();
  };
  const NodeMesh a = improved(created), b = improved(reversed);
  auto triangle_set = [](const NodeMesh& m) {
    std::set<std::pair<std::array<int32_t, 3>, PhasePair>> out;
    for (size_t t = 0; t < m.num_triangles(); ++t) out.insert({m.triangles[t], m.pairs[t]});
    return out;
  };
  ASSERT_EQ(a.points.size(), b.points.size());
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(triangle_set(a), triangle_set(b));
}

// Algorithm 3 and eq. 5: whatever the three corners do, each within half its own
// clamp, the triangle does not invert.
TEST(Clamp, no_triangle_inverts_whatever_its_corners_do) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0, 1);
  auto rand_vec = [&] { return Vec3(g(rng), g(rng), g(rng)); };
  for (int trial = 0; trial < 20000; ++trial) {
    std::array<Vec3, 3> v = {rand_vec(), rand_vec(), rand_vec()};
    const Vec3 normal = (v[1] - v[0]).cross(v[2] - v[0]);
    if (normal.norm() < 1e-3) continue;
    std::array<Vec3, 3> moved;
    for (int c = 0; c < 3; ++c) {
      Vec3 d = 3 * rand_vec();
      const double s = clamp_step(d, v[size_t(c)], v[size_t((c + 1) % 3)], v[size_t((c + 2) % 3)]);
      moved[size_t(c)] = v[size_t(c)] + std::min(1.0, 0.5 * s) * d;
    }
    const Vec3 after = (moved[1] - moved[0]).cross(moved[2] - moved[0]);
    ASSERT_GT(after.dot(normal), 0) << "trial " << trial;
  }
}

TEST(Clamp, allows_the_full_step_when_it_is_safe) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(clamp_step(Vec3(-1, -1, 0), a, b, c), INFINITY); // moving away from the opposite edge
  EXPECT_NEAR(clamp_step(Vec3(1, 1, 0), a, b, c), 0.25, 1e-12); // reaches the midline x + y = 1/2
}

TEST(Clamp, keeps_a_node_inside_the_domain_box) {
  const Box unit{Vec3::Zero(), Vec3::Ones()};
  const Vec3 x(0.5, 0.9, 0.5);
  EXPECT_EQ(box_step(Vec3(0, -1, 0), x, unit, 0), 0.9);                  // down to y = 0
  EXPECT_NEAR(box_step(Vec3(0.1, 0.2, 0), x, unit, 0), 0.5, 1e-12);     // y = 1 first
  EXPECT_EQ(box_step(Vec3(0, 0.2, 0), Vec3(0.5, 1, 0.5), unit, uint8_t(1u << 3)), INFINITY); // held on y = 1
  EXPECT_EQ(box_step(Vec3(0, 0.2, 0), Vec3(0.5, 1.1, 0.5), unit, 0), INFINITY); // already out: no limit
}

// eq. 5 on a whole mesh after flips (whose faces clamp_displacements() reads
// from triangles()): every node's move is scaled by the least of 1 and half
// its box step and of each of its triangles' clamp steps, found here node by
// node through OpenMesh, for moves large enough to hold many nodes back.
TEST(Clamp, scales_each_move_by_the_least_step_of_the_nodes_triangles) {
  Scene scene = example("voronoi7.json", 24);
  InterfaceMesh mesh = initial_mesh(scene);
  FlipParams flips_only;
  flips_only.collapse_below = 0;
  ASSERT_GT(flip_edges(mesh, flips_only).flips, 0u);
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 0.02);
  std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero()); // Eigen leaves a default Vec3 unset
  for (size_t v = 0; v < delta.size(); ++v)
    if (v % 5 != 0) delta[v] = Vec3(g(rng), g(rng), g(rng)); // every fifth node stays
  std::vector<Vec3> clamped = delta;
  clamp_displacements(mesh, ClampParams{}, clamped);
  const auto& pos = mesh.positions();
  size_t held = 0;
  for (size_t v = 0; v < delta.size(); ++v) {
    double scale = delta[v].isZero(0) ? 1 : std::min(1.0, 0.5 * box_step(delta[v], pos[v], mesh.domain(),
                                                                          mesh.box_faces()[v]));
    if (!delta[v].isZero(0))
      mesh.for_each_triangle_at(int32_t(v), [&](int32_t a, int32_t b) {
        scale = std::min(scale, 0.5 * clamp_step(delta[v], pos[v], pos[size_t(a)], pos[size_t(b)]));
      });
    ASSERT_EQ(clamped[v], Vec3(scale * delta[v])) << "node " << v;
    held += scale < 1;
  }
  EXPECT_GT(held, delta.size() / 4);
}

TEST(Flip, improves_quality_and_never_touches_junctions) {
  Scene scene = example("four_spheres.json", 32);
  InterfaceMesh mesh = initial_mesh(scene);
  const NodeMesh before = mesh.to_node_mesh();
  const MeshStats s0 = compute_stats(before);
  FlipParams flips_only; // collapses change junctions on purpose (test_collapse.cpp)
  flips_only.collapse_below = 0;
  FlipStats fs = flip_edges(mesh, flips_only);
  const NodeMesh after = mesh.to_node_mesh();
  EXPECT_GT(fs.flips, 0u);
  EXPECT_TRUE(validate(after).ok()) << validate(after).summary();
  const MeshStats s1 = compute_stats(after);
  EXPECT_GE(s1.min_quality, s0.min_quality);
  EXPECT_GT(s1.mean_quality, s0.mean_quality);
  EXPECT_EQ(s1.triple_curves, s0.triple_curves);
  EXPECT_EQ(s1.triangles, s0.triangles);
  // Junction edges (three or more triangles) are the same set before and after.
  auto junction_edges = [](const NodeMesh& m) {
    std::map<std::pair<int32_t, int32_t>, int> count;
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k) count[std::minmax(t[size_t(k)], t[size_t((k + 1) % 3)])]++;
    std::set<std::pair<int32_t, int32_t>> out;
    for (const auto& [e, n] : count)
      if (n >= 3) out.insert(e);
    return out;
  };
  EXPECT_EQ(junction_edges(after), junction_edges(before));
}

// A strip of identical parallelograms, each split along its long diagonal:
// every diagonal gains the same from a flip, and neighbouring quads share two
// nodes, so which of them flip is decided by the tie-break alone. It must come
// from the nodes, not from OpenMesh's edge ids (which follow the triangle
// order): reversing the triangles' order must not change the result. (Breaking
// ties by edge id flipped quads 0, 2, 4, 7 one way and 0, 3, 5, 7 the other.)
TEST(Flip, ties_are_broken_by_the_nodes_not_by_the_triangle_order) {
  NodeMesh strip;
  strip.domain = {Vec3(-1, -1, 0), Vec3(10, 2, 1)};
  const int n = 8;
  // Coordinates in quarters: every quad's gain is bitwise the same.
  for (int i = 0; i <= n; ++i) strip.points.push_back(Vec3(i, 0, 0.5));        // bottom node i
  for (int i = 0; i <= n; ++i) strip.points.push_back(Vec3(i + 0.75, 1, 0.5)); // top node n + 1 + i
  for (int i = 0; i < n; ++i) {
    const int32_t b0 = i, b1 = i + 1, t0 = n + 1 + i, t1 = n + 2 + i;
    strip.triangles.push_back({b0, b1, t1});
    strip.triangles.push_back({b0, t1, t0});
  }
  strip.pairs.assign(strip.triangles.size(), PhasePair{0, 1});
  NodeMesh reversed = strip;
  std::reverse(reversed.triangles.begin(), reversed.triangles.end());
  auto flipped = [](const NodeMesh& m) {
    InterfaceMesh mesh = InterfaceMesh::from_node_mesh(m);
    FlipParams params;
    params.collapse_below = 0;
    params.max_rounds = 1; // the greedy choice among equals, nothing after it
    EXPECT_EQ(flip_edges(mesh, params).flips, 4u);
    std::set<std::array<int32_t, 3>> out;
    for (auto t : mesh.to_node_mesh().triangles) {
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      out.insert(t);
    }
    return out;
  };
  EXPECT_EQ(flipped(strip), flipped(reversed));
}

} // namespace
