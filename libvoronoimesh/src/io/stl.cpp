/// @file io/stl.cpp
/// STL, binary or ASCII: one file per phase pair (write_mesh) or per phase
/// (write_per_phase_stl). STL holds one unstructured triangle set with float32
/// (binary) coordinates and a normal per triangle, so a multi-surface mesh needs several
/// files, and each file's triangles must be oriented for what it describes.

#include "core/text.hpp"
#include "io/output_buffer.hpp"
#include "io/phase_names.hpp"
#include "io/writers.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/write_mesh.hpp"

#include <Eigen/Geometry>

#include <filesystem>

namespace vm::io {

namespace {

namespace fs = std::filesystem;
using vm::detail::cat;
using vm::detail::put_le;

/// A triangle of `m` as it goes into an STL file: reversed or not.
struct Facet {
  int32_t triangle;
  bool reversed;
};

/// What goes into one STL file: its solid's name and a line of description.
struct Solid {
  std::string name;        ///< a token without spaces (the ASCII `solid` name)
  std::string description; ///< for the binary header
};

/// Writes `facets` as STL, binary or ASCII. The 80-byte binary header holds the
/// description (it must not start with "solid", which some readers take for an
/// ASCII STL); ASCII coordinates are written exactly, binary ones as float32.
void write_stl(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path, const Solid& solid,
               const std::vector<Facet>& facets, bool ascii) {
  vm::detail::write_in_chunks(staged, path, [&](vm::detail::ChunkedOutput& out) {
    std::string& buf = out.text();
    if (ascii) {
      buf += cat("solid ", solid.name, "\n");
    } else {
      std::string header = cat("voronoimesh ", solid.name, ": ", solid.description).substr(0, 80);
      header.resize(80, ' ');
      buf += header;
      put_le(buf, uint32_t(facets.size()));
    }
    for (const Facet& facet : facets) {
      const auto& tri = m.triangles[size_t(facet.triangle)];
      const Vec3 a = m.points[size_t(tri[0])];
      Vec3 b = m.points[size_t(tri[1])], c = m.points[size_t(tri[2])];
      if (facet.reversed) std::swap(b, c);
      const Vec3 normal = (b - a).cross(c - a).normalized(); // zero for a degenerate triangle
      if (ascii) {
        buf += "facet normal ";
        vm::detail::put_point(buf, normal);
        buf += "\n outer loop\n";
        for (const Vec3* v : std::initializer_list<const Vec3*>{&a, &b, &c}) {
          buf += "  vertex ";
          vm::detail::put_point(buf, *v);
          buf += '\n';
        }
        buf += " endloop\nendfacet\n";
      } else {
        for (const Vec3* v : std::initializer_list<const Vec3*>{&normal, &a, &b, &c})
          for (int k = 0; k < 3; ++k) put_le(buf, float((*v)[k]));
        put_le(buf, uint16_t(0));
      }
      out.maybe_flush();
    }
    if (ascii) buf += cat("endsolid ", solid.name, "\n");
  });
}

} // namespace

namespace detail {

std::vector<std::string> write_stl_per_pair(vm::detail::StagedOutputs& staged, const NodeMesh& m,
                                            const std::string& path, bool ascii) {
  const std::vector<PhasePair> pairs = distinct_pairs(m);
  const std::vector<int32_t> index = pair_indices(m, pairs);
  std::vector<std::vector<Facet>> facets(pairs.size());
  for (size_t t = 0; t < m.triangles.size(); ++t) facets[size_t(index[t])].push_back({int32_t(t), false});
  const fs::path p(path);
  std::vector<std::string> written;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const std::string name = phases_token(m, pairs[i]);
    const std::string file = (p.parent_path() / (p.stem().string() + "_" + name + ".stl")).string();
    write_stl(staged, m, file, {name, "surface, normals from the first phase into the second"}, facets[i], ascii);
    written.push_back(file);
  }
  return written;
}

std::vector<std::string> write_per_phase_stl(vm::detail::StagedOutputs& staged, const NodeMesh& m,
                                             const std::string& dir, const WriteOptions& options) {
  const std::string probe = (fs::path(dir) / "phase.stl").string();
  check_output_mesh(m, probe);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw IoError(located(dir, cat("cannot make the directory (", ec ? ec.message() : "a file is in the way", ")")));
  std::vector<std::vector<Facet>> facets(phase_count(m));
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    // The normal points from pairs[t][0] into pairs[t][1]: out of the first.
    facets[size_t(m.pairs[t][0])].push_back({int32_t(t), false});
    facets[size_t(m.pairs[t][1])].push_back({int32_t(t), true});
  }
  std::vector<std::string> written;
  for (size_t p = 0; p < facets.size(); ++p) {
    if (facets[p].empty()) continue;
    const std::string name = phase_token(m, int32_t(p));
    const std::string file = (fs::path(dir) / ("phase_" + name + ".stl")).string();
    write_stl(staged, m, file, {name, "boundary of the phase, normals outward"}, facets[p], options.ascii);
    written.push_back(file);
  }
  return written;
}

} // namespace detail

std::vector<std::string> write_per_phase_stl(const NodeMesh& m, const std::string& dir, const WriteOptions& options) {
  vm::detail::StagedOutputs staged;
  std::vector<std::string> written = detail::write_per_phase_stl(staged, m, dir, options);
  staged.commit();
  return written;
}

} // namespace vm::io
