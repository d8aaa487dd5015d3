/// @file io/ply.cpp
/// write_ply: node-level PLY with double coordinates and phase labels, written
/// to a temporary file and renamed into place (io/ply.hpp).

#include "voronoimesh/io/ply.hpp"

#include "core/text.hpp"
#include "io/output_buffer.hpp"
#include "io/phase_names.hpp"
#include "io/writers.hpp"

#include <string>

namespace vm::io {

namespace {

using vm::detail::cat;
using vm::detail::put_le;
using vm::detail::put_number;

/// A phase name on one header line: control characters would end the line.
std::string header_safe(std::string name) {
  for (char& c : name)
    if (static_cast<unsigned char>(c) < 0x20) c = '_';
  return name;
}

std::string header(const NodeMesh& m, bool ascii) {
  std::string h = "ply\n";
  h += ascii ? "format ascii 1.0\n" : "format binary_little_endian 1.0\n";
  h += "comment voronoimesh interface mesh: normals point from phase0 into phase1\n";
  h += "comment domain";
  for (const Vec3* p : {&m.domain.min, &m.domain.max})
    for (int a = 0; a < 3; ++a) {
      h += ' ';
      put_number(h, (*p)[a]);
    }
  h += '\n';
  if (m.grid_spacing > 0) {
    h += "comment grid_spacing ";
    put_number(h, m.grid_spacing);
    h += '\n';
  }
  // Every phase, present or not, so a reader recovers the whole label set.
  // (phase_count scans every triangle: once, not once per phase.)
  const size_t phases = detail::phase_count(m);
  // A colour goes on a line of its own: a name runs to the end of its line.
  for (size_t p = 0; p < phases; ++p) {
    h += cat("comment phase ", m.label_of(int32_t(p)), " ", header_safe(detail::phase_name(m, int32_t(p))),
             "\n");
    if (const auto color = detail::phase_color(m, int32_t(p))) {
      h += cat("comment phase_color ", m.label_of(int32_t(p)), " ");
      vm::detail::put_color(h, *color);
      h += '\n';
    }
  }
  h += cat("element vertex ", m.points.size(), "\n");
  h += "property double x\nproperty double y\nproperty double z\n";
  h += cat("element face ", m.triangles.size(), "\n");
  h += "property list uchar int vertex_indices\nproperty int phase0\nproperty int phase1\nend_header\n";
  return h;
}

/// The vertices, then the faces with their phase labels.
void write_body(vm::detail::ChunkedOutput& out, const NodeMesh& m, bool ascii) {
  std::string& buf = out.text();
  for (const Vec3& p : m.points) {
    if (ascii) {
      vm::detail::put_point(buf, p);
      buf += '\n';
    } else {
      for (int a = 0; a < 3; ++a) put_le(buf, p[a]);
    }
    out.maybe_flush();
  }
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const int32_t p0 = m.label_of(m.pairs[t][0]), p1 = m.label_of(m.pairs[t][1]);
    if (ascii) {
      buf += cat("3 ", tri[0], " ", tri[1], " ", tri[2], " ", p0, " ", p1, "\n");
    } else {
      buf += char(3);
      for (int32_t v : tri) put_le(buf, v);
      put_le(buf, p0);
      put_le(buf, p1);
    }
    out.maybe_flush();
  }
}

} // namespace

namespace detail {

void write_ply(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path, bool ascii) {
  check_output_mesh(m, path);
  vm::detail::write_in_chunks(staged, path, [&](vm::detail::ChunkedOutput& out) {
    out.text() += header(m, ascii);
    write_body(out, m, ascii);
  });
}

} // namespace detail

void write_ply(const NodeMesh& m, const std::string& path, bool ascii) {
  vm::detail::StagedOutputs staged;
  detail::write_ply(staged, m, path, ascii);
  staged.commit();
}

} // namespace vm::io
