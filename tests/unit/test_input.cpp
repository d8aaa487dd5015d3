// Tests of load_input on label volumes written by the tests themselves: the
// right phases and labels, valid meshes before and after improvement, sub-voxel
// accuracy against the surface the labels were rasterised from, label options,
// labels saved as reals and voxel sizes. (Distance grids and point clouds:
// test_grid_inputs.cpp.)
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/io/volume.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include "fields/top_k_grid_field.hpp"
#include "nrrd_file.hpp"
#include "sphere_volume.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace {

using namespace vm;

using test::temp_path;
using test::write_nrrd;
using namespace test::sphere_volume;

TEST(Nrrd, reads_geometry_and_labels) {
  const io::Volume v = io::read_volume(write_nrrd("geometry.nrrd", sphere_header, sphere_labels(7)));
  EXPECT_TRUE(v.integer);
  EXPECT_EQ(v.size, (std::array<int64_t, 3>{32, 32, 32}));
  EXPECT_DOUBLE_EQ(v.spacing.x(), 0.5);
  EXPECT_EQ(v.origin, origin);
  EXPECT_EQ(v.labels.size(), size_t(n * n * n));
}

TEST(Nrrd, refuses_truncated_data_and_2d_images) {
  std::vector<uint16_t> labels = sphere_labels(7);
  labels.resize(100);
  EXPECT_THROW(io::read_volume(write_nrrd("short.nrrd", sphere_header, labels)), InvalidInput);
  EXPECT_THROW(io::read_volume(write_nrrd("flat.nrrd", "type: uchar\ndimension: 2\nsizes: 2 2\n", std::vector<uint8_t>(4))),
               InvalidInput);
  EXPECT_THROW(io::read_volume(temp_path("missing.nrrd")), IoError);
  EXPECT_THROW(io::read_volume(temp_path("unknown.vol")), InvalidInput); // not a volume extension
}

// Smoothed indicators: one phase per label with its label value, a valid mesh,
// within a fraction of a voxel of the sphere the labels came from; still valid
// and closer after improvement.
TEST(LabelVolume, sphere_is_reproduced_below_voxel_size) {
  const Scene scene = load_input(write_nrrd("sphere.nrrd", sphere_header, sphere_labels(7)));
  EXPECT_EQ(labels_of(*scene.field), (std::vector<int32_t>{0, 7}));
  EXPECT_EQ(scene.field->phase_name(0), "background");
  NodeMesh mesh = create(scene);
  EXPECT_TRUE(validate(mesh).ok());
  const double created = sphere_error_voxels(mesh);
  EXPECT_LT(created, 0.5);
  improve(mesh, *scene.field);
  EXPECT_TRUE(validate(mesh).ok());
  const double improved = sphere_error_voxels(mesh);
  EXPECT_LT(improved, 0.35);
  std::printf("sphere, smoothed indicator: max error %.3f voxels created, %.3f improved\n", created, improved);
}

TEST(LabelVolume, signed_distance_sphere_is_reproduced_below_voxel_size) {
  InputOptions o;
  o.label_function = LabelFunction::signed_distance;
  const Scene scene = load_input(write_nrrd("sphere_sd.nrrd", sphere_header, sphere_labels(7)), o);
  NodeMesh mesh = create(scene);
  EXPECT_TRUE(validate(mesh).ok());
  improve(mesh, *scene.field);
  EXPECT_TRUE(validate(mesh).ok());
  const double improved = sphere_error_voxels(mesh);
  EXPECT_LT(improved, 0.5);
  std::printf("sphere, signed distance: max error %.3f voxels improved\n", improved);
}

// Three labels (a sphere cut in two halves plus background): a triple curve.
TEST(LabelVolume, three_labels_and_label_options) {
  const std::string path = write_nrrd("halves.nrrd", sphere_header, sphere_labels(3, [](int i, int j, int k) {
    return (Vec3(i, j, k) - centre_vox).norm() < radius_vox && i > 15 ? 9 : -1;
  }));
  const Scene scene = load_input(path);
  EXPECT_EQ(labels_of(*scene.field), (std::vector<int32_t>{0, 3, 9}));
  NodeMesh mesh = create(scene);
  EXPECT_TRUE(validate(mesh).ok());
  improve(mesh, *scene.field);
  EXPECT_TRUE(validate(mesh).ok());

  InputOptions drop;
  drop.drop_labels = {9};
  EXPECT_EQ(labels_of(*load_input(path, drop).field), (std::vector<int32_t>{0, 3}));
  InputOptions merge;
  merge.merge_labels = {{9, 3}};
  EXPECT_EQ(labels_of(*load_input(path, merge).field), (std::vector<int32_t>{0, 3}));
  // The background is far wider than the smoothing: left to the labels, it would be arbitrary.
  EXPECT_THROW(load_input(path, InputOptions{.no_background = true}), InvalidInput);
  InputOptions bg3;
  bg3.background = 3;
  EXPECT_EQ(load_input(path, bg3).field->phase_name(1), "background");
  EXPECT_TRUE(load_input(path, bg3).notes.empty());
  // A background label no voxel has is said: a mistyped one names no phase.
  InputOptions bg5;
  bg5.background = 5;
  EXPECT_EQ(load_input(path, bg5).notes, (std::vector<std::string>{"--background 5: no voxel has this label, so no "
                                                                   "phase is the background"}));
  bg5.drop_labels = {9}; // label 9's voxels become background: no note
  EXPECT_TRUE(load_input(path, bg5).notes.empty());
  EXPECT_TRUE(load_input(path).notes.empty());
  InputOptions absent;
  absent.drop_labels = {4};
  EXPECT_THROW(load_input(path, absent), InvalidInput);
}

// Labels saved as reals (float NIfTI from ITK filters and deep-learning tools):
// one real value per voxel, every one whole, is the label volume of those
// integers, the same mesh; a value that is no label is refused naming its voxel.
TEST(LabelVolume, reals_that_are_all_whole_numbers_are_labels) {
  const std::vector<uint16_t> labels = sphere_labels(7);
  const std::string as_reals = "type: double\n" + sphere_header.substr(sphere_header.find('\n') + 1);
  std::vector<double> reals(labels.begin(), labels.end());
  const Scene from_integers = load_input(write_nrrd("sphere_u16.nrrd", sphere_header, labels));
  const Scene from_reals = load_input(write_nrrd("sphere_f64.nrrd", as_reals, reals));
  EXPECT_EQ(labels_of(*from_reals.field), (std::vector<int32_t>{0, 7}));
  EXPECT_EQ(from_reals.notes,
            (std::vector<std::string>{"voxels stored as reals, every one a whole number: read as labels"}));
  const NodeMesh a = create(from_integers), b = create(from_reals);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.triangles, b.triangles);

  reals[size_t(3 + n * (4 + n * 5))] = 6.5; // voxel (3, 4, 5): linear interpolation's work
  const std::string blurred = write_nrrd("sphere_blurred.nrrd", as_reals, reals);
  EXPECT_NE(error_of([&] { load_input(blurred); }).find("voxel (3, 4, 5) holds 6.5, not a label"), std::string::npos);
  // Beyond 2^24 a float no longer tells neighbouring labels apart.
  reals[size_t(3 + n * (4 + n * 5))] = 16777218;
  const std::string wide = write_nrrd("sphere_wide.nrrd", as_reals, reals);
  EXPECT_NE(error_of([&] { load_input(wide); }).find("holds 16777218, not a label"), std::string::npos);
}

// A file that says no voxel size (a NRRD without spacings, a TIFF not written
// by ImageJ) has unit voxels, and says so; voxel_size (--voxel-size) gives the
// voxels theirs, along the file's axes: the mesh of the file that states them.
TEST(LabelVolume, voxel_size_stands_in_for_the_files) {
  const std::vector<uint16_t> labels = sphere_labels(7);
  const std::string bare = write_nrrd("sphere_bare.nrrd", "type: ushort\ndimension: 3\nsizes: 32 32 32\n", labels);
  const std::string sized = write_nrrd("sphere_sized.nrrd", "type: ushort\ndimension: 3\nsizes: 32 32 32\n"
                                                            "spacings: 0.5 0.5 0.55\n", labels);
  EXPECT_EQ(load_input(bare).notes, (std::vector<std::string>{"the file says no voxel size along some axis: voxels "
                                                              "of 1 x 1 x 1 (--voxel-size gives them theirs)"}));
  EXPECT_TRUE(load_input(sized).notes.empty());
  InputOptions given;
  given.voxel_size = Vec3(0.5, 0.5, 0.55);
  const Scene from_option = load_input(bare, given);
  EXPECT_EQ(from_option.notes,
            (std::vector<std::string>{"voxels of 0.5 x 0.5 x 0.55 (--voxel-size; the file's: none)"}));
  const NodeMesh a = create(from_option), b = create(load_input(sized));
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.triangles, b.triangles);
  given.voxel_size = Vec3(0.5, 0, 1);
  EXPECT_NE(error_of([&] { load_input(bare, given); }).find("--voxel-size: every size must be above 0"),
            std::string::npos);
}

// Grain maps: unindexed voxels (label 0) between two grains are filled by the
// grains with --no-background, meeting halfway.
TEST(LabelVolume, no_background_fills_gaps_between_grains) {
  std::vector<uint16_t> v;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v.push_back(uint16_t(i < 15 ? 1 : i > 16 ? 2 : 0)); // gap: i = 15, 16
  InputOptions o;
  o.no_background = true;
  const Scene scene = load_input(write_nrrd("grains.nrrd", sphere_header, v), o);
  EXPECT_EQ(labels_of(*scene.field), (std::vector<int32_t>{1, 2}));
  NodeMesh mesh = create(scene);
  ASSERT_FALSE(mesh.points.empty());
  improve(mesh, *scene.field); // projection puts the nodes on the field's own surface
  for (const Vec3& p : mesh.points) EXPECT_NEAR((p.x() - origin.x()) / voxel, 15.5, 0.05);
}

// Every phase's voxels are counted, and each small phase is named with the
// phase its voxels touch most, wherever in the volume it lies: a 48^3 volume
// (the background is then no small phase, so only the slices of the small ones
// are searched) with a one-voxel label in slice 40 and a 2^3 label inside a
// block of another in slices 18-23.
TEST(LabelVolume, small_labels_are_counted_and_their_neighbours_found_in_any_slice) {
  constexpr int m = 48;
  std::vector<uint16_t> v;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        auto within = [&](int lo, int hi) { return i >= lo && i < hi && j >= lo && j < hi && k >= lo && k < hi; };
        v.push_back(uint16_t(within(20, 22) ? 5 : within(18, 24) ? 7 : i == 30 && j == 9 && k == 40 ? 6 : 0));
      }
  const Scene scene = load_input(write_nrrd("small.nrrd", "type: ushort\ndimension: 3\nsizes: 48 48 48\n", v));
  EXPECT_EQ(labels_of(*scene.field), (std::vector<int32_t>{0, 5, 6, 7}));
  EXPECT_EQ(scene.phase_voxels, (std::vector<int64_t>{m * m * m - 217, 8, 1, 208}));
  // The background has more voxels than a small phase may; 5 lies in 7, 6 and 7 in the background.
  EXPECT_EQ(scene.phase_around, (std::vector<int32_t>{-1, 3, 0, 0}));
}

// A few hundred labels: the field keeps K per voxel whatever the label count.
// Its store holds as much as that of 16 labels in the same blocks (every block's
// neighbours differ in both), and O(voxels x K) bytes. (Time is measured in bench/.)
TEST(LabelVolume, many_labels_stay_cheap) {
  std::vector<uint16_t> many, few;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int block = i / 4 + 8 * (j / 4) + 64 * (k / 8); // 8x8x4 = 256 blocks
        many.push_back(uint16_t(1 + block));
        few.push_back(uint16_t(1 + (i / 4 + 3 * (j / 4) + 5 * (k / 8)) % 16)); // neighbouring blocks differ
      }
  const Scene scene = load_input(write_nrrd("blocks.nrrd", sphere_header, many));
  EXPECT_EQ(scene.field->num_phases(), 256);
  const NodeMesh mesh = create(scene);
  EXPECT_TRUE(validate(mesh).ok());
  const Scene sixteen = load_input(write_nrrd("few.nrrd", sphere_header, few));
  EXPECT_EQ(sixteen.field->num_phases(), 16);
  const auto* store_many = dynamic_cast<const detail::TopKGridField*>(scene.field.get());
  const auto* store_few = dynamic_cast<const detail::TopKGridField*>(sixteen.field.get());
  ASSERT_TRUE(store_many && store_few);
  const size_t nodes = size_t(scene.grid.node_count()), k = size_t(InputOptions{}.top_k);
  EXPECT_LE(store_many->bytes(), nodes * (k * 6 + 4 + 1));
  EXPECT_LE(double(store_many->bytes()), 1.05 * double(store_few->bytes())) << store_few->bytes();
}

// Values are computed only near label changes; a node whose voxels within the
// smoothing radius all share its label holds that label at the same value
// whether it was computed or is implicit (deep inside), so the field has no seam.
TEST(LabelVolume, nodes_deep_inside_hold_one_value_computed_or_not) {
  for (const bool signed_distance : {false, true}) {
    InputOptions o;
    if (signed_distance) o.label_function = LabelFunction::signed_distance;
    const std::vector<uint16_t> labels = sphere_labels(7);
    const Scene scene = load_input(write_nrrd("deep.nrrd", sphere_header, labels), o);
    const int reach = signed_distance ? 4 : 3; // 3 sigma, or the band plus one voxel
    double lo = INFINITY, hi = -INFINITY;
    size_t deep = 0;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const uint16_t label = labels[size_t(i + n * (j + n * k))];
          bool alone = true;
          for (int dk = -reach; dk <= reach && alone; ++dk)
            for (int dj = -reach; dj <= reach && alone; ++dj)
              for (int di = -reach; di <= reach && alone; ++di) {
                const int x = std::clamp(i + di, 0, n - 1), y = std::clamp(j + dj, 0, n - 1), z = std::clamp(k + dk, 0, n - 1);
                alone = labels[size_t(x + n * (y + n * z))] == label;
              }
          if (!alone) continue;
          const double v = scene.field->value(label ? 1 : 0, world(Vec3(i, j, k)));
          lo = std::min(lo, v), hi = std::max(hi, v), ++deep;
        }
    EXPECT_GT(deep, 1000u);
    EXPECT_NEAR(lo, hi, 1e-6 * std::abs(hi)) << (signed_distance ? "signed distance" : "smoothed indicator");
  }
}

// Where the field says a box has one set of top values (create then samples a
// run of lattice nodes once), every point of it has them, bit for bit; it says
// so deep inside and outside the sphere, never across its surface.
TEST(LabelVolume, same_top_values_hold_at_every_point_of_the_box) {
  for (const bool signed_distance : {false, true}) {
    InputOptions o;
    if (signed_distance) o.label_function = LabelFunction::signed_distance;
    const Scene scene = load_input(write_nrrd("same.nrrd", sphere_header, sphere_labels(7)), o);
    const PhaseField& field = *scene.field;
    const size_t k = size_t(std::min(o.top_k, field.num_phases()));
    auto top = [&](const Vec3& x) {
      std::vector<int32_t> ids(k);
      std::vector<double> vals(k);
      field.top_values(x, ids, vals);
      return std::pair{ids, vals};
    };
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-2, n + 1), length(0, 12);
    size_t same = 0, across = 0;
    for (int b = 0; b < 3000; ++b) {
      const Vec3 lo_vox(u(rng), u(rng), u(rng));
      const Vec3 hi_vox = lo_vox + Vec3(length(rng), b % 3 ? 0 : length(rng) / 4, b % 5 ? 0 : length(rng) / 4);
      const bool inside_lo = (lo_vox - centre_vox).norm() < radius_vox, inside_hi = (hi_vox - centre_vox).norm() < radius_vox;
      if (!field.same_top_values(world(lo_vox), world(hi_vox))) continue;
      ++same;
      across += inside_lo != inside_hi;
      const auto first = top(world(lo_vox));
      for (int t = 1; t <= 8; ++t)
        ASSERT_EQ(top(world(lo_vox + (hi_vox - lo_vox) * (t / 8.0))), first) << lo_vox.transpose() << " to " << hi_vox.transpose();
    }
    EXPECT_GT(same, 300u) << "deep inside and outside, boxes are one phase's";
    EXPECT_EQ(across, 0u) << "a box across the surface has two phases";
    EXPECT_FALSE(field.same_top_values(world(centre_vox), world(centre_vox + Vec3(radius_vox, 0, 0))));
  }
}

// The phase functions are computed in parallel blocks: any thread count gives the same values.
TEST(LabelVolume, phase_functions_do_not_depend_on_the_thread_count) {
  const std::string path = write_nrrd("threads.nrrd", sphere_header, sphere_labels(3, [](int i, int j, int k) {
    return (Vec3(i, j, k) - centre_vox).norm() < radius_vox && i > 15 ? 9 : (i + j) % 11 == 0 ? 5 : -1;
  }));
  auto sample = [&](int threads, bool signed_distance) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    InputOptions o;
    if (signed_distance) o.label_function = LabelFunction::signed_distance;
    const Scene scene = load_input(path, o);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, n);
    std::vector<double> out;
    for (int t = 0; t < 2000; ++t) {
      const Vec3 x = world(Vec3(u(rng), u(rng), u(rng)));
      for (int p = 0; p < scene.field->num_phases(); ++p) {
        out.push_back(scene.field->value(p, x));
        const Vec3 g = scene.field->gradient(p, x);
        out.insert(out.end(), {g.x(), g.y(), g.z()});
      }
    }
    return out;
  };
  for (const bool sd : {false, true}) EXPECT_EQ(sample(1, sd), sample(2, sd)) << (sd ? "signed distance" : "indicator");
}

// --voxels-per-cell: the same box in nearly cubic cells of about F voxels, an even count per axis.
TEST(LabelVolume, voxels_per_cell_sets_a_coarser_grid) {
  const std::string path = write_nrrd("coarse.nrrd", sphere_header, sphere_labels(7));
  const Scene fine = load_input(path);
  InputOptions o;
  o.voxels_per_cell = 2;
  const Scene coarse = load_input(path, o);
  EXPECT_EQ(coarse.grid.cells, (std::array<int, 3>{16, 16, 16})); // 31 voxel steps / 2, rounded to even
  EXPECT_EQ(coarse.grid.domain.min, fine.grid.domain.min);
  EXPECT_NEAR(coarse.grid.domain.max.x(), origin.x() + 31 * voxel, 1e-12);
  const NodeMesh mesh = create(coarse);
  EXPECT_TRUE(validate(mesh).ok());
  EXPECT_LT(mesh.num_triangles(), create(fine).num_triangles() / 3);
  o.voxels_per_cell = 0.5;
  EXPECT_THROW(load_input(path, o), InvalidInput);
}

// Slices thicker than their pixels: by default cubic cells of the voxels'
// volume (about as many cells as voxels), said in a note; the voxel grid with
// --voxels-per-cell 1, with --voxel-faithful, and for voxels nearly cubic.
TEST(LabelVolume, flat_voxels_are_meshed_on_cubic_cells_by_default) {
  auto header = [](double dz) {
    return "type: ushort\ndimension: 3\nsizes: 32 32 32\nspace: left-posterior-superior\n"
           "space directions: (0.5,0,0) (0,0.5,0) (0,0," + std::to_string(dz) + ")\nspace origin: (1,2,3)\n";
  };
  const std::string flat = write_nrrd("flat.nrrd", header(1.2), sphere_labels(7));
  const Scene cubic = load_input(flat);
  const Vec3 h = cubic.grid.spacing();
  EXPECT_LT(h.maxCoeff() / h.minCoeff(), 1.05) << h.transpose();
  EXPECT_NEAR(h.x(), std::cbrt(0.5 * 0.5 * 1.2), 0.03);
  const double cells = double(cubic.grid.cells[0]) * cubic.grid.cells[1] * cubic.grid.cells[2];
  EXPECT_NEAR(cells / (32.0 * 32 * 32), 1.0, 0.15);
  ASSERT_EQ(cubic.notes.size(), 1u);
  EXPECT_NE(cubic.notes[0].find("flat"), std::string::npos) << cubic.notes[0];
  EXPECT_TRUE(validate(create(cubic)).ok());
  const std::array<int, 3> voxel_grid{32, 32, 32}; // 31 voxel steps, one more for an even count
  InputOptions o;
  o.voxels_per_cell = 1;
  EXPECT_EQ(load_input(flat, o).grid.cells, voxel_grid);
  EXPECT_TRUE(load_input(flat, o).notes.empty());
  InputOptions faithful;
  faithful.voxel_faithful = true;
  EXPECT_EQ(load_input(flat, faithful).grid.cells, voxel_grid);
  EXPECT_EQ(load_input(write_nrrd("nearly.nrrd", header(0.55), sphere_labels(7))).grid.cells, voxel_grid);
}

TEST(LabelVolume, axis_flips_are_honoured_and_oblique_directions_refused) {
  const std::string flipped = "type: ushort\ndimension: 3\nsizes: 32 32 32\nspace: left-posterior-superior\n"
                              "space directions: (-0.5,0,0) (0,0,0.5) (0,0.5,0)\nspace origin: (1,2,3)\n";
  const Scene scene = load_input(write_nrrd("flipped.nrrd", flipped, sphere_labels(7)));
  EXPECT_NEAR(scene.grid.domain.min.x(), 1 - 0.5 * 31, 1e-12) << "x runs backwards from the origin";
  const std::string oblique = "type: ushort\ndimension: 3\nsizes: 32 32 32\nspace: left-posterior-superior\n"
                              "space directions: (0.5,0.1,0) (0,0.5,0) (0,0,0.5)\n";
  const std::string path = write_nrrd("oblique.nrrd", oblique, sphere_labels(7));
  try {
    load_input(path);
    FAIL() << "an oblique direction was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--ignore-direction"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(load_input(path, InputOptions{.ignore_direction = true}));
}

} // namespace
