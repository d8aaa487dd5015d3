// Inputs the fuzzers (fuzz/, scripts/fuzz.sh) found crashing a reader, running
// out of memory or hanging, kept in tests/data/fuzz/ as the fuzzer wrote them:
// each must now be refused with a vm::Error whose one-line message names the
// file and the problem. A file's name starts with its target's name (without
// '_'): "nrrddetached_..." went to fuzz_nrrd_detached.

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/io/ply.hpp"
#include "voronoimesh/io/volume.hpp"

#include "fields/point_cloud.hpp"
#include "input_layouts.hpp"
#include "scratch_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>

using namespace vm;
namespace fs = std::filesystem;

namespace {

const fs::path data_dir = fs::path(VM_TESTS_DATA_DIR) / "fuzz";

/// The target a kept file went to: its name up to the first '_'.
std::string target_of(const std::string& name) { return name.substr(0, name.find('_')); }

/// The reader of a target's files.
std::function<void(const std::string&)> reader_of(const std::string& target) {
  const std::map<std::string, std::function<void(const std::string&)>> readers = {
      {"scene", [](const std::string& p) { load_scene(p); }},
      {"nrrd", [](const std::string& p) { io::read_nrrd(p); }},
      {"nrrddetached", [](const std::string& p) { io::read_nrrd(p); }},
      {"nrrdcompressed", [](const std::string& p) { io::read_nrrd(p); }},
      {"nifti", [](const std::string& p) { io::read_nifti(p); }},
      {"niftigz", [](const std::string& p) { io::read_nifti(p); }},
      {"niftigzipped", [](const std::string& p) { io::read_nifti(p); }},
      {"metaimage", [](const std::string& p) { io::read_metaimage(p); }},
      {"metaimagedetached", [](const std::string& p) { io::read_metaimage(p); }},
      {"inr", [](const std::string& p) { io::read_inr(p); }},
      {"tiff", [](const std::string& p) { io::read_tiff(p); }},
      {"points", [](const std::string& p) { detail::point_cloud_scene(p, {}); }},
      {"plypoints", [](const std::string& p) { detail::point_cloud_scene(p, {}); }},
      {"plymesh", [](const std::string& p) { io::read_ply(p); }}};
  return readers.at(target);
}

/// The file the reader reads for the kept input `kept`, written into `folder`
/// as its target writes it (fuzz/fuzz_<target>.cpp, fuzz/input_layouts.hpp):
/// split into a header and data files, compressed, or the kept file itself.
std::string rebuild(const std::string& target, const fs::path& kept, const fs::path& folder) {
  const std::string bytes = test::ScratchDir::read_bytes(kept.string());
  auto write = [&](const std::string& name, const std::string& contents) {
    std::ofstream(folder / name, std::ios::binary) << contents;
    return (folder / name).string();
  };
  if (target == "nrrddetached" || target == "metaimagedetached") {
    const auto files = fuzz::split_files(bytes, target == "nrrddetached" ? "input.nhdr" : "input.mhd");
    EXPECT_TRUE(files) << kept << " does not split into files";
    if (!files) return kept.string();
    for (const fuzz::InputFile& f : *files) write(f.name, f.bytes);
    return (folder / files->front().name).string();
  }
  if (target == "niftigzipped") return write("input.nii.gz", fuzz::gzip(bytes));
  if (target == "nrrdcompressed") return write("input.nrrd", fuzz::compress_nrrd_data(bytes));
  return kept.string();
}

/// Each file and a part of the message it must be refused with.
const std::map<std::string, std::string> expected = {
    {"nrrd_ascii_sizes_beyond_file.nrrd", "samples of ASCII data, which take at least 2200122732 bytes"},
    {"nrrddetached_list_names_beyond_sizes.nhdr",
     "data file LIST: its last line '0.5 -0.5 0.5 -0.5' does not end with a line end"},
    {"nrrddetached_skiplist_line_without_skip.nhdr", "line 7 of its header holds a NUL byte"},
    {"nrrddetached_skiplist_long_line_cut_off.nhdr", "line 9 of its header holds a NUL byte"},
    {"nrrdcompressed_field_line_beyond_teems_message_buffer.nrrd", "line 2 of its header is 1077 bytes long"},
    {"points_extent_beyond_double.csv", "the points span more than"},
    {"plypoints_empty_element_of_1e10_items.ply", "bad number"},
    // 3.7 GB allocated, 5.7 s, before libtiff found the strips missing.
    {"tiff_page_of_1.8_gb_in_403_bytes.tif", "page 1 describes 1840317440 bytes of samples, more than the file's 403"},
};

} // namespace

class FuzzRegressions : public test::ScratchDir {};

TEST_F(FuzzRegressions, every_found_input_is_refused_cleanly) {
  for (const auto& [name, message] : expected) {
    const std::string target = target_of(name);
    const fs::path folder = dir_ / name;
    fs::create_directories(folder);
    const std::string path = rebuild(target, data_dir / name, folder);
    try {
      reader_of(target)(path);
      ADD_FAILURE() << name << " was read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

TEST_F(FuzzRegressions, every_file_kept_is_checked) {
  for (const auto& entry : fs::directory_iterator(data_dir))
    EXPECT_TRUE(expected.contains(entry.path().filename().string())) << entry.path() << " is not in the table";
}
