// Label volumes read with InputOptions::voxel_faithful (opt-in, --voxel-faithful)
// keep every label where its voxels are (issue 19): structures one voxel thin
// (islands, a sheet, a tube), negative labels and a 6^3 block whose corners
// smoothing alone rounds off. Every voxel centre is located in the closed mesh
// (check/locate.hpp) after create and after the default label pipeline, and
// counted per label. The default loses such labels.

#include "voronoimesh/check/label_agreement.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/improve/remesh.hpp"
#include "voronoimesh/improve/smooth.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/run/mesher.hpp"
#include "voronoimesh/run/meshing.hpp"

#include "nrrd_file.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace vm;

constexpr int kSize = 32; // voxels per axis, spacing 1, voxel (0,0,0) at the origin

/// Islands at each parity class of the bcc lattice (all even, one odd, two odd,
/// all odd), two of them negative; a sheet, a tube, a block: background 0.
std::vector<int16_t> thin_structures() {
  std::vector<int16_t> v(size_t(kSize * kSize * kSize), 0);
  auto at = [&](int i, int j, int k) -> int16_t& { return v[size_t(i + kSize * (j + kSize * k))]; };
  for (int j = 4; j < 28; ++j)
    for (int k = 4; k < 28; ++k) at(8, j, k) = 2; // a sheet one voxel thick, across x
  for (int k = 4; k < 28; ++k) at(20, 21, k) = 3;  // a tube one voxel wide, along z
  for (int i = 22; i < 28; ++i)
    for (int j = 4; j < 10; ++j)
      for (int k = 20; k < 26; ++k) at(i, j, k) = 4; // the 6^3 block
  const std::array<std::array<int, 4>, 6> islands{{{14, 6, 6, 10}, {15, 6, 12, 11}, {15, 7, 18, 12}, {15, 7, 25, 13},
                                                   {12, 26, 26, -5}, {26, 14, 14, -6}}};
  for (const auto& [i, j, k, label] : islands) at(i, j, k) = int16_t(label);
  return v;
}

struct LabelShare {
  int64_t voxels = 0, inside = 0;
};

/// Per label, its voxel centres (all of them; voxels of `spacing`) and how many lie in its phase of `mesh`.
std::map<int, LabelShare> shares(const NodeMesh& mesh, const Scene& scene, const std::vector<int16_t>& labels,
                                 const Vec3& spacing) {
  PointGrid centres;
  centres.size = {kSize, kSize, kSize};
  centres.spacing = spacing;
  NodeMesh labelled = mesh; // a created mesh knows its phases' ids, not their labels
  labelled.phase_labels.clear();
  for (int p = 0; p < scene.field->num_phases(); ++p) labelled.phase_labels.push_back(scene.field->phase_label(p));
  const LabelAgreement a = label_agreement(labelled, centres, std::vector<int32_t>(labels.begin(), labels.end()));
  std::map<int, LabelShare> by_label;
  for (const LabelAgreement::Label& l : a.labels) by_label[l.label] = {l.voxels, l.in_phase};
  return by_label;
}

/// The smallest share of a label's voxel centres inside its phase, and the share of all of them.
std::array<double, 2> worst_and_all(const std::map<int, LabelShare>& by_label, const char* stage) {
  double worst = 1;
  int64_t voxels = 0, inside = 0;
  for (const auto& [label, s] : by_label) {
    const double share = double(s.inside) / double(s.voxels);
    std::printf("%s: label %d: %lld of %lld voxel centres in its phase\n", stage, label, (long long)s.inside,
                (long long)s.voxels);
    worst = std::min(worst, share), voxels += s.voxels, inside += s.inside;
  }
  return {worst, double(inside) / double(voxels)};
}

struct Meshed {
  std::array<double, 2> created, improved; ///< worst label's share, all voxels' share
  std::map<int, LabelShare> created_by_label, improved_by_label;
};

/// The thin structures with voxels of `spacing` (the same voxels, stretched), read with `input`.
Scene load_thin_structures(const InputOptions& input, const Vec3& spacing) {
  const std::string path = test::write_nrrd(
      "thin_structures.nrrd",
      "type: short\ndimension: 3\nsizes: 32 32 32\nspacings: " + std::to_string(spacing.x()) + " " +
          std::to_string(spacing.y()) + " " + std::to_string(spacing.z()) + "\n",
      thin_structures());
  return load_input(path, input);
}

/// Flat voxels, as CT and MR slices have them (CGAL's liver: 0.62 x 0.62 x 1.33).
const Vec3 kFlatVoxels(0.6, 0.6, 1.35);

/// The thin structures meshed with voxels of `spacing` (the same voxels, stretched).
Meshed mesh_thin_structures(const InputOptions& input, const Vec3& spacing = Vec3::Ones()) {
  const std::vector<int16_t> labels = thin_structures();
  const Scene scene = load_thin_structures(input, spacing);
  MeshOptions o;
  o.close = true;
  o.threads = 2;
  o.pipeline = pipeline_for(o, &scene); // the label volume's default, remesh first
  NodeMesh mesh = create_mesh(scene, o);
  Meshed m;
  m.created_by_label = shares(mesh, scene, labels, spacing);
  m.created = worst_and_all(m.created_by_label, "create");
  improve_mesh(mesh, scene.field, o);
  m.improved_by_label = shares(mesh, scene, labels, spacing);
  m.improved = worst_and_all(m.improved_by_label, "mesh");
  return m;
}

/// Every voxel centre of the one-voxel structures (all labels but the
/// background, 0, and the 6^3 block, 4) in its label's phase.
void expect_one_voxel_structures_kept(const std::map<int, LabelShare>& by_label) {
  for (const auto& [label, share] : by_label)
    if (label != 0 && label != 4) EXPECT_EQ(share.inside, share.voxels) << "label " << label;
}

InputOptions faithful() {
  InputOptions o;
  o.voxel_faithful = true;
  return o;
}

TEST(VoxelFaithful, every_label_keeps_its_voxel_centres) {
  const Meshed m = mesh_thin_structures(faithful());
  EXPECT_EQ(m.created[0], 1.0); // every voxel centre of every label, after create
  // Issue 19 asks 0.9 of every label after the default pipeline. The crossing
  // guard undoes moves that carry the centre of a voxel of a thin structure
  // out of its label (improve/kept_points.hpp): without it the one-voxel tube
  // kept 19 of its 24 centres (0.79), with it 22; the remesh pass's collapses
  // are held to the same (improve/node_merge.hpp): now 24, and the sheet 564
  // of its 576 (563 before); flips and the flip pass's collapses too
  // (improve/kept_points.hpp, flip_loses_kept_point()): the sheet keeps all 576.
  EXPECT_GE(m.improved[0], 0.9);
  EXPECT_GE(m.improved[1], 0.99);
  expect_one_voxel_structures_kept(m.improved_by_label);
}

// Flat voxels (CT and MR slices, CGAL's liver: 0.62 x 0.62 x 1.33): create snaps
// values closer than 0.2 of the grid's largest spacing, more than a voxel's
// lead at its centre (0.3 of the smallest). Snapping tied every centre of the
// one-voxel sheet, tube and islands (all lost), so create snaps nothing at the
// centres of voxels one voxel thin (the field's kept points). The 6^3 block's
// edges and corners, which only lead by that much, may still be tied: 169 of
// its 216 centres after create, 197 after the default pipeline (its remesh
// collapses took 81 of the sheet's 576 centres out of it before they were held
// to the kept points: 495; 563 before flips were held to them too: 576).
TEST(VoxelFaithful, flat_voxels_keep_structures_one_voxel_thin) {
  const Meshed m = mesh_thin_structures(faithful(), kFlatVoxels);
  expect_one_voxel_structures_kept(m.created_by_label);
  EXPECT_GE(m.created_by_label.at(4).inside, 0.75 * double(m.created_by_label.at(4).voxels));
  EXPECT_GE(m.improved[0], 0.9);
  EXPECT_GE(m.improved[1], 0.99);
  expect_one_voxel_structures_kept(m.improved_by_label);
}

// The remesh pass alone, as its first call in the label default runs (splits,
// then four rounds of collapses), on the flat voxels: its collapses at the
// sheet's rim left triangles through the centres there (a thousandth of a
// voxel away, which the point location reads as outside: 572 of the 576).
// Collapses must keep every kept point a little inside (improve/kept_points.cpp).
TEST(VoxelFaithful, remesh_collapses_leave_no_kept_point_on_a_surface) {
  const Scene scene = load_thin_structures(faithful(), kFlatVoxels);
  MeshOptions o;
  o.close = true;
  o.threads = 2;
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(create_mesh(scene, o));
  RemeshParams params;
  params.size = 1.4;
  params.split_first = true;
  const RemeshStats done = remesh_edges(mesh, scene.field.get(), rms_edge_length(mesh), params);
  EXPECT_GT(done.collapses, 5000u); // it coarsens, so the collapses are there to be judged
  expect_one_voxel_structures_kept(shares(mesh.to_node_mesh(), scene, thin_structures(), kFlatVoxels));
}

// The paper's passes, 20 iterations, on the flat voxels: flips were judged
// after they were made, through the faces the last flip of each made, so a
// flip whose two faces later flips changed again went unjudged; the sheet lost
// a centre in the 17th or 18th iteration. Each flip is now judged before it is
// made (flip_gain()).
TEST(VoxelFaithful, the_papers_passes_keep_structures_one_voxel_thin_through_20_iterations) {
  const Scene scene = load_thin_structures(faithful(), kFlatVoxels);
  MeshOptions o;
  o.close = true;
  o.threads = 2;
  o.pipeline = "smooth,project,clamp,flip";
  o.iterations = 20;
  o.stop_when_converged = false;
  NodeMesh mesh = create_mesh(scene, o);
  improve_mesh(mesh, scene.field, o);
  expect_one_voxel_structures_kept(shares(mesh, scene, thin_structures(), kFlatVoxels));
}

// The default (the smoothed indicator as it is, on bcc) loses the islands:
// what the option is there to prevent.
TEST(VoxelFaithful, the_default_loses_one_voxel_islands) {
  const Meshed m = mesh_thin_structures({});
  EXPECT_EQ(m.created[0], 0.0);
}

// --lattice auto is bcc unless the volume is read voxel-faithful and bcc would
// lose more than 1% of a label (the sheet, the tube and some islands here).
TEST(VoxelFaithful, auto_lattice_is_bcc_unless_voxel_faithful) {
  const std::string path = test::write_nrrd(
      "auto_lattice.nrrd", "type: short\ndimension: 3\nsizes: 32 32 32\nspacings: 1 1 1\n", thin_structures());
  const Scene plain = load_input(path), kept = load_input(path, faithful());
  InputOptions distance;
  distance.label_function = LabelFunction::signed_distance;
  const Scene signed_plain = load_input(path, distance);
  distance.voxel_faithful = true; // signed distances lead at voxel centres: only the lattice changes
  const Scene signed_kept = load_input(path, distance);
  std::remove(path.c_str());
  EXPECT_EQ(lattice_for(MeshOptions{}, plain), Lattice::bcc);
  EXPECT_TRUE(plain.notes.empty()); // no line about the lattice without the option
  EXPECT_EQ(lattice_for(MeshOptions{}, signed_plain), Lattice::bcc);
  EXPECT_EQ(lattice_for(MeshOptions{}, kept), Lattice::cube6);
  EXPECT_EQ(lattice_for(MeshOptions{}, signed_kept), Lattice::cube6);
  MeshOptions given;
  given.lattice = Lattice::bcc;
  EXPECT_EQ(lattice_for(given, kept), Lattice::bcc);
}

// A 32^3 volume with two voxels of label 3 between labels 1 and 2, each off
// the bcc lattice and between a voxel of 1 and one of 2 along its lattice
// edge (as label 84 of CGAL's liver, which the bcc lattice lost).
std::vector<int16_t> two_voxels_between_two_labels() {
  std::vector<int16_t> labels(size_t(kSize * kSize * kSize));
  for (int k = 0; k < kSize; ++k)
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i) {
        // 1 below the plane y = 16, 2 above; in it, 1 below z = 15 and 2 above;
        // in that row, 1 and 2 on either side of the two voxels of 3.
        const int side = j != 16 ? j - 16 : k != 15 ? k - 15 : i < 15 ? -1 : i > 16 ? 1 : 0;
        labels[size_t(i + kSize * (j + kSize * k))] = int16_t(side < 0 ? 1 : side > 0 ? 2 : 3);
      }
  return labels;
}

/// The shares of kSize^3 `labels`, written to `file` and read --voxel-faithful,
/// in the closed mesh create makes of them, once --lattice auto has taken cube6
/// for them (expected: bcc cannot hold some of their centres).
std::map<int, LabelShare> shares_on_cube6(const std::vector<int16_t>& labels, const std::string& file) {
  const std::string path = test::write_nrrd(file, "type: short\ndimension: 3\nsizes: 32 32 32\n", labels);
  const Scene scene = load_input(path, faithful());
  std::remove(path.c_str());
  EXPECT_EQ(lattice_for(MeshOptions{}, scene), Lattice::cube6);
  MeshOptions o;
  o.close = true;
  o.threads = 2;
  return shares(create_mesh(scene, o), scene, labels, Vec3::Ones());
}

// Two voxels of label 3 between labels 1 and 2 (two_voxels_between_two_labels()):
// --lattice auto sees that bcc cannot hold them, and create keeps both
// centres in their label.
TEST(VoxelFaithful, a_two_voxel_label_between_two_others_keeps_its_centres) {
  const auto by_label = shares_on_cube6(two_voxels_between_two_labels(), "between_two.nrrd");
  EXPECT_EQ(by_label.at(3).voxels, 2);
  EXPECT_EQ(by_label.at(3).inside, 2);
}

// The voxel centres the bcc lattice cannot hold depend on how much snapping
// may take from their label at the lattice's nodes: a Mesher reads a volume
// for the snap its create will use (MeshOptions::snap), not the default's.
TEST(VoxelFaithful, bcc_losses_are_counted_for_the_snap_create_is_given) {
  std::vector<int16_t> labels(size_t(kSize * kSize * kSize));
  uint32_t random = 12345;
  for (size_t v = 0; v < labels.size(); ++v) {
    random = random * 1664525u + 1013904223u; // labels 1 and 2 in halves, 8% of voxels label 3
    labels[v] = int16_t((random >> 24) < 20 ? 3 : v / (kSize * kSize) % kSize < 16 ? 1 : 2);
  }
  const std::string path =
      test::write_nrrd("snap_losses.nrrd", "type: short\ndimension: 3\nsizes: 32 32 32\nspacings: 1 1 1\n", labels);
  auto centres_lost_at = [&](double snap) {
    MeshOptions o;
    o.snap = snap;
    const Scene scene = Mesher(o).read(path, faithful());
    EXPECT_EQ(scene.notes.size(), 1u);
    return scene.notes.empty() ? 0 : std::stoi(scene.notes.back()); // "N voxel centres lie in ..."
  };
  const int unsnapped = centres_lost_at(0), snapped = centres_lost_at(0.2);
  InputOptions bad = faithful();
  bad.snap = 0.7;
  EXPECT_THROW(load_input(path, bad), InvalidInput);
  std::remove(path.c_str());
  EXPECT_GT(unsnapped, 0);
  EXPECT_GT(snapped, unsnapped);
}

// A sheet one voxel thin in the volume's last layer along x: 32 voxels are 31
// cells, which the grid makes 32 with one node past the last voxel, where the
// field holds the last voxel's values. Its centres between lattice nodes lie
// on edges from the background's layer to that node, which the bcc lattice
// lets the background win; --lattice auto took them for held (a voxel's
// neighbour beyond the volume taken as itself), and the sheet was lost.
TEST(VoxelFaithful, a_sheet_in_the_last_layer_keeps_its_centres) {
  std::vector<int16_t> labels(size_t(kSize * kSize * kSize), 0);
  for (int k = 8; k < 24; ++k)
    for (int j = 8; j < 24; ++j) labels[size_t(kSize - 1 + kSize * (j + kSize * k))] = 3;
  const auto by_label = shares_on_cube6(labels, "last_layer.nrrd");
  EXPECT_EQ(by_label.at(3).voxels, 16 * 16);
  EXPECT_EQ(by_label.at(3).inside, 16 * 16);
}

// Sheets one voxel thin in the volume's first layer along x (on the box face)
// and its last along y (beside the node the grid adds past it) are thin
// structures too: their centres are kept points, and improvement keeps them
// in their phase (before, 2 and 3 of their 256 were not). Of the first, a
// corner on the box face may end on the curve where the sheet meets the face.
TEST(VoxelFaithful, sheets_in_the_first_and_last_layers_keep_their_centres_through_improvement) {
  std::vector<int16_t> labels(size_t(kSize * kSize * kSize), 0);
  for (int k = 8; k < 24; ++k)
    for (int t = 8; t < 24; ++t) {
      labels[size_t(0 + kSize * (t + kSize * k))] = 3;
      labels[size_t(t + kSize * (kSize - 1 + kSize * k))] = 5;
    }
  const std::string path = test::write_nrrd("face_sheets.nrrd", "type: short\ndimension: 3\nsizes: 32 32 32\n", labels);
  const Scene scene = load_input(path, faithful());
  std::remove(path.c_str());
  MeshOptions o;
  o.close = true;
  o.threads = 2;
  o.pipeline = pipeline_for(o, &scene);
  NodeMesh mesh = create_mesh(scene, o);
  improve_mesh(mesh, scene.field, o);
  const auto by_label = shares(mesh, scene, labels, Vec3::Ones());
  EXPECT_GE(by_label.at(3).inside, 16 * 16 - 1);
  EXPECT_EQ(by_label.at(5).inside, 16 * 16);
}

// The tiny test image of mesher suites: label 1 is one voxel.
TEST(VoxelFaithful, two_by_two_by_two_volume_keeps_all_four_labels) {
  const std::vector<uint8_t> labels{0, 0, 0, 1, 2, 3, 2, 3};
  const std::string path = test::write_nrrd("two_cubed.nrrd", "type: uchar\ndimension: 3\nsizes: 2 2 2\n", labels);
  const Scene scene = load_input(path, faithful());
  ASSERT_EQ(scene.field->num_phases(), 4);
  MeshOptions o;
  o.threads = 2;
  o.pipeline = pipeline_for(o, &scene);
  NodeMesh mesh = create_mesh(scene, o);
  improve_mesh(mesh, scene.field, o);
  std::vector<int> bounded(4, 0);
  for (const PhasePair& p : mesh.pairs)
    for (int32_t phase : p) bounded[size_t(phase)] = 1;
  EXPECT_EQ(bounded, std::vector<int>(4, 1));
}

} // namespace
