// DREAM.3D files: a grain map written here through the HDF5 C library in both
// layouts (DREAM.3D 6's SIMPL and DREAM3D-NX 7's), read back as a label volume
// of grains named after their phase, by its name where the file names the
// phases; then files that are not grain maps, and malformed phase names.

#include "nrrd_file.hpp"
#include "refusal.hpp"

#include "voronoimesh/voronoimesh.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

using namespace vm;
using vm::test::refusal;
using vm::test::temp_path;

namespace {

constexpr int nx = 12, ny = 10, nz = 8;

/// Three grains in slabs along x: 1 below x = 4, 2 up to x = 8, 3 beyond.
std::vector<int32_t> grain_ids() {
  std::vector<int32_t> ids;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) ids.push_back(i < 4 ? 1 : i < 8 ? 2 : 3);
  return ids;
}

/// Writes a dataset of `values` shaped `dims` under `parent`.
template <class T>
void dataset(hid_t parent, const char* name, hid_t type, const std::vector<hsize_t>& dims, const std::vector<T>& values) {
  const hid_t space = H5Screate_simple(int(dims.size()), dims.data(), nullptr);
  const hid_t d = H5Dcreate2(parent, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Dclose(d);
  H5Sclose(space);
}

/// Writes a vector attribute of 3 values on `object`.
template <class T>
void attribute(hid_t object, const char* name, hid_t type, const std::vector<T>& values) {
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t a = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(H5Awrite(a, type, values.data()), 0);
  H5Aclose(a);
  H5Sclose(space);
}

hid_t group(hid_t parent, const char* name) { return H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT); }

/// Writes a list of strings at `where` (a path from `parent`): variable length
/// as DREAM.3D writes them, or fixed length, null-padded and UTF-8 (so both
/// character sets are read).
void strings(hid_t parent, const char* where, const std::vector<std::string>& values, bool variable = true) {
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr), type = H5Tcopy(H5T_C_S1);
  size_t width = 1;
  for (const std::string& v : values) width = std::max(width, v.size());
  H5Tset_size(type, variable ? H5T_VARIABLE : width);
  if (!variable) {
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    H5Tset_cset(type, H5T_CSET_UTF8);
  }
  const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  const hid_t d = H5Dcreate2(parent, where, type, space, lcpl, H5P_DEFAULT, H5P_DEFAULT);
  std::vector<const char*> pointers;
  std::string packed;
  for (const std::string& v : values) {
    pointers.push_back(v.c_str());
    packed += v + std::string(width - v.size(), '\0');
  }
  ASSERT_GE(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, variable ? (const void*)pointers.data() : packed.data()), 0);
  H5Dclose(d);
  H5Pclose(lcpl);
  H5Tclose(type);
  H5Sclose(space);
}

/// Adds `values` at `where` to the file at `path`.
void add_strings(const std::string& path, const char* where, const std::vector<std::string>& values, bool variable = true) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  strings(file, where, values, variable);
  H5Fclose(file);
}

const std::vector<hsize_t> cell_shape{nz, ny, nx, 1}; // DREAM.3D: z slowest, x fastest, then components
const std::vector<int32_t> grain_phases{0, 1, 2, 1}; // by grain id; 0 is no grain

/// DREAM.3D 6.x: DataContainers/ImageDataContainer with _SIMPL_GEOMETRY datasets.
std::string write_simpl(const std::string& name) {
  const std::string path = temp_path(name);
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t containers = group(file, "DataContainers"), dc = group(containers, "ImageDataContainer");
  const hid_t geometry = group(dc, "_SIMPL_GEOMETRY");
  dataset(geometry, "DIMENSIONS", H5T_NATIVE_INT64, {3}, std::vector<int64_t>{nx, ny, nz});
  dataset(geometry, "ORIGIN", H5T_NATIVE_FLOAT, {3}, std::vector<float>{1, 2, 3});
  dataset(geometry, "SPACING", H5T_NATIVE_FLOAT, {3}, std::vector<float>{0.5f, 0.5f, 1});
  const hid_t cells = group(dc, "CellData");
  dataset(cells, "FeatureIds", H5T_NATIVE_INT32, cell_shape, grain_ids());
  // The cells' own phases, beside the grain ids: not the grains' phases.
  dataset(cells, "Phases", H5T_NATIVE_INT32, cell_shape, std::vector<int32_t>(nx * ny * nz, 7));
  const hid_t features = group(dc, "CellFeatureData");
  dataset(features, "Phases", H5T_NATIVE_INT32, {4, 1}, grain_phases);
  for (hid_t g : {features, cells, geometry, dc, containers}) H5Gclose(g);
  H5Fclose(file);
  return path;
}

/// DREAM3D-NX 7.x: DataStructure/<geometry> with attributes, attribute matrices in it.
std::string write_nx(const std::string& name) {
  const std::string path = temp_path(name);
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t root = group(file, "DataStructure"), geometry = group(root, "Image Geometry");
  attribute(geometry, "_DIMENSIONS", H5T_NATIVE_UINT64, std::vector<uint64_t>{nx, ny, nz});
  attribute(geometry, "_ORIGIN", H5T_NATIVE_FLOAT, std::vector<float>{1, 2, 3});
  attribute(geometry, "_SPACING", H5T_NATIVE_FLOAT, std::vector<float>{0.5f, 0.5f, 1});
  const hid_t cells = group(geometry, "Cell Data");
  dataset(cells, "FeatureIds", H5T_NATIVE_INT32, cell_shape, grain_ids());
  const hid_t features = group(geometry, "Cell Feature Data");
  dataset(features, "Phases", H5T_NATIVE_INT32, {4, 1}, grain_phases);
  for (hid_t g : {features, cells, geometry, root}) H5Gclose(g);
  H5Fclose(file);
  return path;
}

std::vector<std::string> names_of(const PhaseField& f) {
  std::vector<std::string> out;
  for (int p = 0; p < f.num_phases(); ++p) out.push_back(f.phase_name(p));
  return out;
}

} // namespace

TEST(Dream3d, both_layouts_read_as_grains_named_after_their_phase) {
  const std::vector<std::string> expected{"grain1-phase1", "grain2-phase2", "grain3-phase1"};
  NodeMesh meshes[2];
  int m = 0;
  for (const std::string& path : {write_simpl("grains6.dream3d"), write_nx("grains7.dream3d")}) {
    SCOPED_TRACE(path);
    const Scene scene = load_input(path);
    EXPECT_EQ(names_of(*scene.field), expected);
    EXPECT_EQ(scene.field->phase_label(1), 2);
    EXPECT_EQ(scene.phase_voxels, (std::vector<int64_t>{4 * ny * nz, 4 * ny * nz, 4 * ny * nz}));
    // The origin is the first cell's corner: its centre is half a cell further.
    EXPECT_NEAR(scene.grid.domain.min.x(), 1.25, 1e-6);
    EXPECT_NEAR(scene.grid.domain.min.y(), 2.25, 1e-6);
    EXPECT_NEAR(scene.grid.domain.min.z(), 3.5, 1e-6);
    meshes[m] = create_mesh(scene);
    EXPECT_TRUE(validate(meshes[m]).ok());
    EXPECT_EQ(meshes[m].phase_names, expected);
    // Grains are picked by name like Slicer's segments.
    EXPECT_EQ(names_of(*load_input(path, InputOptions{.drop_labels = {"grain2-phase2"}}).field),
              (std::vector<std::string>{"background", "grain1-phase1", "grain3-phase1"}));
    ++m;
  }
  EXPECT_EQ(meshes[0].points, meshes[1].points);
  EXPECT_EQ(meshes[0].triangles, meshes[1].triangles);
}

TEST(Dream3d, files_that_are_no_grain_map_are_refused_naming_the_file) {
  const std::string text = temp_path("text.dream3d");
  std::ofstream(text) << "not hdf5\n";
  EXPECT_NE(refusal([&] { load_input(text); }).find(text + ": not an HDF5 file"), std::string::npos);

  const std::string empty = temp_path("empty.dream3d");
  H5Fclose(H5Fcreate(empty.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  EXPECT_NE(refusal([&] { load_input(empty); }).find("has neither DataContainers (DREAM.3D 6) nor DataStructure"),
            std::string::npos);

  // A grain map shorter than its geometry says.
  const std::string short_map = temp_path("short.dream3d");
  const hid_t file = H5Fcreate(short_map.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t root = group(file, "DataStructure"), geometry = group(root, "Image");
  attribute(geometry, "_DIMENSIONS", H5T_NATIVE_UINT64, std::vector<uint64_t>{nx, ny, nz + 1});
  attribute(geometry, "_SPACING", H5T_NATIVE_FLOAT, std::vector<float>{1, 1, 1});
  const hid_t cells = group(geometry, "Cell Data");
  dataset(cells, "FeatureIds", H5T_NATIVE_INT32, cell_shape, grain_ids());
  for (hid_t g : {cells, geometry, root}) H5Gclose(g);
  H5Fclose(file);
  const std::string why = refusal([&] { load_input(short_map); });
  EXPECT_NE(why.find(short_map + ": DataStructure/Image/Cell Data/FeatureIds: holds 960 values for 1080 cells"),
            std::string::npos)
      << why;

  // The grains' phases with an absurd size (as a damaged file had): refused
  // before anything that size is allocated. Chunked, so the file stays small.
  const std::string huge = write_nx("huge.dream3d");
  const hid_t f = H5Fopen(huge.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(f, "DataStructure/Image Geometry/Cell Feature Data/Phases", H5P_DEFAULT), 0);
  const hsize_t dims[2] = {hsize_t(1) << 40, 1}, chunk[2] = {1024, 1};
  const hid_t space = H5Screate_simple(2, dims, nullptr), plist = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(plist, 2, chunk);
  H5Dclose(H5Dcreate2(f, "DataStructure/Image Geometry/Cell Feature Data/Phases", H5T_NATIVE_INT32, space, H5P_DEFAULT,
                      plist, H5P_DEFAULT));
  H5Pclose(plist);
  H5Sclose(space);
  H5Fclose(f);
  const std::string absurd = refusal([&] { load_input(huge); });
  EXPECT_NE(absurd.find("Cell Feature Data/Phases: has 1099511627776 entries for grain ids up to 3"), std::string::npos)
      << absurd;

  // An origin that is not finite (DREAM.3D's is read unchecked): refused where
  // the grid is made, not crashed on in create.
  const std::string nan_origin = write_nx("nan_origin.dream3d");
  const hid_t g = H5Fopen(nan_origin.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Adelete_by_name(g, "DataStructure/Image Geometry", "_ORIGIN", H5P_DEFAULT), 0);
  const hid_t geometry_again = H5Gopen2(g, "DataStructure/Image Geometry", H5P_DEFAULT);
  attribute(geometry_again, "_ORIGIN", H5T_NATIVE_FLOAT, std::vector<float>{std::nanf(""), 2, 3});
  H5Gclose(geometry_again);
  H5Fclose(g);
  const std::string not_finite = refusal([&] { load_input(nan_origin); });
  EXPECT_NE(not_finite.find(nan_origin + ": the domain along x is not finite"), std::string::npos) << not_finite;
}

TEST(Dream3d, grains_are_named_after_the_names_the_file_gives_their_phases) {
  const std::vector<std::string> names{"Invalid Phase", "Austenite", "Ferrite"};
  const std::vector<std::string> expected{"grain1-Austenite", "grain2-Ferrite", "grain3-Austenite"};
  // DREAM.3D 6: CellEnsembleData/PhaseName, variable-length strings.
  const std::string simpl = write_simpl("named6.dream3d");
  add_strings(simpl, "DataContainers/ImageDataContainer/CellEnsembleData/PhaseName", names);
  EXPECT_EQ(names_of(*load_input(simpl).field), expected);
  // DREAM3D-NX: PhaseNames (Create Ensemble Info), here fixed-length as numpy writes bytes.
  const std::string nx7 = write_nx("named7.dream3d");
  add_strings(nx7, "DataStructure/Image Geometry/CellEnsembleData/PhaseNames", names, false);
  EXPECT_EQ(names_of(*load_input(nx7).field), expected);
  // The EBSD readers' MaterialName serves when no PhaseName is there; an empty
  // name leaves its grains named by the phase's number.
  const std::string ebsd = write_nx("material.dream3d");
  add_strings(ebsd, "DataStructure/Image Geometry/CellEnsembleData/MaterialName", {"Invalid Phase", "Nickel", ""});
  EXPECT_EQ(names_of(*load_input(ebsd).field),
            (std::vector<std::string>{"grain1-Nickel", "grain2-phase2", "grain3-Nickel"}));
  // The names pick grains on the command line.
  EXPECT_EQ(names_of(*load_input(simpl, InputOptions{.drop_labels = {"grain2-Ferrite"}}).field),
            (std::vector<std::string>{"background", "grain1-Austenite", "grain3-Austenite"}));
}

TEST(Dream3d, malformed_phase_names_are_refused_naming_the_file_and_dataset) {
  // A SIMPL file whose CellEnsembleData group gets what `add` puts in it.
  auto refused = [](const std::string& name, const std::function<void(hid_t ensemble)>& add) {
    const std::string path = write_simpl(name);
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t ensemble = group(file, "DataContainers/ImageDataContainer/CellEnsembleData");
    add(ensemble);
    H5Gclose(ensemble);
    H5Fclose(file);
    const std::string why = refusal([&] { load_input(path); });
    EXPECT_EQ(why.rfind(path + ": DataContainers/ImageDataContainer/CellEnsembleData/PhaseName: ", 0), 0u) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
    return why;
  };
  EXPECT_NE(refused("few.dream3d", [](hid_t e) { strings(e, "PhaseName", {"Invalid Phase", "Austenite"}); })
                .find("has 2 names (phases 0 to 1), but grain 2 is of phase 2"),
            std::string::npos);
  EXPECT_NE(refused("numbers.dream3d",
                    [](hid_t e) { dataset(e, "PhaseName", H5T_NATIVE_INT32, {3}, std::vector<int32_t>{0, 1, 2}); })
                .find("holds no strings"),
            std::string::npos);
  EXPECT_NE(refused("table.dream3d",
                    [](hid_t e) {
                      const hsize_t dims[2] = {3, 2};
                      const hid_t space = H5Screate_simple(2, dims, nullptr), type = H5Tcopy(H5T_C_S1);
                      H5Tset_size(type, 8);
                      H5Dclose(H5Dcreate2(e, "PhaseName", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
                      H5Tclose(type);
                      H5Sclose(space);
                    })
                .find("is not a list of names"),
            std::string::npos);
}
