#pragma once
// Small NRRD files written by tests (the library reads them with Teem).

#include "process_folder.hpp"

#include <fstream>
#include <string>
#include <vector>

namespace vm::test {

/// A path for a test file, in this process's own folder.
inline std::string temp_path(const std::string& name) {
  return (process_folder() / ("vm_test_input_" + name)).string();
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
