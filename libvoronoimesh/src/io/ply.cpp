/// @file io/ply.cpp
/// write_ply: node-level PLY with double coordinates, written to a temporary
/// file and renamed into place (io/ply.hpp).

#include "voronoimesh/io/ply.hpp"

#include "detail/atomic_write.hpp"
#include "detail/text.hpp"
#include "voronoimesh/errors.hpp"


#include <bit>
#include <charconv>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace vm::io {

namespace {

using detail::cat;

/// Shortest text that reads back to exactly `v` (std::to_chars guarantees the
/// round trip, like max_digits10 but without needless digits).
void put_number(std::string& out, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

/// Appends `v` in little-endian byte order.
template <class T>
void put_le(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.append(b, sizeof(T));
}

/// A phase name on one header line: control characters would end the line.
std::string header_safe(std::string name) {
  for (char& c : name)
    if (static_cast<unsigned char>(c) < 0x20) c = '_';
  return name;
}

void check_mesh(const NodeMesh& m, const std::string& path) {
  if (m.pairs.size() != m.triangles.size())
    throw IoError(
        located(path, cat("cannot write: ", m.triangles.size(), " triangles but ", m.pairs.size(), " phase pairs")));
  if (m.points.size() > size_t(std::numeric_limits<int32_t>::max()) ||
      m.triangles.size() > size_t(std::numeric_limits<int32_t>::max()))
    throw IoError(located(path, "cannot write: too many nodes or triangles for 32-bit PLY indices"));
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int32_t v : m.triangles[t])
      if (v < 0 || size_t(v) >= m.points.size())
        throw IoError(located(
            path, cat("cannot write: triangle ", t, " has node ", v, " out of range (", m.points.size(), " nodes)")));
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
  for (size_t i = 0; i < m.phase_names.size(); ++i)
    h += cat("comment phase ", i, " ", header_safe(m.phase_names[i]), "\n");
  h += cat("element vertex ", m.points.size(), "\n");
  h += "property double x\nproperty double y\nproperty double z\n";
  h += cat("element face ", m.triangles.size(), "\n");
  h += "property list uchar int vertex_indices\nproperty int phase0\nproperty int phase1\nend_header\n";
  return h;
}

/// Writes the body in chunks so memory stays small for large meshes.
void write_body(std::ostream& f, const NodeMesh& m, bool ascii) {
  constexpr size_t kChunk = 1 << 20;
  std::string buf;
  auto flush = [&](bool force) {
    if (buf.size() >= kChunk || force) {
      f.write(buf.data(), std::streamsize(buf.size()));
      buf.clear();
    }
  };
  for (const Vec3& p : m.points) {
    for (int a = 0; a < 3; ++a) {
      if (ascii) {
        put_number(buf, p[a]);
        buf += a < 2 ? ' ' : '\n';
      } else {
        put_le(buf, p[a]);
      }
    }
    flush(false);
  }
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const auto& pr = m.pairs[t];
    if (ascii) {
      buf += cat("3 ", tri[0], " ", tri[1], " ", tri[2], " ", pr[0], " ", pr[1], "\n");
    } else {
      buf += char(3);
      for (int32_t v : tri) put_le(buf, v);
      put_le(buf, pr[0]);
      put_le(buf, pr[1]);
    }
    flush(false);
  }
  flush(true);
}

} // namespace

void write_ply(const NodeMesh& m, const std::string& path, bool ascii) {
  check_mesh(m, path);
  detail::write_atomically(path, [&](std::ostream& f) {
    const std::string h = header(m, ascii);
    f.write(h.data(), std::streamsize(h.size()));
    write_body(f, m, ascii);
  });
}

} // namespace vm::io
