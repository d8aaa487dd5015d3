#pragma once
/// @file fuzz/input_layouts.hpp
/// How a fuzz input becomes the files a reader reads, where that is more than
/// writing its bytes: several files from one input (a header and its data
/// files), and data the target compresses itself so that the mutations land in
/// what the decompressor hands the reader rather than in the compressed bytes,
/// which the decompressor would reject. The regression test (tests/unit/
/// test_fuzz_regressions.cpp) rebuilds the files of a kept input the same way.

#include <bzlib.h>
#include <zlib.h>

#include <cctype>
#include <cstdlib>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace vm::fuzz {

/// One file of a multi-file input.
struct InputFile {
  std::string name;  ///< a plain file name, no folder
  std::string bytes; ///< its contents
};

/// Starts each file after the first in a multi-file input: "\n--- NAME\n".
inline constexpr std::string_view file_separator = "\n--- ";

/// The files of a multi-file input: the bytes up to the first separator are
/// the file `first_name`; each "\n--- NAME\n" starts a file NAME holding the
/// bytes up to the next separator. For example
/// "NRRD0004\n...\ndata file: d.raw\n\n--- d.raw\n<samples>" is a detached
/// header and its data file. Returns nullopt when a NAME is not a plain file
/// name (1-64 letters, digits, '.', '_' or '-', not "." or ".."), repeats a
/// name, or there are more than 16 files: those inputs teach the reader nothing.
inline std::optional<std::vector<InputFile>> split_files(std::string_view input, const std::string& first_name) {
  std::vector<InputFile> files;
  std::set<std::string, std::less<>> names;
  std::string name = first_name;
  for (;;) {
    const size_t end = input.find(file_separator);
    files.push_back({name, std::string(input.substr(0, end))});
    if (!names.insert(name).second || files.size() > 16) return std::nullopt;
    if (end == std::string_view::npos) return files;
    input.remove_prefix(end + file_separator.size());
    const size_t eol = input.find('\n');
    name = std::string(input.substr(0, eol));
    input.remove_prefix(eol == std::string_view::npos ? input.size() : eol + 1);
    if (name.empty() || name.size() > 64 || name == "." || name == "..") return std::nullopt;
    for (const char c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') return std::nullopt;
  }
}

/// `bytes` as a gzip stream (what .nii.gz and NRRD's gzip encoding hold).
inline std::string gzip(std::string_view bytes) {
  z_stream z{};
  if (deflateInit2(&z, Z_BEST_SPEED, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) std::abort();
  std::string out(deflateBound(&z, uLong(bytes.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = uInt(bytes.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = uInt(out.size());
  if (deflate(&z, Z_FINISH) != Z_STREAM_END) std::abort();
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

/// `bytes` as a bzip2 stream (NRRD's bzip2 encoding).
inline std::string bzip2(std::string_view bytes) {
  // bzip2's documented bound: 1% more than the input, plus 600 bytes.
  std::string out(bytes.size() + bytes.size() / 100 + 600, '\0');
  auto length = static_cast<unsigned>(out.size());
  if (BZ2_bzBuffToBuffCompress(out.data(), &length, const_cast<char*>(bytes.data()), unsigned(bytes.size()), 1, 0, 0) !=
      BZ_OK)
    std::abort();
  out.resize(length);
  return out;
}

/// An attached NRRD whose data (everything after the header's blank line) is
/// compressed as its "encoding:" line says, gzip (gz) or bzip2 (bz2); other
/// encodings, and files without a blank line, are returned as they are.
inline std::string compress_nrrd_data(std::string_view nrrd) {
  const size_t blank = nrrd.find("\n\n");
  if (blank == std::string_view::npos) return std::string(nrrd);
  const std::string_view header = nrrd.substr(0, blank + 2), data = nrrd.substr(blank + 2);
  const std::string_view key = "\nencoding:";
  const size_t at = header.find(key);
  if (at == std::string_view::npos) return std::string(nrrd);
  std::string_view value = header.substr(at + key.size());
  value = value.substr(0, value.find('\n'));
  while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) value.remove_prefix(1);
  while (!value.empty() && (value.back() == ' ' || value.back() == '\t' || value.back() == '\r'))
    value.remove_suffix(1);
  if (value == "gzip" || value == "gz") return std::string(header) + gzip(data);
  if (value == "bzip2" || value == "bz2") return std::string(header) + bzip2(data);
  return std::string(nrrd);
}

} // namespace vm::fuzz
