#include "io/inflate.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <zlib.h>

#include <limits>

namespace vm::detail {

std::string inflate_exactly(const std::string& path, std::string_view compressed, size_t expected) {
  std::string out(expected, '\0');
  z_stream z{};
  // 15 + 32: the largest window, with zlib/gzip header detection.
  if (inflateInit2(&z, 15 + 32) != Z_OK) throw IoError(located(path, "cannot start zlib decompression"));
  struct End {
    z_stream* z;
    ~End() { inflateEnd(z); }
  } end{&z};
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  size_t in_left = compressed.size(), out_done = 0;
  // zlib counts in 32-bit uInt: feed and drain in chunks it can take.
  constexpr size_t chunk = std::numeric_limits<uInt>::max();
  char spare; // room for one byte beyond `expected`, to notice a longer stream
  int rc = Z_OK;
  while (rc == Z_OK) {
    if (z.avail_in == 0) {
      z.avail_in = uInt(std::min(in_left, chunk));
      in_left -= z.avail_in;
    }
    if (out_done < expected) {
      z.next_out = reinterpret_cast<Bytef*>(out.data() + out_done);
      z.avail_out = uInt(std::min(expected - out_done, chunk));
    } else {
      z.next_out = reinterpret_cast<Bytef*>(&spare);
      z.avail_out = 1;
    }
    const uInt before = z.avail_out;
    rc = inflate(&z, Z_NO_FLUSH);
    const size_t produced = before - z.avail_out;
    if (out_done >= expected && produced > 0)
      throw InvalidInput(located(path, cat("compressed voxel data holds more than the ", expected,
                                           " bytes the header describes (wrong sizes or type?)")));
    out_done += produced;
    if (rc == Z_BUF_ERROR && z.avail_in == 0 && in_left == 0) break; // input used up before the end
  }
  if (rc != Z_STREAM_END && rc != Z_BUF_ERROR)
    throw InvalidInput(located(path, cat("corrupt compressed voxel data (zlib: ", z.msg ? z.msg : "error", ")")));
  if (rc != Z_STREAM_END || out_done < expected)
    throw InvalidInput(located(path, cat("truncated: compressed voxel data ends after ", out_done, " of the ", expected,
                                         " bytes the header describes")));
  return out;
}

} // namespace vm::detail
