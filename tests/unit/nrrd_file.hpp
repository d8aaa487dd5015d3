#pragma once
// Small NRRD files written by tests (the library reads them with Teem).

#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <string>
#include <vector>

namespace vm::test {

/// A path for a test file, in a folder of this process's own (removed when it
/// exits): test runs in several build trees at once must not overwrite each
/// other's files.
inline std::string temp_path(const std::string& name) {
  struct Folder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("vm_test_" + std::to_string(::getpid()));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Folder folder;
  return (folder.path / ("vm_test_input_" + name)).string();
}

/// Writes an attached raw NRRD: `header` holds the type/dimension/sizes lines and
/// any geometry, `data` the samples.
template <class T>
std::string write_nrrd(const std::string& name, const std::string& header, const std::vector<T>& data) {
  const std::string path = temp_path(name);
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\n" << header << "encoding: raw\nendian: little\n\n";
  out.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size() * sizeof(T)));
  return path;
}

} // namespace vm::test
