// Inputs the fuzzers (fuzz/, scripts/fuzz.sh) found crashing a reader, running
// out of memory or hanging, kept in tests/data/fuzz/: each must now be refused
// with a vm::Error whose one-line message names the file and the problem.

#include "voronoimesh/errors.hpp"
#include "voronoimesh/io/ply.hpp"
#include "voronoimesh/io/volume.hpp"
#include "voronoimesh/scene.hpp"

#include "detail/point_cloud.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <string>

using namespace vm;
namespace fs = std::filesystem;

namespace {

const fs::path data_dir = fs::path(VM_TESTS_DATA_DIR) / "fuzz";

/// A file's reader, by the prefix of its name (the fuzz target's reader).
std::function<void(const std::string&)> reader_of(const std::string& name) {
  const std::map<std::string, std::function<void(const std::string&)>> readers = {
      {"scene", [](const std::string& p) { load_scene(p); }},
      {"nrrd", [](const std::string& p) { io::read_nrrd(p); }},
      {"nifti", [](const std::string& p) { io::read_nifti(p); }},
      {"metaimage", [](const std::string& p) { io::read_metaimage(p); }},
      {"inr", [](const std::string& p) { io::read_inr(p); }},
      {"points", [](const std::string& p) { detail::point_cloud_scene(p, {}); }},
      {"plypoints", [](const std::string& p) { detail::point_cloud_scene(p, {}); }},
      {"plymesh", [](const std::string& p) { io::read_ply(p); }}};
  return readers.at(name.substr(0, name.find('_')));
}

/// Each file and a part of the message it must be refused with.
const std::map<std::string, std::string> expected = {
    {"nrrd_ascii_sizes_beyond_file.nrrd", "samples of ASCII data, which take at least 2200122732 bytes"},
    {"points_extent_beyond_double.csv", "the points span more than"},
    {"plypoints_empty_element_of_1e10_items.ply", "bad number"},
};

} // namespace

TEST(FuzzRegressions, every_found_input_is_refused_cleanly) {
  for (const auto& [name, message] : expected) {
    const std::string path = (data_dir / name).string();
    try {
      reader_of(name)(path);
      ADD_FAILURE() << name << " was read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

TEST(FuzzRegressions, every_file_kept_is_checked) {
  for (const auto& entry : fs::directory_iterator(data_dir))
    EXPECT_TRUE(expected.contains(entry.path().filename().string())) << entry.path() << " is not in the table";
}
