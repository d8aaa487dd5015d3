// The library API for programs that hold their own data (fields/array_input.hpp,
// run/meshing.hpp, mesh/queries.hpp): arrays give the same meshes as the matching
// files, the one-call mesher's options do what they say, queries measure what
// the geometry says, and every mistake is a vm::Error naming the problem.

#include "voronoimesh/voronoimesh.hpp"

#include "nrrd_file.hpp"
#include "scratch_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

namespace vm {
namespace {

constexpr double kRadius = 0.3;
const Vec3 kCentreA(0.37, 0.5, 0.5), kCentreB(0.66, 0.52, 0.49);

/// Two overlapping spheres in the unit box, as a simulation would hold them:
/// signed distances (positive inside) of background, A and B on the grid nodes.
struct TwoSpheres {
  GridSpec grid;
  std::vector<double> background, a, b;

  explicit TwoSpheres(int cells) {
    grid.cells = {cells, cells, cells};
    const auto n = grid.nodes();
    for (int64_t k = 0; k < n[2]; ++k)
      for (int64_t j = 0; j < n[1]; ++j)
        for (int64_t i = 0; i < n[0]; ++i) {
          const Vec3 x = grid.node_position(i, j, k);
          a.push_back(kRadius - (x - kCentreA).norm());
          b.push_back(kRadius - (x - kCentreB).norm());
          background.push_back(-std::max(a.back(), b.back()));
        }
  }
  std::vector<double> interleaved() const {
    std::vector<double> v;
    for (size_t n = 0; n < a.size(); ++n) v.insert(v.end(), {background[n], a[n], b[n]});
    return v;
  }
  Scene scene(const PhaseValuesOptions& o = {}) const { return scene_from_phase_values(grid, {background, a, b}, o); }
};

MeshOptions quick(int iterations = 5) {
  MeshOptions o;
  o.iterations = iterations;
  return o;
}

void expect_same_mesh(const NodeMesh& x, const NodeMesh& y) {
  ASSERT_EQ(x.num_nodes(), y.num_nodes());
  ASSERT_GT(x.num_triangles(), 0u);
  EXPECT_EQ(x.points, y.points);
  EXPECT_EQ(x.triangles, y.triangles);
  EXPECT_EQ(x.pairs, y.pairs);
  EXPECT_EQ(x.phase_labels, y.phase_labels);
  EXPECT_EQ(x.phase_names, y.phase_names);
}

/// Runs `f`, which must throw InvalidInput with `part` in its message.
template <class F> void expect_invalid(F&& f, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one saying '" << part << "'";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(ArrayInput, per_phase_and_interleaved_arrays_give_the_same_mesh) {
  const TwoSpheres s(20);
  const NodeMesh separate = mesh_scene(s.scene(), quick());
  const NodeMesh interleaved = mesh_scene(scene_from_interleaved_values(s.grid, s.interleaved(), 3), quick());
  expect_same_mesh(separate, interleaved);
  EXPECT_EQ(separate.phase_names, (std::vector<std::string>{"phase0", "phase1", "phase2"}));
}

TEST(ArrayInput, phase_values_mesh_the_two_spheres_with_their_volumes) {
  const TwoSpheres s(32);
  PhaseValuesOptions o;
  o.names = {"matrix", "a", "b"};
  o.labels = {10, 20, 30};
  const NodeMesh m = mesh_scene(s.scene(o), quick());
  EXPECT_TRUE(validate(m).ok());
  EXPECT_EQ(m.phase_labels, (std::vector<int32_t>{10, 20, 30}));
  EXPECT_EQ(phase_of_label(m, 20), 1);
  EXPECT_EQ(phase_of_label(m, 15), -1);

  // Three surfaces (matrix-a, matrix-b, a-b) that together are the whole mesh.
  const std::vector<Surface> found = surfaces(m);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0].pair, (PhasePair{0, 1}));
  EXPECT_EQ(found[2].pair, (PhasePair{1, 2}));
  size_t triangles = 0;
  for (const Surface& f : found) {
    triangles += f.triangles.size();
    EXPECT_GT(f.area, 0);
  }
  EXPECT_EQ(triangles, m.num_triangles());

  // Each sphere minus its half of the lens: cap volume pi h^2 (3r - h) / 3, h = r - d/2.
  const double d = (kCentreB - kCentreA).norm(), h = kRadius - d / 2;
  const double expected = 4.0 / 3 * std::numbers::pi * std::pow(kRadius, 3) - std::numbers::pi * h * h * (3 * kRadius - h) / 3;
  const auto volumes = phase_volumes(m);
  ASSERT_EQ(volumes.size(), 3u);
  ASSERT_TRUE(volumes[0] && volumes[1] && volumes[2]);
  EXPECT_NEAR(*volumes[1], expected, 0.03 * expected);
  EXPECT_NEAR(*volumes[2], expected, 0.03 * expected);
  // The matrix surrounds both and fills the rest of the unit box.
  EXPECT_NEAR(*volumes[0], 1 - *volumes[1] - *volumes[2], 1e-12);

  // A sphere cut by the box: its surface ends there, so neither volume is known.
  std::vector<double> ball, rest;
  for (int64_t n = 0; n < s.grid.node_count(); ++n) {
    const auto nodes = s.grid.nodes();
    const Vec3 x = s.grid.node_position(n % nodes[0], n / nodes[0] % nodes[1], n / (nodes[0] * nodes[1]));
    ball.push_back(kRadius - (x - Vec3(0, 0.5, 0.5)).norm());
    rest.push_back(-ball.back());
  }
  const auto cut = phase_volumes(create_mesh(scene_from_phase_values(s.grid, {rest, ball})));
  ASSERT_EQ(cut.size(), 2u);
  EXPECT_FALSE(cut[0] || cut[1]);

  // One closed triple curve, the circle where the spheres cross: radius sqrt(r^2 - (d/2)^2).
  const Junctions j = find_junctions(m);
  ASSERT_EQ(j.curves.size(), 1u);
  EXPECT_TRUE(j.curves[0].closed());
  EXPECT_EQ(j.curves[0].phases, (std::vector<int32_t>{0, 1, 2}));
  EXPECT_EQ(curve_points(m, j.curves[0]).size(), j.curves[0].nodes.size());
  const double circle = 2 * std::numbers::pi * std::sqrt(kRadius * kRadius - d * d / 4);
  EXPECT_NEAR(curve_length(m, j.curves[0]), circle, 0.03 * circle);
}

TEST(Meshing, closed_mesh_phases_fill_the_box) {
  const TwoSpheres s(16);
  MeshOptions o = quick(3);
  o.close = true;
  const NodeMesh m = mesh_scene(s.scene(), o);
  ASSERT_EQ(m.phase_names.size(), 4u);
  EXPECT_EQ(m.phase_names[3], "exterior");
  const auto volumes = phase_volumes(m);
  double inside = 0;
  for (int p = 0; p < 3; ++p) {
    ASSERT_TRUE(volumes[size_t(p)]);
    inside += *volumes[size_t(p)];
  }
  EXPECT_NEAR(inside, 1.0, 1e-9); // the unit box
  EXPECT_FALSE(volumes[3]);       // the exterior: all space outside the box
}

TEST(Meshing, a_mesher_makes_mesh_scenes_meshes_step_after_step_and_checks_its_options_first) {
  Mesher mesher(quick(3));
  for (int cells : {12, 16, 20}) { // a series of scenes, as a simulation's steps
    const TwoSpheres s(cells);
    const NodeMesh ours = mesher.mesh(s.scene());
    expect_same_mesh(ours, mesh_scene(s.scene(), quick(3)));
    EXPECT_TRUE(validate(ours).ok());
  }
  EXPECT_EQ(mesher.meshes_made(), 3u);
  MeshOptions typo = quick(3);
  typo.pipeline = "smooth,flp";
  expect_invalid([&] { Mesher bad(typo); }, "unknown pass 'flp'");
  MeshOptions negative = quick(-1);
  expect_invalid([&] { Mesher bad(negative); }, "iterations");
}

TEST(Meshing, options_reach_create_and_improve) {
  const TwoSpheres s(16);
  MeshOptions o = quick(0);
  const NodeMesh initial = create_mesh(s.scene(), o);
  EXPECT_TRUE(validate(initial).ok());
  expect_same_mesh(mesh_scene(s.scene(), o), initial); // 0 iterations: create only
  o.grid = std::array{24, 24, 24};
  EXPECT_GT(create_mesh(s.scene(), o).num_triangles(), initial.num_triangles() * 3 / 2);

  NodeMesh improved = initial;
  o.iterations = 4;
  o.pipeline = "smooth,flip";
  EXPECT_EQ(improve_mesh(improved, s.scene().field, o), 4);
  EXPECT_EQ(improved.num_nodes(), initial.num_nodes());
  EXPECT_NE(improved.points, initial.points);
  EXPECT_GT(compute_stats(improved).min_quality, compute_stats(initial).min_quality);
  // The pipeline's passes come from the registry given: one the built-ins lack
  // runs, and does what it says (pins node 0, which smoothing would move).
  PassRegistry passes = builtin_registry();
  PassInfo pin;
  pin.name = "pin_first";
  pin.summary = "keeps node 0 where it is";
  pin.moves_nodes = true;
  struct Pin : Pass {
    void run(PassContext& c) override { c.displacement()[0] = Vec3::Zero(); }
  };
  pin.make = [](const ParamValues&) { return std::make_unique<Pin>(); };
  passes.add(pin);
  o.passes = &passes;
  o.pipeline = "smooth,pin_first,flip";
  NodeMesh pinned = initial;
  EXPECT_EQ(improve_mesh(pinned, s.scene().field, o), 4);
  EXPECT_EQ(pinned.points[0], initial.points[0]);
  EXPECT_NE(improved.points[0], initial.points[0]);
  o.passes = nullptr; // the built-ins alone do not know it
  EXPECT_THROW(improve_mesh(pinned, s.scene().field, o), InvalidInput);
}

TEST(Meshing, threads_do_not_change_the_mesh) {
  const TwoSpheres s(16);
  MeshOptions o = quick(3);
  o.threads = 1;
  const NodeMesh one = mesh_scene(s.scene(), o);
  o.threads = 2;
  expect_same_mesh(one, mesh_scene(s.scene(), o));
}

class ArrayFiles : public test::ScratchDir {};

TEST_F(ArrayFiles, labels_mesh_like_the_same_label_volume_file) {
  // 20 x 18 x 16 voxels of 0.5 at (1, 2, 3): a sphere of label 7 cut by a slab of label 3.
  GridSpec grid;
  grid.cells = {19, 17, 15};
  grid.domain.min = Vec3(1, 2, 3);
  grid.domain.max = grid.domain.min + 0.5 * Vec3(19, 17, 15);
  std::vector<int32_t> labels;
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 18; ++j)
      for (int i = 0; i < 20; ++i)
        labels.push_back(i > 13 ? 3 : (Vec3(i, j, k) - Vec3(9.3, 8.6, 7.8)).norm() < 6 ? 7 : 0);
  const std::string file = test::write_nrrd(
      "api_labels.nrrd", "type: int\ndimension: 3\nsizes: 20 18 16\nspace: left-posterior-superior\n"
                         "space directions: (0.5,0,0) (0,0.5,0) (0,0,0.5)\nspace origin: (1,2,3)\n", labels);
  for (bool signed_distance : {false, true}) {
    InputOptions o;
    o.label_function = signed_distance ? LabelFunction::signed_distance : LabelFunction::smoothed_indicator;
    const NodeMesh from_array = create_mesh(scene_from_labels(grid, labels, o));
    expect_same_mesh(from_array, create_mesh(load_input(file, o)));
    EXPECT_EQ(from_array.phase_labels, (std::vector<int32_t>{0, 3, 7}));
    EXPECT_EQ(from_array.phase_names[0], "background");
  }
  InputOptions merged;
  merged.merge_labels = {{3, 7}};
  EXPECT_EQ(create_mesh(scene_from_labels(grid, labels, merged)).phase_labels, (std::vector<int32_t>{0, 3}));
  std::filesystem::remove(file);
}

TEST_F(ArrayFiles, points_mesh_like_the_same_point_file) {
  std::vector<Vec3> points;
  std::vector<int32_t> labels;
  std::ofstream file(path("cloud.xyz"));
  for (int i = 0; i < 400; ++i) {
    const Vec3 p(std::fmod(i * 0.618034, 1.0), std::fmod(i * 0.414214, 1.0), std::fmod(i * 0.732051, 1.0));
    points.push_back(p);
    labels.push_back(p.x() + 0.3 * p.y() < 0.6 ? 4 : p.z() < 0.5 ? 8 : 9);
    char line[96];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %d\n", p.x(), p.y(), p.z(), labels.back());
    file << line;
  }
  file.close();
  MeshOptions o;
  o.grid = std::array{24, 24, 24};
  const NodeMesh from_array = create_mesh(scene_from_points(points, labels), o);
  expect_same_mesh(from_array, create_mesh(load_input(path("cloud.xyz")), o));
  EXPECT_EQ(from_array.phase_labels, (std::vector<int32_t>{4, 8, 9}));
}

TEST(ArrayInput, mistakes_are_invalid_input_naming_the_problem) {
  TwoSpheres s(8);
  expect_invalid([&] { scene_from_phase_values(s.grid, {s.a}); }, "phase values: has 1 phase(s); meshing needs 2 or more");
  const std::vector<double> short_array(10, 0.0);
  expect_invalid([&] { scene_from_phase_values(s.grid, {s.a, short_array}); },
                 "phase values: phase 1 holds 10 values; the grid's 729 nodes need 729");
  expect_invalid([&] { scene_from_interleaved_values(s.grid, s.a, 3); }, "the array holds 729 values; the grid's 729 nodes need 2187");
  s.b[s.grid.node_index(2, 3, 4)] = std::nan("");
  PhaseValuesOptions o;
  o.source = "step 12";
  expect_invalid([&] { scene_from_phase_values(s.grid, {s.a, s.b}, o); }, "step 12: phase 1 at node (2, 3, 4): value nan is not a finite float");
  o.labels = {5, 5};
  expect_invalid([&] { scene_from_phase_values(s.grid, {s.a, s.a}, o); }, "step 12: phase labels must be strictly increasing");
  o.labels = {};
  o.names = {"one"};
  expect_invalid([&] { scene_from_phase_values(s.grid, {s.a, s.a}, o); }, "1 phase names for 2 phases");
  GridSpec flat = s.grid;
  flat.cells[2] = 0;
  expect_invalid([&] { scene_from_labels(flat, std::vector<int32_t>(81, 1)); }, "labels: grid: 0 cells along axis z");
  expect_invalid([&] { scene_from_labels(s.grid, std::vector<int32_t>(729, 1)); }, "labels: has 1 phase(s) after the label options");
  InputOptions bad;
  bad.smoothing = 9;
  expect_invalid([&] { scene_from_labels(s.grid, std::vector<int32_t>(729, 1), bad); }, "--smoothing: must be in (0, 8]");
  const std::vector<Vec3> points{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  expect_invalid([&] { scene_from_points(points, std::vector<int32_t>{1}); }, "points: 2 points but 1 labels");
  expect_invalid([&] { scene_from_points(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, NAN, 1)}, std::vector<int32_t>{1, 2}); },
                 "points: point 1: coordinates must be finite");
}

/// f() throws InvalidOption naming `option`, its problem saying `problem`.
template <class F> void expect_invalid_option(F&& f, const std::string& option, const std::string& problem) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one on " << option;
  } catch (const InvalidOption& e) {
    EXPECT_EQ(e.option(), option) << e.what();
    EXPECT_NE(e.problem().find(problem), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()), option + ": " + e.problem());
  }
}

TEST(Meshing, mistakes_are_invalid_input_naming_the_option) {
  const TwoSpheres s(8);
  MeshOptions o;
  o.grid = std::array{8, 0, 8};
  expect_invalid_option([&] { create_mesh(s.scene(), o); }, "grid", "must be between 1 and 4096 cells per axis, got 0");
  o = {};
  o.threads = -1;
  expect_invalid_option([&] { mesh_scene(s.scene(), o); }, "threads", "must be 0 (all cores) or more");
  o = {};
  o.top_k = 17;
  expect_invalid_option([&] { mesh_scene(s.scene(), o); }, "top_k", "must be between 1 and 16, got 17");
  o = {};
  o.snap = 0.6;
  expect_invalid_option([&] { create_mesh(s.scene(), o); }, "snap", "must be between 0 and 0.5");
  o = {};
  o.iterations = -1;
  NodeMesh created = create_mesh(s.scene());
  expect_invalid_option([&] { improve_mesh(created, s.scene().field, o); }, "iterations", "must be 0 or more");
  o = {};
  o.pipeline = "smooth,wiggle";
  NodeMesh m = create_mesh(s.scene());
  expect_invalid([&] { improve_mesh(m, s.scene().field, o); }, "wiggle");
  expect_invalid([&] { create_mesh(Scene{s.grid, nullptr}); }, "scene: no phase field");
}

} // namespace
} // namespace vm
