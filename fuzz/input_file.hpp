#pragma once
/// @file fuzz/input_file.hpp
/// What every fuzz target shares: the readers take a path, so each input is
/// written to a file of the reader's extension in a folder of this process's
/// own (parallel fuzzing jobs must not overwrite each other's inputs), and a
/// reader may refuse an input only with a vm::Error: any other exception
/// escapes to libFuzzer, which reports it as a crash.

#include "voronoimesh/errors.hpp"
#include "voronoimesh/scene.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace vm::fuzz {

/// A folder for this process's inputs, removed when the fuzzer exits normally.
class InputFolder {
public:
  InputFolder() : path_(std::filesystem::temp_directory_path() / ("vm_fuzz_" + std::to_string(getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~InputFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

private:
  std::filesystem::path path_;
};

/// The folder's path: an empty folder apart from the inputs, so readers that
/// follow a name in the input to another file (a detached NRRD, a MetaImage
/// ElementDataFile, a scene's grid phase) find at most the input itself.
inline const std::filesystem::path& input_folder() {
  static const InputFolder folder;
  return folder.path();
}

/// Writes `data` to "input<extension>" in input_folder() and returns its path.
inline std::string write_input(const uint8_t* data, size_t size, const std::string& extension) {
  const std::string path = (input_folder() / ("input" + extension)).string();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(data, 1, size, f) != size || std::fclose(f) != 0) {
    std::perror(path.c_str());
    std::abort(); // the machine, not the reader, failed: stop fuzzing
  }
  return path;
}

/// Runs `read` on `data` written as a file of `extension`; a vm::Error is a
/// clean refusal.
template <class Read> int read_as_file(const uint8_t* data, size_t size, const std::string& extension, Read read) {
  const std::string path = write_input(data, size, extension);
  try {
    read(path);
  } catch (const vm::Error&) {
  }
  return 0;
}

/// Evaluates every phase of `scene` at its domain's centre: some faults (a bad
/// expression, an empty point region) show only when a field is evaluated.
inline void evaluate_at_centre(const Scene& scene) {
  const Vec3 centre = (scene.grid.domain.min + scene.grid.domain.max) / 2;
  std::vector<double> values(size_t(scene.field->num_phases()));
  scene.field->values(centre, values);
}

} // namespace vm::fuzz
