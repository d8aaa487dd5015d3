/// @file test_smooth.cpp
/// Smoothing forces on closed triple curves of few nodes (improve/smooth.hpp).

#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include "fixtures.hpp"
#include "mesh_checks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {

using namespace vm;

/// A ball of radius 0.3 at the origin cut by the plane z = 0 between phases
/// "above" (0) and "below" (1): their triple curve is the ball's equator, here
/// a loop of three nodes at the given angles (degrees), with the ball's caps
/// as fans to its poles and the plane out to the box.
struct EquatorLoop {
  Scene scene;
  InterfaceMesh mesh;
  std::array<int32_t, 3> loop;
};

EquatorLoop equator_loop(const std::array<double, 3>& degrees) {
  Scene scene = parse_scene(R"({"domain": {"min": [-1, -1, -1], "max": [1, 1, 1]}, "grid": 8, "phases": [
      {"name": "above", "kind": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]},
      {"name": "below", "kind": "plane", "point": [0, 0, 0], "normal": [0, 0, -1]},
      {"name": "ball", "kind": "sphere", "center": [0, 0, 0], "radius": 0.3}]})",
                            "equator");
  test::Builder b(scene.grid.domain);
  std::array<Vec3, 3> at;
  for (size_t i = 0; i < 3; ++i) {
    const double t = degrees[i] * std::numbers::pi / 180;
    at[i] = Vec3(0.3 * std::cos(t), 0.3 * std::sin(t), 0);
  }
  const Vec3 top(0, 0, 0.3), bottom(0, 0, -0.3);
  const std::array<Vec3, 4> corner = {Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0), Vec3(-1, -1, 0)};
  // Each cap's triangles face away from the inside of the tetrahedron the
  // cap and the loop bound.
  for (const auto& [pole, outside] : {std::pair{top, 0}, std::pair{bottom, 1}}) {
    const Vec3 inside = (at[0] + at[1] + at[2] + pole) / 4;
    for (size_t i = 0; i < 3; ++i) {
      const Vec3 centroid = (at[i] + at[(i + 1) % 3] + pole) / 3;
      b.tri_towards(at[i], at[(i + 1) % 3], pole, 2 * centroid - inside, 2, outside);
    }
  }
  // The plane outside the loop (at[0] near 0 degrees, at[2] near 180).
  const Vec3 up(0, 0, 1);
  for (const auto& [p, q, r] : {std::array{at[0], corner[0], corner[1]}, std::array{at[0], corner[1], at[1]},
                                 std::array{at[1], corner[1], corner[2]}, std::array{at[1], corner[2], at[2]},
                                 std::array{at[2], corner[2], corner[3]}, std::array{at[2], corner[3], corner[0]},
                                 std::array{at[2], corner[0], at[0]}})
    b.tri_towards(p, q, r, up, 1, 0);
  std::array<int32_t, 3> loop{b.node(at[0]), b.node(at[1]), b.node(at[2])};
  NodeMesh m = b.mesh;
  m.phase_names = {"above", "below", "ball"};
  return {std::move(scene), InterfaceMesh::from_node_mesh(m), loop};
}

double angle_of(const Vec3& p) { return std::atan2(p.y(), p.x()) * 180 / std::numbers::pi; }

// Kept along the curve, the Laplacian moves nodes down the sum of squared
// chords, which on a loop of three is smallest with the three together: on a
// 64^3 label volume a loop's nodes sat 0.10, 0.57 and 0.60 apart. On such a
// loop each node moves instead toward the farther of the other two, by a
// quarter of how much farther.
TEST(Smooth, nodes_of_a_loop_of_three_move_apart_not_together) {
  const EquatorLoop e = equator_loop({0, 40, 180});
  std::vector<Vec3> delta(e.mesh.num_nodes(), Vec3::Zero());
  add_smoothing_forces(e.mesh, *e.scene.field, SmoothParams{}, delta);
  const auto& pos = e.mesh.positions();
  auto chord = [&](int i, int j) { return (pos[size_t(e.loop[size_t(i)])] - pos[size_t(e.loop[size_t(j)])]).norm(); };
  // The node at 0 degrees moves away from the one at 40 (down y, its tangent),
  // the one at 40 away from it (up the angle), by a quarter of the difference.
  const Vec3 first = delta[size_t(e.loop[0])], second = delta[size_t(e.loop[1])];
  EXPECT_NEAR(first.y(), -0.25 * (chord(0, 2) - chord(0, 1)), 1e-12);
  EXPECT_NEAR(first.x(), 0, 1e-12);
  const Vec3 tangent_at_40(-std::sin(40 * std::numbers::pi / 180), std::cos(40 * std::numbers::pi / 180), 0);
  EXPECT_NEAR(second.dot(tangent_at_40), 0.25 * (chord(1, 2) - chord(1, 0)), 1e-12);
  EXPECT_NEAR(second.norm(), std::abs(second.dot(tangent_at_40)), 1e-12);
  for (const Vec3& d : {first, second}) EXPECT_EQ(d.z(), 0);
}

// Iterated with projection, clamping and flips, the three spread round the
// loop and stay on it, in a valid mesh whose triangles face as their phases do.
TEST(Smooth, a_loop_of_three_ends_evenly_spread_on_its_curve) {
  EquatorLoop e = equator_loop({0, 25, 180});
  const Pipeline pipeline = Pipeline::parse("smooth,project,clamp,flip", builtin_registry());
  pipeline.run(e.mesh, e.scene.field.get(), test::iterations(40));
  const NodeMesh after = e.mesh.to_node_mesh();
  EXPECT_TRUE(validate(after).ok()) << validate(after).summary();
  EXPECT_EQ(test::inverted_triangles(after, *e.scene.field), 0u);
  std::array<double, 3> angles;
  for (size_t i = 0; i < 3; ++i) {
    const Vec3& p = e.mesh.positions()[size_t(e.loop[i])];
    EXPECT_NEAR(p.norm(), 0.3, 1e-6);
    EXPECT_NEAR(p.z(), 0, 1e-6);
    angles[i] = angle_of(p);
  }
  std::sort(angles.begin(), angles.end());
  const std::array<double, 3> gaps = {angles[1] - angles[0], angles[2] - angles[1], 360 - (angles[2] - angles[0])};
  for (double gap : gaps) EXPECT_NEAR(gap, 120, 5);
}

} // namespace
