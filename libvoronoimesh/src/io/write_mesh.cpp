/// @file io/write_mesh.cpp
/// write_mesh(): the format by the file's extension (io/write_mesh.hpp), and the
/// checks every writer relies on.

#include "voronoimesh/io/write_mesh.hpp"

#include "core/text.hpp"
#include "io/writers.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/ply.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <limits>

namespace vm::io {

namespace {

using vm::detail::cat;

/// The extension of `path` in lower case, with the dot ("" if none).
std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

using vm::detail::StagedOutputs;

/// Writes one format among the staged outputs; returns the files written.
using FormatWriter = std::vector<std::string> (*)(StagedOutputs&, const NodeMesh&, const std::string&,
                                                  const WriteOptions&);

/// Writers that write exactly the file asked for.
template <void (*write)(StagedOutputs&, const NodeMesh&, const std::string&)>
std::vector<std::string> one_file(StagedOutputs& staged, const NodeMesh& m, const std::string& path,
                                  const WriteOptions&) {
  write(staged, m, path);
  return {path};
}

void write_vtu(StagedOutputs& staged, const NodeMesh& m, const std::string& path) {
  detail::write_vtk_xml(staged, m, path, detail::VtkDataset::unstructured_grid);
}
void write_vtp(StagedOutputs& staged, const NodeMesh& m, const std::string& path) {
  detail::write_vtk_xml(staged, m, path, detail::VtkDataset::poly_data);
}

/// Every format by extension: the one list output_extensions() and write_mesh() read.
const std::vector<std::pair<std::string, FormatWriter>>& formats() {
  static const std::vector<std::pair<std::string, FormatWriter>> all{
      {".ply",
       [](StagedOutputs& staged, const NodeMesh& m, const std::string& path,
          const WriteOptions& o) -> std::vector<std::string> {
         detail::write_ply(staged, m, path, o.ascii);
         return {path};
       }},
      {".obj", [](StagedOutputs& staged, const NodeMesh& m, const std::string& path,
                  const WriteOptions&) { return detail::write_obj(staged, m, path); }},
      {".stl", [](StagedOutputs& staged, const NodeMesh& m, const std::string& path,
                  const WriteOptions& o) { return detail::write_stl_per_pair(staged, m, path, o.ascii); }},
      {".msh", one_file<detail::write_msh>},
      {".vtu", one_file<write_vtu>},
      {".vtp", one_file<write_vtp>},
      {".mesh", one_file<detail::write_medit>},
  };
  return all;
}

} // namespace

namespace detail {

void check_output_mesh(const NodeMesh& m, const std::string& path) {
  if (m.pairs.size() != m.triangles.size())
    throw IoError(
        located(path, cat("cannot write: ", m.triangles.size(), " triangles but ", m.pairs.size(), " phase pairs")));
  if (m.points.size() > size_t(std::numeric_limits<int32_t>::max()) ||
      m.triangles.size() > size_t(std::numeric_limits<int32_t>::max()))
    throw IoError(located(path, "cannot write: too many nodes or triangles for 32-bit indices"));
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    for (int32_t v : m.triangles[t])
      if (v < 0 || size_t(v) >= m.points.size())
        throw IoError(located(
            path, cat("cannot write: triangle ", t, " has node ", v, " out of range (", m.points.size(), " nodes)")));
    const PhasePair& p = m.pairs[t];
    if (p[0] < 0 || p[0] >= p[1] || p[1] > std::numeric_limits<int16_t>::max())
      throw IoError(located(path, cat("cannot write: triangle ", t, " has the phase pair (", p[0], ", ", p[1],
                                      "), not two phase ids a < b")));
  }
}

} // namespace detail

namespace {

/// The writer for the extension of `path`; throws InvalidInput if there is none.
FormatWriter writer_for(const std::string& path) {
  const std::string ext = extension_of(path);
  for (const auto& [known, write] : formats())
    if (known == ext) return write;
  std::string list;
  for (const auto& [known, write] : formats()) list += (list.empty() ? "" : ", ") + known;
  throw InvalidInput(located(path, ext.empty() ? cat("no extension to choose the output format by (known: ", list, ")")
                                               : cat("unknown output format '", ext, "' (known: ", list, ")")));
}

} // namespace

const std::vector<std::string>& output_extensions() {
  static const std::vector<std::string> known = [] {
    std::vector<std::string> exts;
    for (const auto& [ext, write] : formats()) exts.push_back(ext);
    return exts;
  }();
  return known;
}

void check_output_format(const std::string& path) {
  writer_for(path);
}

namespace detail {

std::vector<std::string> write_mesh(StagedOutputs& staged, const NodeMesh& m, const std::string& path,
                                    const WriteOptions& options) {
  const FormatWriter write = writer_for(path);
  check_output_mesh(m, path);
  return write(staged, m, path, options);
}

} // namespace detail

std::vector<std::string> write_mesh(const NodeMesh& m, const std::string& path, const WriteOptions& options) {
  StagedOutputs staged;
  std::vector<std::string> written = detail::write_mesh(staged, m, path, options);
  staged.commit();
  return written;
}

} // namespace vm::io
