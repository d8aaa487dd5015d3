// 3D Slicer segmentations (.seg.nrrd): segment names become phase names and
// name labels on the command line; layered (4-D) files are flattened with the
// smaller segment winning where segments overlap. And --world: one
// segmentation saved in an LPS and a RAS file gives one mesh.

#include "nrrd_file.hpp"
#include "refusal.hpp"

#include "voronoimesh/voronoimesh.hpp"

#include <gtest/gtest.h>
#include <nifti2_io.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

using namespace vm;
using vm::test::refusal;
using vm::test::temp_path;
using vm::test::write_nrrd;

namespace {

constexpr int n = 16;

bool in_cube(int i, int j, int k, int lo, int hi) {
  return lo <= i && i < hi && lo <= j && j < hi && lo <= k && k < hi;
}

/// An organ (a cube of 10^3 voxels) with a tumour (4^3) inside.
uint8_t organ_with_tumour(int i, int j, int k) { return in_cube(i, j, k, 6, 10) ? 2 : in_cube(i, j, k, 3, 13) ? 1 : 0; }

/// The header lines of segment i.
std::string segment(int i, const std::string& name, int label, int layer, const std::string& color = "0.5 0.25 1") {
  const std::string key = "Segment" + std::to_string(i) + "_";
  return key + "ID:=Segment_" + std::to_string(i + 1) + "\n" + key + "Name:=" + name + "\n" + key +
         "LabelValue:=" + std::to_string(label) + "\n" + key + "Layer:=" + std::to_string(layer) + "\n" + key +
         "Color:=" + color + "\n";
}

/// A segmentation of `layers` layers, layer l of voxel (i, j, k) holding value(l, i, j, k), in LPS.
template <class Value>
std::string write_segmentation(const std::string& name, int layers, const std::string& segments, Value value) {
  std::vector<uint8_t> data;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int l = 0; l < layers; ++l) data.push_back(value(l, i, j, k));
  const std::string sizes = std::to_string(n) + " " + std::to_string(n) + " " + std::to_string(n);
  const std::string header =
      layers == 1 ? "type: uchar\ndimension: 3\nspace: left-posterior-superior\nsizes: " + sizes +
                        "\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nkinds: domain domain domain\n"
                  : "type: uchar\ndimension: 4\nspace: left-posterior-superior\nsizes: " + std::to_string(layers) + " " +
                        sizes + "\nspace directions: none (1,0,0) (0,1,0) (0,0,1)\nkinds: list domain domain domain\n";
  return write_nrrd(name, header + "space origin: (10,20,30)\n" + segments, data);
}

std::vector<std::string> names_of(const PhaseField& f) {
  std::vector<std::string> out;
  for (int p = 0; p < f.num_phases(); ++p) out.push_back(f.phase_name(p));
  return out;
}

std::vector<int32_t> labels_of(const PhaseField& f) {
  std::vector<int32_t> out;
  for (int p = 0; p < f.num_phases(); ++p) out.push_back(f.phase_label(p));
  return out;
}

} // namespace

TEST(Segmentation, segment_names_name_the_phases_and_the_labels_on_the_command_line) {
  const std::string path =
      write_segmentation("organ.seg.nrrd", 1, segment(0, "liver", 1, 0) + segment(1, "tumour", 2, 0) +
                                                  segment(2, "vessel", 3, 0),
                         [](int, int i, int j, int k) { return organ_with_tumour(i, j, k); });
  const Scene scene = load_input(path);
  EXPECT_EQ(names_of(*scene.field), (std::vector<std::string>{"background", "liver", "tumour"}));
  EXPECT_EQ(labels_of(*scene.field), (std::vector<int32_t>{0, 1, 2}));
  EXPECT_EQ(scene.world, "LPS (the file's)");
  // A segment without voxels is said, not dropped in silence.
  ASSERT_EQ(scene.notes.size(), 1u);
  EXPECT_EQ(scene.notes[0], "segment 'vessel' (label 3) has no voxels: it is no phase");
  // The mesh carries the names into every file.
  const NodeMesh mesh = create_mesh(scene);
  EXPECT_EQ(mesh.phase_names, (std::vector<std::string>{"background", "liver", "tumour"}));

  // Labels by name, as by value.
  EXPECT_EQ(names_of(*load_input(path, InputOptions{.drop_labels = {"tumour"}}).field),
            (std::vector<std::string>{"background", "liver"}));
  EXPECT_EQ(names_of(*load_input(path, InputOptions{.merge_labels = {{"tumour", "liver"}}}).field),
            (std::vector<std::string>{"background", "liver"}));
  EXPECT_EQ(names_of(*load_input(path, InputOptions{.keep_labels = {"tumour"}}).field),
            (std::vector<std::string>{"background", "tumour"}));
  EXPECT_EQ(names_of(*load_input(path, InputOptions{.keep_labels = {2}}).field),
            (std::vector<std::string>{"background", "tumour"}));
  const std::string unknown = refusal([&] { load_input(path, InputOptions{.drop_labels = {"kidney"}}); });
  EXPECT_NE(unknown.find("--drop-labels: no segment is named 'kidney' (its segments: 'liver', 'tumour', 'vessel')"),
            std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find(path), std::string::npos) << unknown;
  const std::string empty = refusal([&] { load_input(path, InputOptions{.keep_labels = {"vessel"}}); });
  EXPECT_NE(empty.find("--keep-labels: label 3 ('vessel') is not in the volume"), std::string::npos) << empty;
}

TEST(Segmentation, segment_colours_colour_their_phases_in_the_mesh) {
  const std::string path = write_segmentation(
      "colours.seg.nrrd", 1, segment(0, "liver", 1, 0, "0.9 0.5 0.25") + segment(1, "tumour", 2, 0, "0 0.5 1"),
      [](int, int i, int j, int k) { return organ_with_tumour(i, j, k); });
  const Scene scene = load_input(path);
  const std::optional<Rgb> liver = Rgb{0.9f, 0.5f, 0.25f}, tumour = Rgb{0, 0.5f, 1};
  EXPECT_EQ(scene.field->phase_color(0), std::nullopt) << "the background is no segment";
  EXPECT_EQ(scene.field->phase_color(1), liver);
  EXPECT_EQ(scene.field->phase_color(2), tumour);
  EXPECT_EQ(create_mesh(scene).phase_colors, (std::vector<std::optional<Rgb>>{std::nullopt, liver, tumour}));
  // A closed mesh's exterior has no colour; merged segments show the colour of the label they keep.
  const NodeMesh closed = create_mesh(scene, MeshOptions{.close = true});
  EXPECT_EQ(closed.phase_colors, (std::vector<std::optional<Rgb>>{std::nullopt, liver, tumour}));
  EXPECT_EQ(closed.phase_names.back(), kOutsidePhaseName);
  const Scene merged = load_input(path, InputOptions{.merge_labels = {{"tumour", "liver"}}});
  EXPECT_EQ(merged.field->phase_color(1), liver);
  // Through the improvement passes, whose mesh is rebuilt from and to a NodeMesh.
  EXPECT_EQ(mesh_scene(scene, MeshOptions{.iterations = 2}).phase_colors, create_mesh(scene).phase_colors);
}

TEST(Segmentation, overlapping_layers_give_each_voxel_to_the_smaller_segment) {
  // Slicer stores overlapping segments in layers: the organ in layer 0, the
  // tumour inside it in layer 1, both with label value 1.
  const std::string path =
      write_segmentation("layers.seg.nrrd", 2, segment(0, "liver", 1, 0) + segment(1, "tumour", 1, 1),
                         [](int l, int i, int j, int k) {
                           return uint8_t(l == 0 ? in_cube(i, j, k, 3, 13) : in_cube(i, j, k, 6, 10));
                         });
  const Scene scene = load_input(path);
  EXPECT_EQ(names_of(*scene.field), (std::vector<std::string>{"background", "liver", "tumour"}));
  // Label values collide across layers: segment i becomes label i + 1.
  EXPECT_EQ(labels_of(*scene.field), (std::vector<int32_t>{0, 1, 2}));
  EXPECT_EQ(scene.phase_voxels, (std::vector<int64_t>{n * n * n - 1000, 1000 - 64, 64}));
  ASSERT_EQ(scene.notes.size(), 1u);
  EXPECT_EQ(scene.notes[0], "64 voxels lie in more than one segment: each went to the smallest segment holding it");
  const NodeMesh mesh = create_mesh(scene);
  EXPECT_TRUE(validate(mesh).ok());
  // The tumour is a phase of the mesh: surfaces liver|tumour, no background|tumour.
  const auto has_pair = [&](PhasePair p) { return std::find(mesh.pairs.begin(), mesh.pairs.end(), p) != mesh.pairs.end(); };
  EXPECT_TRUE(has_pair({1, 2}));
  EXPECT_FALSE(has_pair({0, 2}));
}

TEST(Segmentation, malformed_segment_headers_are_refused_naming_the_file) {
  auto refused = [](const std::string& name, int layers, const std::string& segments) {
    const std::string path = write_segmentation(name, layers, segments, [](int, int i, int j, int k) {
      return uint8_t(in_cube(i, j, k, 3, 13));
    });
    const std::string why = refusal([&] { load_input(path); });
    EXPECT_NE(why.find(path), std::string::npos) << why;
    return why;
  };
  EXPECT_NE(refused("bad_layer.seg.nrrd", 1, segment(0, "a", 1, 2)).find("segment 0 ('a') is in layer 2, but the file has 1 layer"),
            std::string::npos);
  EXPECT_NE(refused("twice.seg.nrrd", 1, segment(0, "a", 1, 0) + segment(1, "b", 1, 0))
                .find("segments 0 and 1 both have label value 1 in layer 0"),
            std::string::npos);
  EXPECT_NE(refused("zero.seg.nrrd", 1, segment(0, "a", 0, 0)).find("has label value 0"), std::string::npos);
  EXPECT_NE(refused("word.seg.nrrd", 1, "Segment0_ID:=s\nSegment0_LabelValue:=one\n")
                .find("Segment0_LabelValue is 'one'; expected an integer"),
            std::string::npos);
  // A segment without its ID would end the list there, the names after it lost without a word.
  EXPECT_NE(refused("gap.seg.nrrd", 1, "Segment0_Name:=liver\nSegment0_LabelValue:=1\n" + segment(1, "tumour", 2, 0))
                .find("has Segment1_ID but no Segment0_ID: segments are numbered from 0 without gaps"),
            std::string::npos);
  // In a layered file every value must be a segment's.
  EXPECT_NE(refused("stray.seg.nrrd", 2, segment(0, "a", 2, 0) + segment(1, "b", 1, 1))
                .find("layer 0 holds value 1 at voxel"),
            std::string::npos);
}

// One segmentation in a NIfTI file (RAS) and an NRRD file (LPS): the same
// voxels at mirrored world positions. In one frame, they mesh the same.
TEST(Segmentation, world_frames_make_an_lps_and_a_ras_file_mesh_the_same) {
  const Vec3 lps_origin(10, 20, 30);
  std::vector<uint8_t> lps, ras(size_t(n * n * n));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) lps.push_back(uint8_t(in_cube(i, j, k, 3, 13)) + uint8_t(i > 8 && in_cube(i, j, k, 3, 13)));
  const std::string nrrd = write_nrrd("world.nrrd",
                                      "type: uchar\ndimension: 3\nspace: left-posterior-superior\nsizes: 16 16 16\n"
                                      "space directions: (1,0,0) (0,1,0) (0,0,1)\nkinds: domain domain domain\n"
                                      "space origin: (10,20,30)\n",
                                      lps);
  // The NIfTI twin: RAS x = -LPS x, y = -LPS y, with its voxel axes running
  // the other way along x and y so that its own direction is the identity.
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        ras[size_t(i + n * (j + n * k))] = lps[size_t((n - 1 - i) + n * ((n - 1 - j) + n * k))];
  const int64_t dims[8] = {3, n, n, n, 1, 1, 1, 1};
  nifti_image* nim = nifti_make_new_nim(dims, DT_UINT8, 1);
  std::copy(ras.begin(), ras.end(), static_cast<uint8_t*>(nim->data));
  nim->sform_code = NIFTI_XFORM_SCANNER_ANAT;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) nim->sto_xyz.m[r][c] = r == c;
    nim->sto_xyz.m[r][3] = r == 2 ? lps_origin[2] : -(lps_origin[r] + (n - 1));
  }
  const std::string nifti = temp_path("world.nii");
  nim->nifti_type = NIFTI_FTYPE_NIFTI1_1;
  ASSERT_EQ(nifti_set_filenames(nim, nifti.c_str(), 0, 1), 0);
  nifti_image_write(nim);
  nifti_image_free(nim);

  auto mesh_in = [](const std::string& path, World world) {
    const Scene scene = load_input(path, InputOptions{.world = world});
    return std::pair{scene.world, create_mesh(scene)};
  };
  const auto [nrrd_frame, from_nrrd] = mesh_in(nrrd, World::ras);
  const auto [nifti_frame, from_nifti] = mesh_in(nifti, World::ras);
  EXPECT_EQ(nrrd_frame, "RAS (converted from the file's LPS)");
  EXPECT_EQ(nifti_frame, "RAS (the file's)");
  ASSERT_EQ(from_nrrd.num_triangles(), from_nifti.num_triangles());
  ASSERT_GT(from_nrrd.num_triangles(), 0u);
  auto sorted_points = [](const NodeMesh& m) {
    std::vector<std::array<double, 3>> p;
    for (const Vec3& x : m.points) p.push_back({x.x(), x.y(), x.z()});
    std::sort(p.begin(), p.end());
    return p;
  };
  const auto a = sorted_points(from_nrrd), b = sorted_points(from_nifti);
  ASSERT_EQ(a.size(), b.size());
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[i][size_t(c)] - b[i][size_t(c)]));
  EXPECT_LT(worst, 1e-9);
  // The LPS file's own frame is the mirror image: x and y change sign, so
  // the voxel centres span [10, 25] in LPS x and [-25, -10] in RAS x.
  const auto [own_frame, own] = mesh_in(nrrd, World::file);
  EXPECT_EQ(own_frame, "LPS (the file's)");
  EXPECT_NEAR(own.domain.min.x(), 10, 1e-9);
  EXPECT_NEAR(from_nrrd.domain.min.x(), -25, 1e-9);
  EXPECT_NEAR(own.domain.min.y(), 20, 1e-9);
  EXPECT_NEAR(from_nrrd.domain.min.y(), -35, 1e-9);
  EXPECT_NEAR(own.domain.min.z(), from_nrrd.domain.min.z(), 1e-9);
  // A file that names no frame cannot be converted.
  const std::string plain = write_nrrd("noframe.nrrd", "type: uchar\ndimension: 3\nsizes: 16 16 16\n", lps);
  const std::string why = refusal([&] { load_input(plain, InputOptions{.world = World::lps}); });
  EXPECT_NE(why.find("--world lps: the file does not say which anatomical frame"), std::string::npos) << why;
}
