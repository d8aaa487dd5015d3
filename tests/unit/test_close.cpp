// Tests of closed domains (CreateParams::close, fields/outside_phase.hpp): the box faces
// become surfaces against an "exterior" phase, every phase is a closed volume,
// and improvement keeps box nodes on their faces, edges and corners.

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/array_input.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/smooth.hpp"
#include "voronoimesh/io/ply.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/run/meshing.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>

namespace {

using namespace vm;

Scene example(const std::string& name, int grid) { return test::example_scene(name, grid); }

NodeMesh closed_mesh(const Scene& scene) {
  CreateParams params;
  params.close = true;
  return test::created_mesh(scene, params, with_outside_phase(scene.field, scene.grid.domain).get());
}

/// Volume enclosed by each phase (divergence theorem over its triangles, with the
/// normal of pair (a, b) pointing out of a and into b).
std::map<int32_t, double> phase_volumes(const NodeMesh& m) {
  std::map<int32_t, double> v;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const auto& tri = m.triangles[t];
    const double six = m.points[size_t(tri[0])].dot(m.points[size_t(tri[1])].cross(m.points[size_t(tri[2])]));
    v[m.pairs[t][0]] += six / 6;
    v[m.pairs[t][1]] -= six / 6;
  }
  return v;
}

/// Distance of p from the surface of `box`.
double off_box(const Box& box, const Vec3& p) {
  double d = INFINITY;
  for (int a = 0; a < 3; ++a) d = std::min({d, std::abs(p[a] - box.min[a]), std::abs(p[a] - box.max[a])});
  return d;
}

void expect_closed_partition(const NodeMesh& m, int field_phases) {
  ASSERT_TRUE(validate(m).ok()) << validate(m).summary();
  // Every edge is shared by at least two triangles: nothing is open, not even on the box.
  std::map<std::pair<int32_t, int32_t>, int> edges;
  for (const auto& t : m.triangles)
    for (int c = 0; c < 3; ++c) ++edges[{std::min(t[c], t[(c + 1) % 3]), std::max(t[c], t[(c + 1) % 3])}];
  size_t open = 0;
  for (const auto& [e, n] : edges) open += n < 2;
  EXPECT_EQ(open, 0u);
  // The phases fill the box: their volumes are positive and add up to it, and the
  // outside phase encloses minus the box.
  const Vec3 size = m.domain.max - m.domain.min;
  const double box = size.prod();
  const auto volumes = phase_volumes(m);
  double inside = 0;
  for (const auto& [phase, volume] : volumes)
    if (phase != field_phases) {
      EXPECT_GT(volume, 0) << "phase " << phase;
      inside += volume;
    }
  EXPECT_NEAR(inside, box, 1e-9 * box);
  EXPECT_NEAR(volumes.at(field_phases), -box, 1e-9 * box);
  // Outside triangles lie on the box.
  for (size_t t = 0; t < m.num_triangles(); ++t)
    if (m.pairs[t][1] == field_phases)
      for (int32_t v : m.triangles[t]) EXPECT_LT(off_box(m.domain, m.points[size_t(v)]), 1e-12);
}

TEST(Close, created_phases_are_closed_volumes_that_fill_the_box) {
  for (const char* name : {"four_spheres.json", "voronoi7.json", "split_sphere.json"}) {
    SCOPED_TRACE(name);
    const Scene scene = example(name, 24);
    const NodeMesh m = closed_mesh(scene);
    expect_closed_partition(m, scene.field->num_phases());
    EXPECT_TRUE(find_self_intersections(m).ok());
  }
}

TEST(Close, improvement_keeps_box_nodes_on_their_faces_edges_and_corners) {
  const Scene scene = example("voronoi7.json", 24);
  const NodeMesh created = closed_mesh(scene);
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(created);
  ASSERT_EQ(mesh.outside_phase(), scene.field->num_phases());
  const std::vector<uint8_t> box_faces = mesh.box_faces();
  const std::vector<Vec3> before = mesh.positions();
  const auto field = with_outside_phase(scene.field, scene.grid.domain);
  RunOptions run;
  run.iterations = 20;
  // Without collapses node ids survive, so every node can be followed.
  Pipeline::parse("smooth,project,clamp,flip:collapse_below=0", builtin_registry()).run(mesh, field.get(), run);
  const NodeMesh m = mesh.to_node_mesh();
  expect_closed_partition(m, scene.field->num_phases());
  EXPECT_TRUE(find_self_intersections(m).ok());
  ASSERT_EQ(m.num_nodes(), created.num_nodes());
  size_t moved = 0;
  for (size_t v = 0; v < m.num_nodes(); ++v) moved += m.points[v] != before[v];
  EXPECT_GT(moved, m.num_nodes() / 2);
  for (size_t v = 0; v < m.num_nodes(); ++v)
      for (int a = 0; a < 3; ++a)
        if (box_faces[v] >> (2 * a) & 3) EXPECT_EQ(m.points[v][a], before[v][a]) << "node " << v << " axis " << a;
  // The eight corners are still nodes.
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner(c & 1 ? m.domain.max.x() : m.domain.min.x(), c & 2 ? m.domain.max.y() : m.domain.min.y(),
                      c & 4 ? m.domain.max.z() : m.domain.min.z());
    bool found = false;
    for (const Vec3& p : m.points) found = found || p == corner;
    EXPECT_TRUE(found) << "corner " << c;
  }
}

// A node where an interface meets a box face has three phases with the outside
// one, and one box face: order 4 by its phases and faces, as a quadruple point,
// which forces leave where it is. Its constraints are those of a curve (the
// outside phase's surfaces are the box faces), and it is smoothed along it as
// in a mesh that is not closed: frozen, voronoi7's nodes there held a triangle
// of q 0.383 at the box (0.649 now).
TEST(Close, nodes_where_an_interface_meets_the_box_are_smoothed_along_their_curve) {
  const Scene scene = example("voronoi7.json", 24);
  const InterfaceMesh mesh = InterfaceMesh::from_node_mesh(closed_mesh(scene));
  const auto field = with_outside_phase(scene.field, scene.grid.domain);
  std::vector<Vec3> force(mesh.num_nodes(), Vec3::Zero());
  add_smoothing_forces(mesh, *field, SmoothParams{}, force);
  size_t on_box_curves = 0, pushed = 0;
  for (size_t v = 0; v < mesh.num_nodes(); ++v) {
    if (phase_count(mesh.phases()[v]) != 3 || std::popcount(unsigned(mesh.box_faces()[v])) != 1) continue;
    ++on_box_curves;
    pushed += force[v].norm() > 1e-6 * scene.grid.h();
  }
  ASSERT_GT(on_box_curves, 50u);
  EXPECT_GT(pushed, on_box_curves * 9 / 10) << pushed << " of " << on_box_curves;
}

TEST(Close, the_outside_phase_wins_exactly_outside_the_box) {
  const Scene scene = example("four_spheres.json", 16);
  const auto f = with_outside_phase(scene.field, scene.grid.domain);
  const int out = scene.field->num_phases();
  EXPECT_EQ(f->num_phases(), out + 1);
  EXPECT_EQ(f->phase_name(out), kOutsidePhaseName);
  std::vector<double> v(size_t(out + 1));
  for (const Vec3& x : {Vec3(0.5, 0.5, 0.5), Vec3(0.01, 0.3, 0.7), Vec3(-0.1, 0.5, 0.5), Vec3(1.2, 1.2, -0.3)}) {
    f->values(x, v);
    const bool outside = ((x.array() < 0) || (x.array() > 1)).any();
    const double best_inner = *std::max_element(v.begin(), v.end() - 1);
    EXPECT_EQ(v.back() > best_inner, outside) << x.transpose();
    // top_values() agrees (its values() asks the inner field's top values: a
    // nested call that once shrank the outer one's scratch to the inner phases).
    std::array<int32_t, 2> ids;
    std::array<double, 2> top;
    f->top_values(x, ids, top);
    EXPECT_EQ(ids[0] == out, outside) << x.transpose();
    EXPECT_EQ(top[0], *std::max_element(v.begin(), v.end()));
  }
  // On a face the outside phase ties the winner, and its gradient there differs
  // from the winner's by the outward normal.
  const Vec3 on_face(1.0, 0.4, 0.6);
  f->values(on_face, v);
  EXPECT_DOUBLE_EQ(v.back(), *std::max_element(v.begin(), v.end() - 1));
  const int winner = int(std::max_element(v.begin(), v.end() - 1) - v.begin());
  EXPECT_TRUE((f->gradient(out, on_face) - f->gradient(winner, on_face)).isApprox(Vec3(1, 0, 0)));
}

/// A label volume of two halves, labels `low` (x < 3) and `high`, 6 voxels a side.
Scene two_labels(int32_t low, int32_t high) {
  GridSpec grid;
  grid.cells = {5, 5, 5};
  grid.domain = {Vec3::Zero(), Vec3::Constant(5)};
  std::vector<int32_t> labels;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) labels.push_back(i < 3 ? low : high);
  return scene_from_labels(grid, labels);
}

// The outside phase takes the label above every other (so it is the last by
// label, where a mesh read back looks for it); labels at both ends of the
// 32-bit range keep it so, and the mesh reads back closed.
TEST(Close, the_outside_phase_has_the_label_above_the_largest_one_and_reads_back_last) {
  constexpr int32_t lowest = std::numeric_limits<int32_t>::min(), highest = std::numeric_limits<int32_t>::max();
  MeshOptions close;
  close.close = true;
  close.iterations = 2;
  const NodeMesh m = mesh_scene(two_labels(lowest, highest - 1), close);
  ASSERT_TRUE(validate(m).ok()) << validate(m).summary();
  EXPECT_EQ(m.outside_phase, 2);
  EXPECT_EQ(m.phase_labels, (std::vector<int32_t>{lowest, highest - 1, highest}));
  const std::string file = "close_extreme_labels.ply";
  io::write_ply(m, file);
  const NodeMesh back = io::read_ply(file);
  std::filesystem::remove(file);
  ASSERT_TRUE(validate(back).ok()) << validate(back).summary();
  EXPECT_EQ(back.outside_phase, 2);
  EXPECT_EQ(back.phase_labels, m.phase_labels);
  EXPECT_EQ(back.pairs, m.pairs);
}

// Label 2147483647 leaves no 32-bit label above it: closing is refused, naming
// the label and the way out, before any sampling. (It once wrapped round to
// -2147483648: a mesh whose outside phase came first by label, invalid when
// read back, with exit 0.)
TEST(Close, a_phase_of_the_largest_32_bit_label_cannot_be_closed_and_says_why) {
  MeshOptions close;
  close.close = true;
  const Scene scene = two_labels(7, std::numeric_limits<int32_t>::max());
  try {
    create_mesh(scene, close);
    FAIL() << "closed a domain with label 2147483647";
  } catch (const InvalidOption& e) {
    EXPECT_EQ(e.option(), "close");
    EXPECT_NE(std::string(e.what()).find("'label2147483647' has label 2147483647"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--merge-labels"), std::string::npos) << e.what();
  }
  EXPECT_THROW(with_outside_phase(scene.field, scene.grid.domain), InvalidOption);
  EXPECT_TRUE(validate(create_mesh(scene)).ok()); // unclosed, the label is a label like any other
}

} // namespace
