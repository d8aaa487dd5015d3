/// @file test_polish.cpp
/// The polish pass (improve/polish.hpp): what it moves, where to, and that its
/// moves raise the triangles around them and keep nodes on their interfaces.

#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/polish.hpp"
#include "voronoimesh/improve/project.hpp"
#include "voronoimesh/improve/registry.hpp"
#include "voronoimesh/improve/smooth.hpp"
#include "voronoimesh/mesh/triangle_quality.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace {

using namespace vm;

/// The smallest quality of the triangles at node n with the nodes at `p`.
double worst_at(const InterfaceMesh& mesh, const std::vector<Vec3>& p, int32_t n) {
  double worst = 1;
  mesh.for_each_triangle_at(n, [&](int32_t a, int32_t b) {
    worst = std::min(worst, triangle_quality(p[size_t(n)], p[size_t(a)], p[size_t(b)]));
  });
  return worst;
}

/// Checks what add_polish_moves() promises on `mesh`; the nodes after its moves.
std::vector<Vec3> polish_and_check(const InterfaceMesh& mesh, const PhaseField& field) {
  std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
  const size_t count = add_polish_moves(mesh, field, PolishParams{}, delta);
  std::vector<Vec3> after = mesh.positions();
  std::vector<int32_t> moved;
  for (size_t n = 0; n < after.size(); ++n)
    if (!delta[n].isZero(0)) after[n] += delta[n], moved.push_back(int32_t(n));
  EXPECT_EQ(moved.size(), count);
  for (int32_t n : moved) {
    // Surface and curve nodes only (a box face counts as one more constraint),
    // on the box faces they were on, none next to another.
    const int order = junction_order(mesh, n);
    EXPECT_TRUE(order == 2 || order == 3) << "node " << n;
    for (int a = 0; a < 3; ++a)
      if (mesh.box_faces()[size_t(n)] >> (2 * a) & 3u) EXPECT_EQ(delta[size_t(n)][a], 0) << "node " << n;
    const Box& box = mesh.domain();
    EXPECT_TRUE((after[size_t(n)].array() >= box.min.array()).all() && (after[size_t(n)].array() <= box.max.array()).all())
        << "node " << n << " left the box";
    for (int32_t m : mesh.neighbours(n)) EXPECT_TRUE(delta[size_t(m)].isZero(0)) << n << " and " << m;
    // Better around it (its neighbours stay), and no farther from its surface
    // or curve than it was (eq. 4's step there, a first-order distance).
    EXPECT_GT(worst_at(mesh, after, n), worst_at(mesh, mesh.positions(), n)) << "node " << n;
    const double off_before = node_projection_step(mesh, field, n, mesh.positions()[size_t(n)]).norm();
    EXPECT_LE(node_projection_step(mesh, field, n, after[size_t(n)]).norm(), std::max(1e-12, off_before))
        << "node " << n;
  }
  return after;
}

/// The nodes at other places in `after` than in the mesh.
std::vector<int32_t> moved_nodes(const InterfaceMesh& mesh, const std::vector<Vec3>& after) {
  std::vector<int32_t> moved;
  for (size_t n = 0; n < after.size(); ++n)
    if (after[n] != mesh.positions()[n]) moved.push_back(int32_t(n));
  return moved;
}

// A flat interface, z = 0.5, in 4 x 4 cells whose outer nodes lie on the box:
// the centre node pushed off-centre leaves thin triangles, and polishing
// moves a node of them within the plane to where the thin ones are fatter.
TEST(Polish, moves_a_surface_node_within_its_surface_to_raise_its_triangles) {
  const Scene scene = parse_scene(R"({"domain": {"min": [0.2, 0.2, 0], "max": [0.8, 0.8, 1]},
      "phases": [{"kind": "constant", "value": 0},
                 {"kind": "plane", "point": [0.5, 0.5, 0.5], "normal": [0, 0, 1]}]})",
                                  "inline");
  test::Builder b(scene.grid.domain);
  b.rect(Vec3(0.2, 0.2, 0.5), Vec3(0.6, 0, 0), Vec3(0, 0.6, 0), 4, 0, 1);
  NodeMesh m = b.mesh;
  const auto centre = size_t(std::find(m.points.begin(), m.points.end(), Vec3(0.5, 0.5, 0.5)) - m.points.begin());
  ASSERT_LT(centre, m.points.size());
  m.points[centre] = Vec3(0.56, 0.53, 0.5);
  const InterfaceMesh mesh = InterfaceMesh::from_node_mesh(m);
  const std::vector<double>& quality = mesh.qualities();
  const double worst_before = *std::min_element(quality.begin(), quality.end());
  ASSERT_LT(worst_before, PolishParams{}.below);

  const std::vector<Vec3> after = polish_and_check(mesh, *scene.field);
  const std::vector<int32_t> moved = moved_nodes(mesh, after);
  ASSERT_FALSE(moved.empty());
  for (int32_t n : moved) EXPECT_NEAR(after[size_t(n)].z(), 0.5, 1e-15) << "node " << n; // a move in the plane
}

// On a created mesh of seven Voronoi cells (nodes where create snapped them,
// thin triangles at every junction), moved curve nodes stay on their curves
// (surface nodes on the box along the box), and quadruple points stay.
TEST(Polish, moves_curve_nodes_along_their_curves_and_box_nodes_along_the_box) {
  const Scene scene = test::example_scene("voronoi7.json", 16);
  const InterfaceMesh mesh = test::initial_mesh(scene);
  const std::vector<int32_t> moved = moved_nodes(mesh, polish_and_check(mesh, *scene.field));
  const auto curve_nodes = std::count_if(moved.begin(), moved.end(), [&](int32_t n) { return junction_order(mesh, n) == 3; });
  EXPECT_GT(curve_nodes, 0);
  EXPECT_LT(size_t(curve_nodes), moved.size()); // surface nodes too
  EXPECT_TRUE(std::any_of(moved.begin(), moved.end(), [&](int32_t n) { return mesh.box_faces()[size_t(n)] != 0; }));
}

// Polishing (from iteration 6, the scenes' default) leaves the worst triangle
// of the 30 cells no worse than the same run without it, and better.
TEST(Polish, raises_the_worst_triangle_of_thirty_cells) {
  const Scene scene = test::example_scene("voronoi30.json", 32);
  auto worst_after = [&](const std::string& pipeline) {
    InterfaceMesh mesh = test::initial_mesh(scene);
    Pipeline::parse(pipeline, builtin_registry()).run(mesh, scene.field.get(), test::iterations(12));
    const std::vector<double>& quality = mesh.qualities();
    return *std::min_element(quality.begin(), quality.end());
  };
  const std::string with = kScenePipeline;
  const std::string without = with.substr(0, with.rfind(",polish"));
  ASSERT_NE(with, without);
  EXPECT_GT(worst_after(with), worst_after(without));
}

} // namespace
