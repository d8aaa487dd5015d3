// Labelled point clouds (paper sect. 5, eq. 7) from PLY and text files: the
// paper's four-region example meshed from both, and the PLY variants and
// errors of the point reader.
#include "scratch_dir.hpp"

#include "fields/point_cloud.hpp"

#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace vm;
using PlyPoints = vm::test::ScratchDir;

struct LabelledPoint {
  Vec3 p;
  int32_t label;
};

/// The four regions of scripts/make_point_cloud.py (the same shape; the script
/// uses Python's generator, this one a fixed mt19937_64): 2 green inside a torus
/// that runs through the red ball 1 and up into blue 3, above a wavy surface the
/// ball's top pokes through; 4 grey the rest.
int32_t region(const Vec3& x) {
  const double ring = std::hypot(x.y() - 0.5, x.z() - 0.5) - 0.28;
  if (std::hypot(ring, x.x() - 0.5) < 0.1) return 2;
  if ((x - Vec3(0.5, 0.5, 0.42)).norm() < 0.3) return 1;
  if (x.z() > 0.72 + 0.06 * std::sin(2 * std::numbers::pi * x.x()) * std::cos(2 * std::numbers::pi * x.y())) return 3;
  return 4;
}

std::vector<LabelledPoint> four_regions(int count) {
  std::mt19937_64 rng(20240607);
  // 53 random bits per coordinate: the same numbers on every standard library.
  const auto unit = [&] { return double(rng() >> 11) * 0x1p-53; };
  std::vector<LabelledPoint> out;
  for (int i = 0; i < count; ++i) {
    const double x = unit(), y = unit(), z = unit();
    out.push_back({Vec3(x, y, z), region(Vec3(x, y, z))});
  }
  return out;
}

/// Text: %.17g round-trips every double, so both files hold the same points.
void write_xyz(const std::string& path, const std::vector<LabelledPoint>& pts) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fprintf(f, "# x y z label\n");
  for (const auto& [p, l] : pts) std::fprintf(f, "%.17g %.17g %.17g %d\n", p.x(), p.y(), p.z(), l);
  std::fclose(f);
}

/// Big-endian binary with an unused property between the coordinates and the
/// label, and a face element a point cloud does not need: the reader must skip both.
void write_ply_be(const std::string& path, const std::vector<LabelledPoint>& pts) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_big_endian 1.0\nelement vertex " << pts.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nproperty uchar red\nproperty int label\n"
         "element face 0\nproperty list uchar int vertex_indices\nend_header\n";
  const auto put = [&](auto v) {
    auto bytes = std::bit_cast<std::array<char, sizeof v>>(v);
    if constexpr (std::endian::native == std::endian::little) std::reverse(bytes.begin(), bytes.end());
    out.write(bytes.data(), std::streamsize(bytes.size()));
  };
  for (const auto& [p, l] : pts) put(p.x()), put(p.y()), put(p.z()), put(uint8_t(200)), put(int32_t(l));
}

NodeMesh create_mesh(const Scene& scene) {
  SampledField field = SampledField::sample(*scene.field, grid_for_lattice(scene.grid, Lattice::bcc));
  NodeMesh mesh;
  create_initial_mesh(field, {}, mesh);
  return mesh;
}

NodeMesh improved(const NodeMesh& node_mesh, const PhaseField& field) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(node_mesh);
  RunOptions run;
  run.iterations = 20;
  Pipeline::parse(kDefaultPipeline, builtin_registry()).run(mesh, &field, run);
  return mesh.to_node_mesh();
}

bool same(const NodeMesh& a, const NodeMesh& b) {
  return a.points == b.points && a.triangles == b.triangles && a.pairs == b.pairs;
}

/// Over the vertices of each surface (a, b): how far from halfway between the
/// nearest points of a and of b, |d_a - d_b|; the largest and the mean.
std::pair<double, double> off_halfway(const NodeMesh& m, const PhaseField& f) {
  double worst = 0, sum = 0;
  size_t n = 0;
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int32_t v : m.triangles[t]) {
      const Vec3& x = m.points[size_t(v)];
      const double off = std::abs(f.value(m.pairs[t][0], x) - f.value(m.pairs[t][1], x));
      worst = std::max(worst, off), sum += off, ++n;
    }
  return {worst, sum / double(n)};
}

// Sect. 5, Fig. 10: four regions of random points on a 32^3 grid. The same
// points as PLY and as text give the same meshes, and the improved mesh lies
// where eq. 7 puts the interfaces: halfway between the two regions' points.
TEST_F(PlyPoints, four_regions_from_ply_and_text_mesh_alike_and_halfway) {
  constexpr int count = 8000;
  const auto pts = four_regions(count);
  write_xyz(path("four.xyz"), pts);
  write_ply_be(path("four.ply"), pts);
  Scene ply = load_input(path("four.ply")), xyz = load_input(path("four.xyz"));
  ply.grid.cells = xyz.grid.cells = {32, 32, 32};
  ASSERT_EQ(ply.field->num_phases(), 4);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(ply.field->phase_label(i), i + 1);

  const NodeMesh created = create_mesh(ply);
  EXPECT_TRUE(validate(created).ok()) << validate(created).summary();
  EXPECT_TRUE(same(created, create_mesh(xyz)));
  const NodeMesh mesh = improved(created, *ply.field);
  EXPECT_TRUE(validate(mesh).ok()) << validate(mesh).summary();
  EXPECT_TRUE(same(mesh, improved(create_mesh(xyz), *xyz.field)));

  const double spacing = std::cbrt(1.0 / count); // mean distance between neighbouring points
  const auto [worst_created, mean_created] = off_halfway(created, *ply.field);
  const auto [worst, mean] = off_halfway(mesh, *ply.field);
  std::printf("|d_a - d_b| / spacing: create max %.3f mean %.4f, mesh max %.3f mean %.4f\n", worst_created / spacing,
              mean_created / spacing, worst / spacing, mean / spacing);
  // Measured: create max 0.86 mean 0.13 spacings, mesh max 0.76 mean 0.010
  // (spacing 0.05, a grid cell 0.034): projection onto the exact distances
  // pulls the vertices onto the interfaces; the worst is a surface node the
  // crossing guard holds back (0.29 without the guard: these interfaces have
  // corners finer than a cell, which the mesh cannot follow without crossing).
  // Which node the guard holds, and how far, changes with any change to the
  // passes: before triple-curve forces were kept along their curves, max 0.42
  // and mean 0.016; with them 0.71; with the quality floor 0.76.
  EXPECT_LT(worst, 0.8 * spacing);
  EXPECT_LT(mean, 0.025 * spacing);
  EXPECT_LT(mean, mean_created / 5);
}

/// The message load_input throws for `body` written to `name`.
std::string error_of(const std::string& file, const std::string& body) {
  std::ofstream(file) << body;
  try {
    load_input(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// Ascii PLY with float labels named 'phase' (as some tools write them) reads
// like the text file of the same points; what is not a labelled cloud is refused.
TEST_F(PlyPoints, ascii_float_phase_labels_and_errors) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  std::ofstream(path("a.ply")) << head << "property float phase\nend_header\n0 0 0 7\n1 0 0 7.0\n0 1 0 -2\n";
  std::ofstream(path("a.xyz")) << "0 0 0 7\n1 0 0 7\n0 1 0 -2\n";
  const Scene ply = load_input(path("a.ply")), xyz = load_input(path("a.xyz"));
  EXPECT_EQ(ply.field->phase_label(0), -2);
  EXPECT_EQ(ply.field->phase_label(1), 7);
  EXPECT_EQ(ply.grid.domain.min, xyz.grid.domain.min);
  EXPECT_EQ(ply.field->value(1, Vec3(0.5, 0.2, 0)), xyz.field->value(1, Vec3(0.5, 0.2, 0)));
  // As a spreadsheet or a Windows editor saves them: a byte order mark first, CRLF line ends.
  std::ofstream(path("windows.xyz")) << "\xEF\xBB\xBF" "0 0 0 7\r\n1 0 0 7\r\n0 1 0 -2\r\n";
  const Scene windows = load_input(path("windows.xyz"));
  EXPECT_EQ(windows.grid.domain.min, xyz.grid.domain.min);
  EXPECT_EQ(windows.field->value(1, Vec3(0.5, 0.2, 0)), xyz.field->value(1, Vec3(0.5, 0.2, 0)));

  const std::string f = path("b.ply");
  EXPECT_EQ(error_of(f, head + "end_header\n0 0 0\n1 0 0\n0 1 0\n"),
            f + ": no vertex property 'label' (a labelled point cloud needs one)");
  EXPECT_EQ(error_of(f, head + "property float label\nend_header\n0 0 0 1\n1 0 0 1.5\n0 1 0 2\n"),
            f + ": vertex 1: label 1.5 is not a 32-bit integer");
  EXPECT_EQ(error_of(f, head + "property int label\nend_header\n0 0 0 1\n1 nan 0 1\n0 1 0 2\n"),
            f + ": vertex 1: coordinates must be finite");
  EXPECT_EQ(error_of(f, head + "property int label\nend_header\n0 0 0 1\n1 0 0 1\n0 1 0 1\n"),
            f + ": has 1 label(s); a labelled point cloud needs 2 or more");
  EXPECT_EQ(error_of(f, "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                        "property int label\nend_header\n"),
            f + ": has no points");
  EXPECT_EQ(error_of(f, head + "property int label\nend_header\n0 0 0 1\n"), f + ": truncated: element 'vertex' declares 3 items but only 8 bytes remain");
}

// The k nearest regions found through the tree of all points, the shortcut for
// one-seed grains and the per-thread cache of the nearest point must all agree
// with evaluating every phase from scratch: grains (a label per seed) and a few
// labels shared by many seeds, queried at the seeds themselves (ties) and
// between them, values and gradients asked in either order.
TEST(PointCloudField, top_values_and_gradients_match_every_phase_evaluated) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (const int labels : {0, 10}) { // 0: every seed its own label
    vm::detail::LabelledPoints cloud;
    for (int i = 0; i < 600; ++i) {
      cloud.points.emplace_back(u(rng), u(rng), u(rng));
      cloud.labels.push_back(labels ? int32_t(rng() % labels) : i);
    }
    const Scene scene = vm::detail::point_cloud_scene(cloud, "cloud");
    const PhaseField& field = *scene.field;
    const int n = field.num_phases();
    std::vector<double> all(static_cast<size_t>(n));
    for (int q = 0; q < 200; ++q) {
      const Vec3 x = q % 4 == 0 ? cloud.points[size_t(q)] : Vec3(u(rng), u(rng), u(rng));
      std::array<int32_t, 4> ids, want_ids;
      std::array<double, 4> vals, want_vals;
      field.top_values(x, ids, vals);
      field.PhaseField::top_values(x, want_ids, want_vals); // every phase evaluated
      EXPECT_EQ(ids, want_ids) << "query " << q;
      EXPECT_EQ(vals, want_vals) << "query " << q;
      field.values(x, all);
      for (int32_t p : {ids[0], ids[3], int32_t(q % n)}) {
        const Vec3 g = field.gradient(p, x); // gradient first, then value, then the gradient again
        EXPECT_EQ(field.value(p, x), all[size_t(p)]);
        EXPECT_EQ(field.gradient(p, x), g);
        if (all[size_t(p)] < 0) EXPECT_NEAR(g.norm(), 1.0, 1e-12);
      }
    }
  }
}

} // namespace
