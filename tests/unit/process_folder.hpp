#pragma once
/// @file process_folder.hpp
/// A folder of this process's own for the files tests and fuzz targets write:
/// test runs in several build trees at once, and parallel fuzzing jobs, must not
/// overwrite each other's files.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace vm::test {

/// <tmp>/vm_<pid>, made on first use and removed when the process exits normally.
inline const std::filesystem::path& process_folder() {
  struct Folder {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("vm_" + std::to_string(::getpid()));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Folder folder;
  return folder.path;
}

} // namespace vm::test
