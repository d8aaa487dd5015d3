#pragma once
/// @file fuzz/input_file.hpp
/// What every fuzz target shares: the readers take a path, so each input is
/// written to a file of the reader's extension in a folder of this process's
/// own (parallel fuzzing jobs must not overwrite each other's inputs), and a
/// reader may refuse an input only with a vm::Error: any other exception
/// escapes to libFuzzer, which reports it as a crash.

#include "input_layouts.hpp"
#include "process_folder.hpp"

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/scene.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vm::fuzz {

/// The folder inputs are written to: empty apart from them, so readers that
/// follow a name in the input to another file (a detached NRRD, a MetaImage
/// ElementDataFile, a scene's grid phase) find only the input's own files.
inline const std::filesystem::path& input_folder() { return vm::test::process_folder(); }

/// Writes `bytes` to `name` in input_folder() and returns its path.
inline std::string write_file(const std::string& name, std::string_view bytes) {
  const std::string path = (input_folder() / name).string();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fclose(f) != 0) {
    std::perror(path.c_str());
    std::abort(); // the machine, not the reader, failed: stop fuzzing
  }
  return path;
}

/// Writes `data` to "input<extension>" in input_folder() and returns its path.
inline std::string write_input(const uint8_t* data, size_t size, const std::string& extension) {
  return write_file("input" + extension, std::string_view(reinterpret_cast<const char*>(data), size));
}

/// Empties input_folder() and writes `files` into it (the first is the one
/// to read); returns the first one's path. The files of the previous input
/// must not answer this one's names.
inline std::string write_files(const std::vector<InputFile>& files) {
  for (const auto& entry : std::filesystem::directory_iterator(input_folder())) std::filesystem::remove_all(entry);
  for (const InputFile& f : files) write_file(f.name, f.bytes);
  return (input_folder() / files.front().name).string();
}

/// Runs `read` on the file at `path`; a vm::Error is a clean refusal.
template <class Read> int read_cleanly(const std::string& path, Read read) {
  try {
    read(path);
  } catch (const vm::Error&) {
  }
  return 0;
}

/// Runs `read` on `data` written as a file of `extension`.
template <class Read> int read_as_file(const uint8_t* data, size_t size, const std::string& extension, Read read) {
  return read_cleanly(write_input(data, size, extension), read);
}

/// Runs `read` on the first of the files `data` holds in the layout of
/// split_files() (input_layouts.hpp), named `first_name`; inputs that do not
/// split into plain file names are left out of the corpus (-1).
template <class Read> int read_as_files(const uint8_t* data, size_t size, const std::string& first_name, Read read) {
  const auto files = split_files(std::string_view(reinterpret_cast<const char*>(data), size), first_name);
  if (!files) return -1;
  return read_cleanly(write_files(*files), read);
}

/// Evaluates every phase of `scene` at its domain's centre: some faults (a bad
/// expression, an empty point region) show only when a field is evaluated.
inline void evaluate_at_centre(const Scene& scene) {
  const Vec3 centre = (scene.grid.domain.min + scene.grid.domain.max) / 2;
  std::vector<double> values(size_t(scene.field->num_phases()));
  scene.field->values(centre, values);
}

} // namespace vm::fuzz
