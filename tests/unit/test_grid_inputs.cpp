// Tests of load_input on distance grids (one file with a component per phase,
// or one file per phase through a scene's "grid" phases) and labelled point
// clouds: the phases they make, the same mesh either way, and errors that name
// the scene, the phase and the file.
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/input.hpp"

#include "nrrd_file.hpp"
#include "sphere_volume.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace vm;

using test::temp_path;
using test::write_nrrd;
using namespace test::sphere_volume;

/// Three distance components per voxel of the 32^3 volume, interleaved: the
/// outside (0), a sphere, and the same sphere beyond i = 15.4.
std::vector<float> distance_components() {
  std::vector<float> d;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double r = (Vec3(i, j, k) - centre_vox).norm();
        d.push_back(0.f);                                      // outside
        d.push_back(float(radius_vox - r));                    // sphere, i <= 15
        d.push_back(float(radius_vox - r - (15.4 - i > 0 ? 15.4 - i : 0))); // the same sphere, beyond i = 15.4
      }
  return d;
}

const std::string components_header = "type: float\ndimension: 4\nsizes: 3 32 32 32\nkinds: vector domain domain domain\n";

// A 3-component float NRRD, components first: one phase per component.
TEST(DistanceGrid, components_are_phases) {
  const std::vector<float> d = distance_components();
  const Scene scene = load_input(write_nrrd("dist.nrrd", components_header, d));
  EXPECT_EQ(scene.field->num_phases(), 3);
  const NodeMesh mesh = create(scene);
  EXPECT_TRUE(validate(mesh).ok());
  EXPECT_THROW(load_input(write_nrrd("dist4.nrrd", "type: float\ndimension: 4\nsizes: 32 32 32 3\nkinds: domain domain domain vector\n", d)), InvalidInput);
}

// One file per phase, as level-set codes write them: the same geometry as the
// sphere volume, voxels 0.5 apart from (1, 2, 3).
std::string geometry(const std::string& directions = "(0.5,0,0) (0,0.5,0) (0,0,0.5)", const std::string& origin = "(1,2,3)") {
  return "space: left-posterior-superior\nspace directions: " + directions + "\nspace origin: " + origin + "\n";
}

/// Writes component c of distance_components() as a scalar float NRRD.
std::string write_phase_file(const std::string& name, int c, const std::string& space = geometry()) {
  const std::vector<float> all = distance_components();
  std::vector<float> one;
  for (size_t v = 0; v < all.size() / 3; ++v) one.push_back(all[3 * v + size_t(c)]);
  return write_nrrd(name, "type: float\ndimension: 3\nsizes: 32 32 32\n" + space, one);
}

/// Writes a scene with these phases (a JSON array) next to the NRRD files.
std::string write_scene(const std::string& name, const std::string& phases, const std::string& more = "") {
  const std::string path = temp_path(name);
  std::ofstream(path) << "{" << more << "\"phases\": " << phases << "}\n";
  return path;
}

std::string grid_phase(const std::string& file, const std::string& more = "") {
  return "{\"kind\": \"grid\", \"file\": \"" + file + "\"" + more + "}";
}

TEST(GridPhases, one_file_per_phase_meshes_as_one_multi_component_file) {
  const std::string all = write_nrrd("gp_all.nrrd",
                                     components_header + geometry("none (0.5,0,0) (0,0.5,0) (0,0,0.5)"),
                                     distance_components());
  for (int c = 0; c < 3; ++c) write_phase_file("gp" + std::to_string(c) + ".nrrd", c);
  const Scene multi = load_input(all);
  // Relative names are found next to the scene; an absolute one is taken as it is.
  const Scene files = load_input(write_scene("gp.json", "[" + grid_phase("vm_test_input_gp0.nrrd") + ", " +
                                                            grid_phase("vm_test_input_gp1.nrrd") + ", " +
                                                            grid_phase(temp_path("gp2.nrrd")) + "]"));
  // Closed-form and grid phases together: the outside is 0 in both.
  const Scene mixed = load_input(write_scene("gp_mixed.json", "[{\"kind\": \"constant\", \"value\": 0}, " +
                                                                  grid_phase("vm_test_input_gp_all.nrrd", ", \"component\": 1") + ", " +
                                                                  grid_phase("vm_test_input_gp_all.nrrd", ", \"component\": 2") + "]"));
  const NodeMesh expected = create(multi);
  ASSERT_GT(expected.num_triangles(), 1000u);
  for (const Scene* scene : {&files, &mixed}) {
    EXPECT_EQ(scene->grid.cells, multi.grid.cells);
    EXPECT_EQ(scene->grid.domain.min, multi.grid.domain.min);
    EXPECT_EQ(scene->grid.domain.max, multi.grid.domain.max);
    const NodeMesh mesh = create(*scene);
    EXPECT_EQ(mesh.points, expected.points);
    EXPECT_EQ(mesh.triangles, expected.triangles);
    EXPECT_EQ(mesh.pairs, expected.pairs);
    EXPECT_TRUE(validate(mesh).ok());
  }
  // A domain inside the voxels (centres +- half a voxel) and a coarser grid are the scene's to choose.
  const Scene part = load_input(write_scene("gp_part.json", "[" + grid_phase("vm_test_input_gp0.nrrd") + ", " +
                                                                grid_phase("vm_test_input_gp1.nrrd") + "]",
                                            "\"domain\": {\"min\": [0.75, 1.75, 2.75], \"max\": [9, 10, 11]}, \"grid\": 16, "));
  EXPECT_EQ(part.grid.cells[0], 16);
  EXPECT_TRUE(validate(create(part)).ok());
}

TEST(GridPhases, errors_name_the_scene_and_the_phase) {
  write_phase_file("gp0.nrrd", 0);
  write_nrrd("gp_labels.nrrd", sphere_header, sphere_labels(7));
  write_nrrd("gp_short.nrrd", "type: float\ndimension: 3\nsizes: 32 32 16\n", std::vector<float>(32 * 32 * 16));
  write_phase_file("gp_spacing.nrrd", 1, geometry("(0.25,0,0) (0,0.5,0) (0,0,0.5)"));
  write_phase_file("gp_origin.nrrd", 1, geometry("(0.5,0,0) (0,0.5,0) (0,0,0.5)", "(1,2,4)"));
  write_phase_file("gp_flipped.nrrd", 1, geometry("(-0.5,0,0) (0,0.5,0) (0,0,0.5)"));
  // Phase 1 beside a good phase 0; the message must start with the scene and the phase.
  const std::string scene = temp_path("gp_err.json");
  auto error = [&](const std::string& phase1, const std::string& more = "") {
    write_scene("gp_err.json", "[" + grid_phase("vm_test_input_gp0.nrrd") + ", " + phase1 + "]", more);
    return error_of([&] { load_input(scene); });
  };
  EXPECT_THROW(load_input(write_scene("gp_err.json", "[" + grid_phase("vm_test_input_gp0.nrrd") + ", " +
                                                         grid_phase("vm_test_input_nothere.nrrd") + "]")),
               IoError);
  EXPECT_EQ(error(grid_phase("vm_test_input_nothere.nrrd")),
            scene + ": phase 1: " + temp_path("nothere.nrrd") + ": cannot open (No such file or directory)");
  EXPECT_EQ(error(grid_phase("vm_test_input_gp0.nrrd", ", \"component\": 1")),
            scene + ": phase 1: 'component' 1 is out of range: 'vm_test_input_gp0.nrrd' has 1 component(s), 0 to 0");
  EXPECT_EQ(error(grid_phase("vm_test_input_gp_labels.nrrd")),
            scene + ": phase 1: 'vm_test_input_gp_labels.nrrd' holds integers (a label volume?); a grid phase needs real values");
  const std::string other = scene + ": phase 1: 'vm_test_input_gp_";
  const std::string grid0 = " is not on the grid of 'vm_test_input_gp0.nrrd' (phase 0): ";
  EXPECT_EQ(error(grid_phase("vm_test_input_gp_short.nrrd")),
            other + "short.nrrd'" + grid0 + "sizes 32x32x16 vs 32x32x32; all grid phases must share one voxel grid");
  EXPECT_EQ(error(grid_phase("vm_test_input_gp_spacing.nrrd")),
            other + "spacing.nrrd'" + grid0 + "spacing [0.25, 0.5, 0.5] vs [0.5, 0.5, 0.5]; all grid phases must share one voxel grid");
  EXPECT_EQ(error(grid_phase("vm_test_input_gp_origin.nrrd")),
            other + "origin.nrrd'" + grid0 + "origin [1, 2, 4] vs [1, 2, 3] (after applying each file's direction); all grid phases must share one voxel grid");
  // A flipped axis moves every voxel but one: a different grid in world coordinates.
  EXPECT_NE(error(grid_phase("vm_test_input_gp_flipped.nrrd")).find("origin [-14.5, 2, 3]"), std::string::npos);
  EXPECT_EQ(error(grid_phase("vm_test_input_gp0.nrrd"), "\"domain\": {\"min\": [0, 0, 0], \"max\": [10, 10, 10]}, "),
            scene + ": domain: reaches beyond the voxels of the grid phases along x (they cover [0.75, 1.75, 2.75] to "
                    "[16.75, 17.75, 18.75]); give a domain inside them, or none to mesh all of them");
  EXPECT_EQ(error(grid_phase("")), scene + ": phase 1: 'file' must not be empty");
  EXPECT_EQ(error("{\"kind\": \"grid\", \"file\": \"x.nrrd\", \"radius\": 1}"),
            scene + ": phase 1: unknown key 'radius' (expected kind, name, file, component)");
}

// Eq. 7: two clusters of points; the surface lies halfway between them.
TEST(PointCloud, surface_lies_halfway_between_labelled_points) {
  const std::string path = temp_path("cloud.xyz");
  {
    std::ofstream out(path);
    out << "# x y z label\n";
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) out << 0.0 << " " << i * 0.2 << " " << j * 0.2 << " 4\n" << 1.0 << " " << i * 0.2 << " " << j * 0.2 << " 11\n";
  }
  const Scene scene = load_input(path);
  EXPECT_EQ(labels_of(*scene.field), (std::vector<int32_t>{4, 11}));
  NodeMesh mesh = create(scene);
  EXPECT_TRUE(validate(mesh).ok());
  improve(mesh, *scene.field);
  EXPECT_TRUE(validate(mesh).ok());
  for (const Vec3& p : mesh.points) EXPECT_NEAR(p.x(), 0.5, 1e-6);

  std::ofstream(temp_path("bad.xyz")) << "0 0 0 1\n0 0 zero 2\n";
  try {
    load_input(temp_path("bad.xyz"));
    FAIL() << "a bad line was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
  }
}

} // namespace
