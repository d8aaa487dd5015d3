// The acceptance test of label volumes: a synthetic volume of overlapping
// ellipsoids (labels 3, 7 and 200 in background 0) is meshed with a closed
// domain and improved; then every voxel centre is located in the mesh by
// casting rays along x, and the phase around it must be its voxel's label
// wherever the voxel is more than a voxel away from any other label.

#include "voronoimesh/check/label_agreement.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/run/meshing.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include "fixtures.hpp"
#include "nrrd_file.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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

/// Meshes the ellipsoids (closed domain, 20 iterations of `pipeline`) with `options` and
/// counts the voxel centres whose phase in the mesh is their label, overall and
/// among those whose neighbours within `margin` voxels all share their label.
LabelAgreement mesh_and_compare(const InputOptions& options, int margin,
                                const std::string& pipeline = kDefaultPipeline) {
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
  NodeMesh m = mesh.to_node_mesh();
  EXPECT_TRUE(validate(m).ok()) << validate(m).summary();
  for (int p = 0; p < scene.field->num_phases(); ++p) m.phase_labels.push_back(scene.field->phase_label(p));

  PointGrid voxel_centres;
  voxel_centres.size = {kSize, kSize, kSize};
  const std::vector<int32_t> labels(voxels.begin(), voxels.end());
  const LabelAgreement a = label_agreement(m, voxel_centres, labels, margin);
  std::printf("voxel centres: %lld of %lld far from interfaces agree, %lld of %lld overall (%.2f%%), %lld undecided\n",
              (long long)a.interior_in_phase, (long long)a.interior, (long long)a.in_phase, (long long)a.voxels,
              100.0 * double(a.in_phase) / double(a.voxels), (long long)a.undecided);
  return a;
}

TEST(LabelVolume, mesh_phases_agree_with_the_voxel_labels) {
  const LabelAgreement a = mesh_and_compare({}, 1);
  EXPECT_EQ(a.interior_in_phase, a.interior);
  EXPECT_GT(double(a.in_phase), 0.97 * double(a.voxels));
  EXPECT_LT(a.undecided, a.voxels / 100);
}

TEST(LabelVolume, the_agreement_counts_every_label_and_says_so_in_text_and_json) {
  const LabelAgreement a = mesh_and_compare({}, 1);
  std::vector<int32_t> labels;
  int64_t voxels = 0, in_phase = 0;
  for (const LabelAgreement::Label& l : a.labels) labels.push_back(l.label), voxels += l.voxels, in_phase += l.in_phase;
  EXPECT_EQ(labels, (std::vector<int32_t>{0, 3, 7, 200}));
  EXPECT_EQ(voxels, a.voxels);
  EXPECT_EQ(in_phase, a.in_phase);
  EXPECT_TRUE(a.lost().empty());
  ASSERT_NE(a.worst(), nullptr);
  EXPECT_LE(double(a.worst()->in_phase) / double(a.worst()->voxels), double(a.in_phase) / double(a.voxels));
  const std::string text = to_text(a);
  EXPECT_NE(text.find("voxel centres in their label's phase: "), std::string::npos) << text;
  EXPECT_NE(text.find("worst label " + std::to_string(a.worst()->label) + ": "), std::string::npos) << text;
  EXPECT_NE(text.find("labels with none in their phase: none"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(to_json(a));
  EXPECT_EQ(j.at("in_phase").get<int64_t>(), a.in_phase);
  EXPECT_EQ(j.at("labels").size(), 4u);
}

TEST(LabelVolume, the_agreement_of_a_mesh_that_is_not_closed_is_refused) {
  PointGrid centres;
  centres.size = {2, 2, 2};
  const std::vector<int32_t> labels(8, 1);
  EXPECT_THROW(label_agreement(test::tetrahedron(), centres, labels), InvalidInput);
  NodeMesh closed = test::tetrahedron();
  closed.outside_phase = 0;
  EXPECT_THROW(label_agreement(closed, centres, std::vector<int32_t>(7, 1)), InvalidInput); // a label short
}

// A file whose x axis runs backwards, meshed in its own LPS frame and converted
// to RAS: read_placed_volume() puts the voxels where load_input() put the
// mesh, so the centres agree as well as on plain axes (the ellipsoids are not
// symmetric: a voxel grid left unflipped would disagree across most of them).
TEST(LabelVolume, voxel_centres_of_flipped_and_converted_volumes_are_placed_as_the_mesh_was) {
  std::vector<uint8_t> voxels;
  for (int k = 0; k < kSize; ++k)
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i) voxels.push_back(ellipsoid_label(i, j, k));
  const std::string path =
      test::write_nrrd("flipped_ellipsoids.nrrd",
                       "type: uchar\ndimension: 3\nsizes: 40 40 40\nspace: left-posterior-superior\n"
                       "space directions: (-1,0,0) (0,1,0) (0,0,1)\nspace origin: (39,0,0)\n",
                       voxels);
  for (const World world : {World::file, World::ras}) {
    InputOptions options;
    options.world = world;
    MeshOptions close;
    close.close = true;
    close.iterations = 3;
    const NodeMesh m = mesh_scene(load_input(path, options), close);
    const io::Volume v = read_placed_volume(path, options);
    EXPECT_TRUE(v.direction.isIdentity());
    const LabelAgreement a = label_agreement(m, {v.origin, v.spacing, v.size}, v.labels);
    EXPECT_EQ(a.interior_in_phase, a.interior) << "world " << int(world);
    EXPECT_GT(double(a.in_phase), 0.97 * double(a.voxels)) << "world " << int(world);
    // The file's own voxel order, placed as if its axes were plain, lands elsewhere: thousands
    // of interior centres in another label's phase (4,400 in the file's frame, 2,000 in RAS,
    // where only y is flipped).
    const LabelAgreement unplaced =
        label_agreement(m, {v.origin, v.spacing, v.size}, std::vector<int32_t>(voxels.begin(), voxels.end()));
    EXPECT_LT(unplaced.interior_in_phase + 1000, a.interior_in_phase) << "world " << int(world);
  }
}

// --voxels-per-cell 2: a mesh with about a quarter of the triangles, still
// right wherever the labels are 2 voxels from any other label.
TEST(LabelVolume, coarser_grid_agrees_with_the_voxel_labels) {
  InputOptions coarse;
  coarse.voxels_per_cell = 2;
  const LabelAgreement a = mesh_and_compare(coarse, 2);
  EXPECT_EQ(a.interior_in_phase, a.interior);
  EXPECT_GT(double(a.in_phase), 0.95 * double(a.voxels));
  EXPECT_LT(a.undecided, a.voxels / 100);
}

// Remeshed to edges 1.4 times as long (about half the triangles; the default
// for label volumes): as right as the paper's pipeline wherever the labels are
// a voxel from any other label.
TEST(LabelVolume, remeshed_mesh_agrees_with_the_voxel_labels) {
  const LabelAgreement a = mesh_and_compare({}, 1, kLabelVolumePipeline);
  EXPECT_EQ(a.interior_in_phase, a.interior);
  EXPECT_GT(double(a.in_phase), 0.97 * double(a.voxels));
  EXPECT_LT(a.undecided, a.voxels / 100);
}

// Every voxel centre counts, the outer layer's too: on the box faces of the low
// sides, located a hair inside, and on the high sides, where a grid of an odd
// number of cells reaches one voxel beyond them. Two slabs of 6 and 5 voxels
// (x < 6: label 1, else 2) across an 11 x 6 x 5 volume: every centre lies a
// voxel or more from the flat interface between them, so all are in their phase.
// (Before, only the 9 x 4 x 3 centres off the outer layer were counted.)
TEST(LabelVolume, the_outer_layer_of_voxel_centres_is_located_too) {
  std::vector<uint8_t> voxels;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 11; ++i) voxels.push_back(i < 6 ? 1 : 2);
  const std::string path = test::write_nrrd("slabs.nrrd", "type: uchar\ndimension: 3\nsizes: 11 6 5\n", voxels);
  const Scene scene = load_input(path);
  CreateParams close;
  close.close = true;
  const auto phases = with_outside_phase(scene.field, scene.grid.domain);
  NodeMesh m = test::created_mesh(scene, close, phases.get());
  for (int p = 0; p < scene.field->num_phases(); ++p) m.phase_labels.push_back(scene.field->phase_label(p));
  const io::Volume v = read_placed_volume(path, {});
  const LabelAgreement a = label_agreement(m, {v.origin, v.spacing, v.size}, {v.labels.data(), v.labels.size()});
  EXPECT_EQ(a.voxels, 11 * 6 * 5);
  EXPECT_EQ(a.undecided, 0);
  EXPECT_EQ(a.in_phase, a.voxels);
}

} // namespace
