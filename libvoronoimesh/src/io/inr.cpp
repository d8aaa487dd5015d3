/// @file io/inr.cpp
/// INRIMAGE-4 (.inr, .inr.gz), the format CGAL's mesh generator reads label
/// images in: a text header of KEY=VALUE lines padded to a multiple of 256
/// bytes, then the raw voxels (components interleaved). zlib's gzread reads
/// plain and gzip-compressed files alike.

#include "voronoimesh/io/volume.hpp"

#include "core/huge_pages.hpp"
#include "core/text.hpp"
#include "io/voxel_data.hpp"
#include "voronoimesh/core/errors.hpp"

#include <zlib.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>

namespace vm::io {

namespace {

using detail::cat;

constexpr std::string_view magic = "#INRIMAGE-4#{\n";
constexpr std::string_view header_end = "##}\n";
constexpr size_t block = 256;
constexpr size_t max_header = 1 << 20; // far beyond any real header; stops a search through garbage

struct GzCloser {
  void operator()(gzFile_s* g) const { gzclose(g); }
};
using GzFile = std::unique_ptr<gzFile_s, GzCloser>;

/// "read error (<zlib's reason>)" for the last failed gzread.
std::string gz_reason(gzFile g) {
  int code = 0;
  const char* msg = gzerror(g, &code);
  if (code == Z_ERRNO) return std::strerror(errno);
  return msg && *msg ? msg : "unknown error";
}

/// Reads up to `n` bytes; fewer only at the end of the data.
size_t read_some(const std::string& path, gzFile g, char* out, size_t n) {
  size_t done = 0;
  while (done < n) {
    const unsigned want = unsigned(std::min<size_t>(n - done, 1u << 30));
    const int got = gzread(g, out + done, want);
    if (got < 0) throw InvalidInput(located(path, cat("corrupt or truncated data (", gz_reason(g), ")")));
    if (got == 0) break;
    done += size_t(got);
  }
  return done;
}

/// The header text, from the magic line to the end marker that closes its
/// last 256-byte block.
std::string read_header(const std::string& path, gzFile g) {
  std::string header;
  char buf[block];
  while (true) {
    const size_t got = read_some(path, g, buf, block);
    if (header.empty() && std::string_view(buf, got).substr(0, magic.size()) != magic)
      throw InvalidInput(located(path, "not an INR file (no #INRIMAGE-4#{ magic)"));
    header.append(buf, got);
    const size_t end = header.find(header_end, header.size() - got);
    if (end != std::string::npos && end + header_end.size() != header.size())
      throw InvalidInput(located(path, "the ##} end of header is not at a 256-byte boundary"));
    if (got < block)
      throw InvalidInput(located(path, cat("truncated header (", header.size(), " bytes and no ##} end)")));
    if (end != std::string::npos) return header;
    if (header.size() >= max_header)
      throw InvalidInput(located(path, cat("no ##} end of header in the first ", max_header, " bytes")));
  }
}

double number(const std::string& path, const std::string& key, const std::string& value) {
  double x;
  if (!detail::parse_number(value, x) || !std::isfinite(x))
    throw InvalidInput(located(path, cat(key, "=", value, " is not a finite number")));
  return x;
}

int64_t count(const std::string& path, const std::string& key, const std::string& value) {
  int64_t x;
  if (!detail::parse_number(value, x) || x < 1)
    throw InvalidInput(located(path, cat(key, "=", value, " is not a positive integer")));
  return x;
}

/// KEY=VALUE fields of the header; '#' lines are comments.
std::map<std::string, std::string> parse_fields(const std::string& path, const std::string& header) {
  std::map<std::string, std::string> fields;
  size_t pos = magic.size();
  const size_t stop = header.size() - header_end.size();
  for (int line_no = 2; pos < stop; ++line_no) {
    const size_t eol = header.find('\n', pos);
    std::string line = header.substr(pos, eol - pos);
    line.erase(line.find_last_not_of(" \t\r") + 1); // trailing blanks some writers leave
    pos = eol + 1;
    if (line.empty() || line[0] == '#') continue;
    const size_t eq = line.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InvalidInput(located(path, cat("header line ", line_no, " '", line, "' is not KEY=VALUE")));
    if (!fields.emplace(line.substr(0, eq), line.substr(eq + 1)).second)
      throw InvalidInput(located(path, cat(line.substr(0, eq), " is given twice")));
  }
  return fields;
}

detail::VoxelType voxel_type(const std::string& path, const std::string& type, const std::string& pixsize) {
  using detail::VoxelType;
  static const std::map<std::pair<std::string, std::string>, VoxelType> types = {
      {{"unsigned fixed", "8 bits"}, VoxelType::u8},  {{"signed fixed", "8 bits"}, VoxelType::i8},
      {{"unsigned fixed", "16 bits"}, VoxelType::u16}, {{"signed fixed", "16 bits"}, VoxelType::i16},
      {{"unsigned fixed", "32 bits"}, VoxelType::u32}, {{"signed fixed", "32 bits"}, VoxelType::i32},
      {{"float", "32 bits"}, VoxelType::f32},          {{"float", "64 bits"}, VoxelType::f64}};
  auto it = types.find({type, pixsize});
  if (it == types.end())
    throw InvalidInput(located(path, cat("TYPE=", type, " with PIXSIZE=", pixsize,
                                         " is not supported (8/16/32-bit fixed, 32/64-bit float)")));
  return it->second;
}

/// True for big-endian data.
bool big_endian(const std::string& path, const std::map<std::string, std::string>& fields, detail::VoxelType type) {
  auto it = fields.find("CPU");
  if (it == fields.end()) {
    if (detail::voxel_type_bytes(type) == 1) return false;
    throw InvalidInput(located(path, "no CPU line: the byte order of multi-byte voxels is unknown"));
  }
  const std::string& cpu = it->second;
  if (cpu == "decm" || cpu == "alpha" || cpu == "pc") return false;
  if (cpu == "sun" || cpu == "sgi") return true;
  throw InvalidInput(located(path, cat("CPU=", cpu, " is not decm, alpha, pc, sun or sgi")));
}

/// Size, components, spacing and origin. TX/TY/TZ place voxel (0, 0, 0) (as CGAL
/// writes and reads them); XO/YO/ZO and RX/RY/RZ mean different things to
/// different writers (CGAL keeps XO as an integer centre), so only 0 is read.
void read_geometry(const std::string& path, const std::map<std::string, std::string>& fields, Volume& v) {
  auto get = [&](const char* key) -> const std::string* {
    auto it = fields.find(key);
    return it == fields.end() ? nullptr : &it->second;
  };
  const char* dims[] = {"XDIM", "YDIM", "ZDIM"};
  for (int a = 0; a < 3; ++a) {
    const std::string* value = get(dims[a]);
    if (!value) throw InvalidInput(located(path, cat("no ", dims[a], " (required)")));
    v.size[a] = count(path, dims[a], *value);
  }
  if (const std::string* value = get("VDIM")) {
    const int64_t c = count(path, "VDIM", *value);
    if (c > std::numeric_limits<int>::max()) throw InvalidInput(located(path, cat("VDIM=", c, " is too large")));
    v.components = int(c);
  }
  const char* spacing[] = {"VX", "VY", "VZ"};
  const char* translation[] = {"TX", "TY", "TZ"};
  Eigen::Matrix3d steps = Eigen::Matrix3d::Identity();
  Vec3 origin = Vec3::Zero();
  for (int a = 0; a < 3; ++a) {
    if (const std::string* value = get(spacing[a])) {
      steps(a, a) = number(path, spacing[a], *value);
      if (!(steps(a, a) > 0)) throw InvalidInput(located(path, cat(spacing[a], "=", *value, " is not > 0")));
    } else {
      v.spacing_stated = false;
    }
    if (const std::string* value = get(translation[a])) origin[a] = number(path, translation[a], *value);
  }
  for (const char* key : {"XO", "YO", "ZO", "RX", "RY", "RZ"})
    if (const std::string* value = get(key); value && number(path, key, *value) != 0)
      throw InvalidInput(located(path, cat(key, "=", *value, " is not supported (use TX/TY/TZ for the origin)")));
  if (const std::string* value = get("SCALE"); value && *value != "2**0")
    throw InvalidInput(located(path, cat("SCALE=", *value, " (fixed-point scaling) is not supported")));
  detail::set_voxel_axes(v, steps, origin, path);
}

} // namespace

Volume read_inr(const std::string& path) {
  GzFile g(gzopen(path.c_str(), "rb"));
  if (!g) throw IoError(located(path, cat("cannot open (", std::strerror(errno), ")")));
  const std::string header = read_header(path, g.get());
  const auto fields = parse_fields(path, header);
  Volume v;
  read_geometry(path, fields, v);
  auto field = [&](const char* key) {
    auto it = fields.find(key);
    if (it == fields.end()) throw InvalidInput(located(path, cat("no ", key, " (required)")));
    return it->second;
  };
  const detail::VoxelType type = voxel_type(path, field("TYPE"), field("PIXSIZE"));
  const bool msb = big_endian(path, fields, type);
  const uint64_t needed = detail::voxel_data_bytes(path, v, type);
  // Check the sizes against the file before allocating what the header asks for.
  std::error_code ec;
  const uint64_t file_size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(located(path, cat("cannot read (", ec.message(), ")")));
  if (gzdirect(g.get()))
    detail::check_voxel_data_length(path, needed, file_size - header.size());
  else
    detail::check_inflatable(path, needed, file_size);
  std::string data;
  detail::resize_on_huge_pages(data, size_t(needed));
  const size_t got = read_some(path, g.get(), data.data(), data.size());
  if (got < needed)
    throw InvalidInput(located(path, cat("truncated: the header describes ", needed, " bytes of voxel data, the file holds ",
                                         got)));
  char extra;
  if (read_some(path, g.get(), &extra, 1) != 0)
    throw InvalidInput(located(path, cat("holds more than the ", needed, " bytes of voxel data the header describes (wrong sizes or type?)")));
  detail::decode_voxels(v, reinterpret_cast<const unsigned char*>(data.data()), type, msb, path);
  return v;
}

} // namespace vm::io
