/// @file test_project.cpp
/// Newton steps onto surfaces, triple curves and quadruple points (eq. 4 and
/// the least-squares step, improve/project.hpp).

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/project.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace {

using namespace vm;

TEST(Project, step_lands_on_a_plane_and_a_sphere_interface) {
  Scene s = parse_scene(R"({"phases": [{"kind": "constant", "value": 0},
      {"kind": "plane", "point": [0.5, 0.5, 0.5], "normal": [0, 0, 1]},
      {"kind": "sphere", "center": [0.5, 0.5, 0.5], "radius": 0.25}]})",
                        "inline");
  std::array<int32_t, 2> pair01{0, 1}, pair02{0, 2};
  Vec3 x(0.3, 0.6, 0.55);
  x += projection_step(*s.field, x, pair01);
  EXPECT_NEAR(x.z(), 0.5, 1e-12); // linear: exact in one step
  Vec3 y(0.5, 0.5, 0.9);
  for (int i = 0; i < 5; ++i) y += projection_step(*s.field, y, pair02);
  EXPECT_NEAR((y - Vec3(0.5, 0.5, 0.5)).norm(), 0.25, 1e-12);
  std::array<int32_t, 3> triple{0, 1, 2};
  Vec3 z(0.6, 0.5, 0.6);
  for (int i = 0; i < 30; ++i) z += projection_step(*s.field, z, triple);
  EXPECT_NEAR(z.z(), 0.5, 1e-9); // on the circle where the plane cuts the sphere
  EXPECT_NEAR((z - Vec3(0.5, 0.5, 0.5)).norm(), 0.25, 1e-9);
}

// A node holds at most kMaxPhasesAtNode phases; a caller asking for more gets
// an error naming the limit, not a write past the step's scratch arrays.
TEST(Project, more_phases_than_a_node_holds_are_refused) {
  std::string phases;
  for (size_t i = 0; i <= kMaxPhasesAtNode; ++i)
    phases += (i ? "," : "") + std::string(R"({"kind": "sphere", "center": [0.5, 0.5, 0.5], "radius": )") +
              std::to_string(0.1 + 0.01 * double(i)) + "}";
  Scene s = parse_scene("{\"phases\": [" + phases + "]}", "inline");
  std::array<int32_t, kMaxPhasesAtNode + 1> all;
  for (size_t i = 0; i < all.size(); ++i) all[i] = int32_t(i);
  EXPECT_THROW(projection_step(*s.field, Vec3(0.5, 0.5, 0.7), all), InvalidInput);
  EXPECT_NO_THROW(projection_step(*s.field, Vec3(0.5, 0.5, 0.7), std::span(all).first(kMaxPhasesAtNode)));
}

// Four Voronoi seeds almost in one plane: their quadruple point is well defined
// (the four distances equal), but the six pairs' gradient differences nearly
// share a plane, and eq. 4's mean of the pairs' steps crawls along its normal.
// The least-squares step (ProjectParams::least_squares_from) converges at
// Newton's rate; for two phases it is eq. 4's own step.
TEST(Project, least_squares_reaches_a_quadruple_point_that_eq4_approaches_slowly) {
  Scene s = parse_scene(R"({"phases": [{"kind": "seeds", "points": [[0.2, 0.2, 0.5]]},
      {"kind": "seeds", "points": [[0.8, 0.2, 0.5]]}, {"kind": "seeds", "points": [[0.2, 0.8, 0.5]]},
      {"kind": "seeds", "points": [[0.8, 0.8, 0.56]]}]})",
                        "inline");
  const std::array<int32_t, 4> all{0, 1, 2, 3};
  // The point equidistant from the four seeds: x = y = 0.5 by symmetry, z from |p - s0| = |p - s3|.
  const double z = (0.56 * 0.56 - 0.5 * 0.5) / (2 * (0.56 - 0.5));
  const Vec3 exact(0.5, 0.5, z);
  auto iterate = [&](const ProjectParams& params, int steps) {
    Vec3 x = exact + Vec3(0.02, -0.01, 0.05);
    for (int i = 0; i < steps; ++i) x += projection_step(*s.field, x, all, params);
    return (x - exact).norm();
  };
  ProjectParams least_squares;
  least_squares.least_squares_from = 4;
  EXPECT_LT(iterate(least_squares, 6), 1e-9);
  EXPECT_GT(iterate(ProjectParams{}, 60), 0.02); // eq. 4: most of the 0.055 still to go after sixty
  // Two phases: one pair, and the same step either way.
  const std::array<int32_t, 2> pair{0, 3};
  least_squares.least_squares_from = 2;
  const Vec3 x(0.4, 0.45, 0.7);
  EXPECT_LT((projection_step(*s.field, x, pair, least_squares) - projection_step(*s.field, x, pair)).norm(), 1e-15);
}

// A mesh of the plane z = 0.5 projected onto the plane z = 0.9: 0.4 off, about
// six edges at grid 16. Each node's step is cut to its mean edge length, along
// the uncut step; with max_step 0 (the paper's) it is the whole 0.4.
TEST(Project, steps_are_cut_to_the_mean_edge_length_at_the_node) {
  const auto plane_at = [](double z) {
    return parse_scene(R"({"phases": [{"kind": "constant", "value": 0},
        {"kind": "plane", "point": [0.5, 0.5, )" + std::to_string(z) + R"(], "normal": [0, 0, 1]}]})",
                       "inline");
  };
  const InterfaceMesh mesh = test::initial_mesh(plane_at(0.5));
  const Scene far = plane_at(0.9);
  ProjectParams uncut;
  uncut.max_step = 0;
  std::vector<Vec3> cut_steps(mesh.num_nodes(), Vec3::Zero()), whole_steps = cut_steps;
  add_projection(mesh, *far.field, ProjectParams{}, cut_steps);
  add_projection(mesh, *far.field, uncut, whole_steps);
  ASSERT_GT(mesh.num_nodes(), 100u);
  for (size_t n = 0; n < mesh.num_nodes(); ++n) {
    const Vec3& x = mesh.positions()[n];
    EXPECT_NEAR(whole_steps[n].z(), 0.9 - x.z(), 1e-12);
    const double edge = mean_edge_length_at(mesh, int32_t(n));
    ASSERT_LT(edge, 0.2); // so the cut is real
    EXPECT_NEAR(cut_steps[n].norm(), edge, 1e-12);
    EXPECT_LT((cut_steps[n].normalized() - whole_steps[n].normalized()).norm(), 1e-12);
  }
}

} // namespace
