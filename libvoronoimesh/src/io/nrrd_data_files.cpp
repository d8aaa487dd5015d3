#include "io/nrrd_data_files.hpp"

#include "core/text.hpp"
#include "io/voxel_data.hpp"
#include "voronoimesh/core/errors.hpp"

#include <bzlib.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <memory>

namespace vm::io::nrrd {

namespace fs = std::filesystem;
using detail::cat;

namespace {

/// The data files in Teem's order: the header's own file when the data is attached.
std::vector<fs::path> data_files(const std::string& path, NrrdIoState& io, const std::vector<fs::path>& detached) {
  const bool teem_detached = io.dataFNFormat || io.dataFNArr->len > 0;
  // screen_data_files() reads the header as Teem does, so the two agree.
  if (teem_detached != !detached.empty() || (teem_detached && _nrrdDataFNNumber(&io) != detached.size()))
    throw InvalidInput(located(path, "its data files could not be checked (Teem reads the header differently)"));
  return teem_detached ? detached : std::vector<fs::path>{fs::path(path)};
}

/// "its file", "its data file X" or "its N data files (X ... Y)", for messages.
std::string describe(const std::string& path, const std::vector<fs::path>& files) {
  if (files.size() == 1) return files[0] == fs::path(path) ? "its file" : cat("its data file ", files[0].string());
  return cat("its ", files.size(), " data files (", files.front().string(), " ... ", files.back().string(), ")");
}

uint64_t saturating_add(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }
uint64_t saturating_mul(uint64_t a, uint64_t b) { return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b; }

/// The bytes Teem skips before the data of file `i` (a SKIPLIST's own, or the
/// header's "byte skip"; -1, "the data ends the file", skips nothing extra).
uint64_t byte_skip(const NrrdIoState& io, size_t i) {
  return uint64_t(std::max(0L, io.dataFSkip ? io.dataFSkip[i] : io.byteSkip));
}

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

/// The bytes the bzip2 stream at `file`'s position inflates to, counted up to
/// `want` and not kept, as Teem reads it (one stream per file). Throws
/// InvalidInput naming `name` when it is not bzip2 data.
uint64_t bzip2_bytes(const std::string& path, std::FILE* file, uint64_t want, const fs::path& name) {
  int error = BZ_OK, ignored = BZ_OK;
  BZFILE* bz = BZ2_bzReadOpen(&error, file, 0, 0, nullptr, 0);
  std::vector<char> buffer(1 << 16);
  uint64_t got = 0;
  while (error == BZ_OK && got < want) {
    const int n = BZ2_bzRead(&error, bz, buffer.data(), int(std::min<uint64_t>(buffer.size(), want - got)));
    if (error == BZ_OK || error == BZ_STREAM_END) got += uint64_t(n);
  }
  BZ2_bzReadClose(&ignored, bz);
  // A stream that stops early is truncated: the caller reports how much it held.
  if (error != BZ_OK && error != BZ_STREAM_END && error != BZ_UNEXPECTED_EOF)
    throw InvalidInput(located(path, cat(describe(path, {name}), " is not valid bzip2 data (",
                                         error == BZ_DATA_ERROR_MAGIC ? "BZ_DATA_ERROR_MAGIC"
                                         : error == BZ_DATA_ERROR     ? "BZ_DATA_ERROR"
                                                                      : cat("bzip2 error ", error),
                                         ")")));
  return got;
}

/// The bytes the gzip (or zlib) data at `file`'s position inflates to, members
/// one after the other as Teem reads them, counted up to `want` and not kept.
/// Throws InvalidInput naming `name` when it is not such data.
uint64_t gzip_bytes(const std::string& path, std::FILE* file, uint64_t want, const fs::path& name) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) throw InvalidInput(located(path, "cannot start zlib"));
  std::vector<unsigned char> in(1 << 16), out(1 << 16);
  uint64_t got = 0;
  int status = Z_OK;
  while (got < want) {
    if (z.avail_in == 0) {
      const size_t n = std::fread(in.data(), 1, in.size(), file);
      if (n == 0) break; // the file ends: the caller reports how much it held
      z.next_in = in.data();
      z.avail_in = unsigned(n);
    }
    z.next_out = out.data();
    z.avail_out = unsigned(std::min<uint64_t>(out.size(), want - got));
    const unsigned before = z.avail_out;
    status = inflate(&z, Z_NO_FLUSH);
    got += before - z.avail_out;
    if (status == Z_STREAM_END) {
      if (z.avail_in == 0 && std::feof(file)) break;
      inflateReset(&z); // another member follows
      continue;
    }
    if (status != Z_OK && status != Z_BUF_ERROR) break;
  }
  inflateEnd(&z);
  if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR)
    throw InvalidInput(located(path, cat(describe(path, {name}), " is not valid gzip data (",
                                         status == Z_DATA_ERROR ? "Z_DATA_ERROR" : cat("zlib error ", status), ")")));
  return got;
}

/// Throws unless each compressed data file inflates to its share of `needed`
/// bytes plus its byte skip (Teem reads the same number of samples from each),
/// inflating it as `count` does, without keeping what it inflates: the memory
/// touched grows with the data, not with what the header claims.
void check_inflates(const std::string& path, NrrdIoState& io, const std::vector<fs::path>& files, uint64_t samples,
                    uint64_t needed, const char* encoding,
                    uint64_t (*count)(const std::string&, std::FILE*, uint64_t, const fs::path&)) {
  for (size_t i = 0; i < files.size(); ++i) {
    const uint64_t want = saturating_add(needed / files.size(), byte_skip(io, i));
    uint64_t got = 0;
    if (files.size() == 1 && io.dataFile) {
      got = count(path, io.dataFile, want, files[i]); // Teem left it where the data starts
    } else {
      File f(std::fopen(files[i].c_str(), "rb"), &std::fclose);
      if (!f) throw IoError(located(path, cat("cannot open its data file ", files[i].string())));
      if (nrrdLineSkip(f.get(), &io) != 0) {
        free(biffGetDone(NRRD));
        throw InvalidInput(
            located(path, cat("its data file ", files[i].string(), " has fewer lines than 'line skip'")));
      }
      got = count(path, f.get(), want, files[i]);
    }
    if (got < want)
      throw InvalidInput(located(path, cat("truncated: the header describes ", samples, " samples (", needed,
                                           " bytes) of ", encoding, " data; ", describe(path, {files[i]}),
                                           " inflates to ", got, " of the ", want, " bytes it must hold")));
  }
}

} // namespace

void check_data_fits(const std::string& path, NrrdIoState& io, const std::vector<fs::path>& detached, uint64_t samples,
                     uint64_t sample_bytes) {
  const std::vector<fs::path> files = data_files(path, io, detached);
  const NrrdEncoding* e = io.encoding;
  uint64_t held = 0, skips = 0;
  for (size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    const uintmax_t size = fs::file_size(files[i], ec);
    held += ec ? 0 : uint64_t(size);
    skips = saturating_add(skips, byte_skip(io, i));
  }
  // A single file's data starts where Teem left it: after the header when it
  // is attached, after the lines skipped, and the bytes skipped unless the
  // skip is within the inflated data.
  if (files.size() == 1 && io.dataFile) {
    held -= std::min<uint64_t>(held, uint64_t(std::max(0L, std::ftell(io.dataFile))));
    if (!e->isCompression) skips = 0;
  }
  const uint64_t needed = samples * sample_bytes; // below the memory, so no overflow
  const std::string skip_note = skips > 0 ? cat(" after skipping ", skips, " bytes") : "";
  if (e->isCompression) {
    if (e == nrrdEncodingBzip2) return check_inflates(path, io, files, samples, needed, "bzip2", bzip2_bytes);
    if (saturating_add(needed, skips) <= detail::max_inflated_bytes(held)) {
      if (e == nrrdEncodingGzip) check_inflates(path, io, files, samples, needed, "gzip", gzip_bytes);
      return;
    }
    throw InvalidInput(
        located(path, cat("the header describes ", samples, " samples (", needed, " bytes)", skip_note, " of ", e->name,
                          " data; ", describe(path, files), files.size() > 1 ? " hold " : " holds ", held,
                          " compressed bytes, which cannot inflate to that many (corrupt sizes?)")));
  }
  // Raw data takes its bytes, hex two digits a byte, ascii a character a sample at least.
  const uint64_t least = saturating_add(skips, e == nrrdEncodingRaw     ? needed
                                               : e == nrrdEncodingHex   ? saturating_mul(2, needed)
                                               : e == nrrdEncodingAscii ? samples
                                                                        : 0);
  if (least > held)
    throw InvalidInput(located(path, cat("truncated: the header describes ", samples, " samples of ", e->name, " data",
                                         skip_note, ", which take at least ", least, " bytes; ", describe(path, files),
                                         files.size() > 1 ? " hold " : " holds ", held)));
}

} // namespace vm::io::nrrd
