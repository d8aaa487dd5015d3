#pragma once
/// @file io/output_buffer.hpp
/// What every mesh writer needs to put text and bytes into a file quickly: the
/// shortest exact text of a double, little-endian binary values, and a buffer
/// that goes to the stream in large chunks (so memory stays small and the
/// stream sees few writes, whatever the mesh size).

#include "core/staged_outputs.hpp"
#include "voronoimesh/core/types.hpp"

#include <bit>
#include <charconv>
#include <cstring>
#include <functional>
#include <ostream>
#include <string>
#include <utility>

namespace vm::detail {

/// Appends the shortest text that reads back to exactly `v` (std::to_chars
/// guarantees the round trip, like max_digits10 but without needless digits).
inline void put_number(std::string& out, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, size_t(r.ptr - buf));
}

/// Appends an integer in decimal.
inline void put_int(std::string& out, long long v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, size_t(r.ptr - buf));
}

/// Appends "r g b", each the shortest text that reads back to exactly its float.
inline void put_color(std::string& out, const Rgb& rgb) {
  for (size_t c = 0; c < 3; ++c) {
    if (c) out += ' ';
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, rgb[c]);
    out.append(buf, size_t(r.ptr - buf));
  }
}

/// Appends "x y z", each coordinate as put_number() writes it.
inline void put_point(std::string& out, const Vec3& p) {
  for (int a = 0; a < 3; ++a) {
    if (a) out += ' ';
    put_number(out, p[a]);
  }
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

/// A string buffer in front of a stream: append to text(), call maybe_flush()
/// after each item and finish() at the end (write_in_chunks() does both ends).
class ChunkedOutput {
public:
  explicit ChunkedOutput(std::ostream& out) : out_(out) {}
  std::string& text() { return buf_; }
  /// Hands the buffer to the stream once it holds about 1 MiB.
  void maybe_flush() {
    if (buf_.size() >= kChunk) flush();
  }
  void finish() { flush(); }

private:
  static constexpr size_t kChunk = size_t(1) << 20;
  void flush() {
    out_.write(buf_.data(), std::streamsize(buf_.size()));
    buf_.clear();
  }
  std::ostream& out_;
  std::string buf_;
};

/// Writes `path` among `staged` (StagedOutputs::write()) through a ChunkedOutput:
/// `body` appends to out.text(), calling out.maybe_flush() as it goes.
inline void write_in_chunks(StagedOutputs& staged, const std::string& path,
                            const std::function<void(ChunkedOutput&)>& body) {
  staged.write(path, [&](std::ostream& f) {
    ChunkedOutput out(f);
    body(out);
    out.finish();
  });
}

} // namespace vm::detail
