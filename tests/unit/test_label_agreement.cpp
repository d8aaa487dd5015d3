// The acceptance test of label volumes: a synthetic volume of overlapping
// ellipsoids (labels 3, 7 and 200 in background 0) is meshed with a closed
// domain and improved; then every voxel centre is located in the mesh by
// casting rays along x, and the phase around it must be its voxel's label
// wherever the voxel is more than a voxel away from any other label.

#include "voronoimesh/check/locate.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include "fixtures.hpp"
#include "nrrd_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace vm;

constexpr int kSize = 40; // voxels per axis, spacing 1, voxel (0,0,0) at the origin

/// Label of voxel (i, j, k): three overlapping ellipsoids, later ones on top.
uint8_t ellipsoid_label(int i, int j, int k) {
  struct Ellipsoid {
    Vec3 centre, radii;
    uint8_t label;
  };
  const Ellipsoid shapes[] = {{{14, 18, 20}, {10, 7, 13}, 3}, {{25, 20, 18}, {9, 13, 8}, 7}, {{20, 12, 27}, {6, 6, 9}, 200}};
  uint8_t label = 0;
  for (const Ellipsoid& e : shapes)
    if ((Vec3(i, j, k) - e.centre).cwiseQuotient(e.radii).squaredNorm() < 1) label = e.label;
  return label;
}

struct Agreement {
  size_t far = 0, far_agree = 0, all = 0, all_agree = 0, undecided = 0;
};

/// Meshes the ellipsoids (closed domain, 20 iterations of `pipeline`) with `options` and
/// counts the voxel centres whose phase in the mesh is their label, overall and
/// among those whose neighbours within `margin` voxels all share their label.
Agreement mesh_and_compare(const InputOptions& options, int margin, const std::string& pipeline = kDefaultPipeline) {
  std::vector<uint8_t> voxels;
  for (int k = 0; k < kSize; ++k)
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i) voxels.push_back(ellipsoid_label(i, j, k));
  const std::string path = test::write_nrrd("ellipsoids.nrrd", "type: uchar\ndimension: 3\nsizes: 40 40 40\n", voxels);
  const Scene scene = load_input(path, options);
  EXPECT_EQ(scene.field->num_phases(), 4);
  CreateParams close;
  close.close = true;
  const auto phases = with_outside_phase(scene.field, scene.grid.domain);
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::created_mesh(scene, close, phases.get()));
  RunOptions run;
  run.iterations = 20;
  Pipeline::parse(pipeline, builtin_registry()).run(mesh, phases.get(), run);
  const NodeMesh m = mesh.to_node_mesh();
  EXPECT_TRUE(validate(m).ok()) << validate(m).summary();

  PointGrid voxel_centres;
  voxel_centres.size = {kSize, kSize, kSize};
  const std::vector<int32_t> located = locate_grid_points(m, voxel_centres);
  Agreement a;
  for (int k = 1; k < kSize - 1; ++k)
    for (int j = 1; j < kSize - 1; ++j)
      for (int i = 1; i < kSize - 1; ++i) {
        const size_t v = size_t(i + kSize * (j + kSize * k));
        if (located[v] < 0) {
          ++a.undecided;
          continue;
        }
        const int label = voxels[v];
        const bool agree = scene.field->phase_label(located[v]) == label;
        bool uniform = true; // all neighbours within the margin share the label: far from any interface
        for (int dk = -margin; dk <= margin; ++dk)
          for (int dj = -margin; dj <= margin; ++dj)
            for (int di = -margin; di <= margin; ++di) {
              const int x = std::clamp(i + di, 0, kSize - 1), y = std::clamp(j + dj, 0, kSize - 1),
                        z = std::clamp(k + dk, 0, kSize - 1);
              uniform = uniform && voxels[size_t(x + kSize * (y + kSize * z))] == label;
            }
        ++a.all, a.all_agree += agree;
        if (uniform) ++a.far, a.far_agree += agree;
      }
  std::printf("voxel centres: %zu of %zu far from interfaces agree, %zu of %zu overall (%.2f%%), %zu undecided\n",
              a.far_agree, a.far, a.all_agree, a.all, 100.0 * double(a.all_agree) / double(a.all), a.undecided);
  return a;
}

TEST(LabelVolume, mesh_phases_agree_with_the_voxel_labels) {
  const Agreement a = mesh_and_compare({}, 1);
  EXPECT_EQ(a.far_agree, a.far);
  EXPECT_GT(double(a.all_agree), 0.97 * double(a.all));
  EXPECT_LT(a.undecided, a.all / 100);
}

// --voxels-per-cell 2: a mesh with about a quarter of the triangles, still
// right wherever the labels are 2 voxels from any other label.
TEST(LabelVolume, coarser_grid_agrees_with_the_voxel_labels) {
  InputOptions coarse;
  coarse.voxels_per_cell = 2;
  const Agreement a = mesh_and_compare(coarse, 2);
  EXPECT_EQ(a.far_agree, a.far);
  EXPECT_GT(double(a.all_agree), 0.95 * double(a.all));
  EXPECT_LT(a.undecided, a.all / 100);
}

// Remeshed to edges 1.4 times as long (about half the triangles; the default
// for label volumes): as right as the paper's pipeline wherever the labels are
// a voxel from any other label.
TEST(LabelVolume, remeshed_mesh_agrees_with_the_voxel_labels) {
  const Agreement a = mesh_and_compare({}, 1, kLabelVolumePipeline);
  EXPECT_EQ(a.far_agree, a.far);
  EXPECT_GT(double(a.all_agree), 0.97 * double(a.all));
  EXPECT_LT(a.undecided, a.all / 100);
}

} // namespace
