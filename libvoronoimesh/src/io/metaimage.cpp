/// @file io/metaimage.cpp
/// MetaImage (ITK's .mha with the voxel data after the header, .mhd with the
/// data in a separate file). The header is "Key = Value" text, parsed here by
/// hand: it is small, and no Debian library reads it outside ITK.

#include "voronoimesh/io/volume.hpp"

#include "core/input_file.hpp"
#include "core/text.hpp"
#include "io/inflate.hpp"
#include "io/voxel_data.hpp"
#include "voronoimesh/core/errors.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

namespace vm::io {

namespace {

using detail::cat;

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

/// The header's fields, and where the voxel data starts when it is LOCAL.
struct Header {
  std::map<std::string, std::string, std::less<>> fields;
  size_t data_start = 0;
};

/// Reads "Key = Value" lines up to ElementDataFile, which MetaImage requires to
/// be the last one (in a .mha the voxel data follows its line).
Header parse_header(const std::string& path, const std::string& text) {
  Header h;
  size_t pos = 0;
  for (int line_no = 1;; ++line_no) {
    if (pos >= text.size())
      throw InvalidInput(located(path, "no ElementDataFile line (it ends a MetaImage header)"));
    size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    const std::string_view line = trim(std::string_view(text).substr(pos, eol - pos));
    pos = eol + 1;
    if (line.empty()) continue;
    const auto eq = line.find('=');
    if (eq == std::string_view::npos || trim(line.substr(0, eq)).empty())
      throw InvalidInput(located(path, cat("line ", line_no, " is not 'Key = Value' (not a MetaImage header?)")));
    const std::string key(trim(line.substr(0, eq)));
    if (!h.fields.emplace(key, std::string(trim(line.substr(eq + 1)))).second)
      throw InvalidInput(located(path, cat(key, " is given twice")));
    if (key == "ElementDataFile") {
      h.data_start = std::min(pos, text.size());
      return h;
    }
  }
}

/// Typed access to the fields, with messages naming the key.
class Fields {
public:
  Fields(const std::string& path, const Header& h) : path_(path), h_(h) {}

  const std::string* find(std::string_view key) const {
    auto it = h_.fields.find(key);
    return it == h_.fields.end() ? nullptr : &it->second;
  }
  const std::string& required(std::string_view key) const {
    if (auto* v = find(key)) return *v;
    throw InvalidInput(located(path_, cat("no ", key, " (required)")));
  }
  /// The one of `keys` (synonyms) that is given, or nullptr.
  const char* one_of(std::initializer_list<const char*> keys) const {
    const char* found = nullptr;
    for (const char* k : keys)
      if (find(k)) {
        if (found) throw InvalidInput(located(path_, cat("both ", found, " and ", k, " are given")));
        found = k;
      }
    return found;
  }
  bool boolean(std::string_view key, bool fallback) const {
    const std::string* v = find(key);
    if (!v) return fallback;
    if (*v == "True" || *v == "true" || *v == "1") return true;
    if (*v == "False" || *v == "false" || *v == "0") return false;
    throw InvalidInput(located(path_, cat(key, " = '", *v, "' is not True or False")));
  }
  /// Exactly `count` numbers.
  std::vector<double> numbers(std::string_view key, size_t count) const {
    std::vector<double> out;
    std::istringstream in(required(key));
    std::string word;
    while (in >> word) {
      double x;
      if (!detail::parse_number(word, x) || !std::isfinite(x))
        throw InvalidInput(located(path_, cat(key, ": '", word, "' is not a finite number")));
      out.push_back(x);
    }
    if (out.size() != count)
      throw InvalidInput(located(path_, cat(key, " has ", out.size(), " values, NDims is ", count)));
    return out;
  }
  int64_t integer(std::string_view key) const {
    const std::string& v = required(key);
    int64_t x;
    if (!detail::parse_number(v, x))
      throw InvalidInput(located(path_, cat(key, " = '", v, "' is not an integer")));
    return x;
  }

private:
  const std::string& path_;
  const Header& h_;
};

detail::VoxelType element_type(const std::string& path, const std::string& name) {
  using detail::VoxelType;
  static const std::map<std::string, VoxelType, std::less<>> types = {
      {"MET_UCHAR", VoxelType::u8},  {"MET_CHAR", VoxelType::i8},   {"MET_USHORT", VoxelType::u16},
      {"MET_SHORT", VoxelType::i16}, {"MET_UINT", VoxelType::u32},  {"MET_INT", VoxelType::i32},
      {"MET_FLOAT", VoxelType::f32}, {"MET_DOUBLE", VoxelType::f64}};
  auto it = types.find(name);
  if (it == types.end())
    throw InvalidInput(located(path, cat("ElementType ", name,
                                         " is not supported (MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, MET_UINT, "
                                         "MET_INT, MET_FLOAT or MET_DOUBLE)")));
  return it->second;
}

/// Size, components and geometry; a 2-D image is one slice of a 3-D volume.
void read_geometry(const std::string& path, const Fields& f, Volume& v) {
  if (f.required("ObjectType") != "Image")
    throw InvalidInput(located(path, cat("ObjectType is '", f.required("ObjectType"), "', not Image")));
  const int64_t nd = f.integer("NDims");
  if (nd != 2 && nd != 3) throw InvalidInput(located(path, cat("NDims is ", nd, ", only 2 or 3 are read")));
  const size_t n = size_t(nd);
  const std::vector<double> dims = f.numbers("DimSize", n);
  v.size[2] = 1;
  for (size_t a = 0; a < n; ++a) {
    if (dims[a] != std::floor(dims[a]) || dims[a] < 1 || dims[a] > 9e18)
      throw InvalidInput(located(path, cat("DimSize value ", dims[a], " is not a positive integer")));
    v.size[a] = int64_t(dims[a]);
  }
  if (f.find("ElementNumberOfChannels")) {
    const int64_t c = f.integer("ElementNumberOfChannels");
    if (c < 1 || c > std::numeric_limits<int>::max())
      throw InvalidInput(located(path, cat("ElementNumberOfChannels is ", c, ", must be >= 1")));
    v.components = int(c);
  }
  Eigen::Matrix3d steps = Eigen::Matrix3d::Identity();
  Vec3 origin = Vec3::Zero();
  // ElementSpacing is the distance between voxel centres; ElementSize, the
  // voxel's physical extent, stands in for it when it is absent (as in ITK).
  if (const char* key = f.find("ElementSpacing") ? "ElementSpacing" : f.find("ElementSize") ? "ElementSize" : nullptr) {
    const std::vector<double> s = f.numbers(key, n);
    for (size_t a = 0; a < n; ++a) {
      if (!(s[a] > 0)) throw InvalidInput(located(path, cat(key, " value ", s[a], " is not > 0")));
      steps(a, a) = s[a];
    }
  } else {
    v.spacing_stated = false;
  }
  if (const char* key = f.one_of({"TransformMatrix", "Rotation", "Orientation"})) {
    // Row-major as written, each run of NDims values one axis direction (ITK's reading).
    const std::vector<double> m = f.numbers(key, n * n);
    Eigen::Matrix3d dir = Eigen::Matrix3d::Identity();
    for (size_t a = 0; a < n; ++a)
      for (size_t b = 0; b < n; ++b) dir(b, a) = m[a * n + b];
    steps = dir * steps;
  }
  if (const char* key = f.one_of({"Offset", "Origin", "Position"})) {
    const std::vector<double> o = f.numbers(key, n);
    for (size_t a = 0; a < n; ++a) origin[a] = o[a];
  }
  detail::set_voxel_axes(v, steps, origin, path);
}

/// The bytes holding the voxel data (still compressed when CompressedData):
/// after the header for LOCAL, else the named file, relative to the header.
std::string_view data_bytes(const std::string& path, const Fields& f, const std::string& text, size_t data_start,
                            std::string& storage, uint64_t raw_bytes, bool compressed) {
  const std::string& name = f.required("ElementDataFile");
  int64_t skip = f.find("HeaderSize") ? f.integer("HeaderSize") : 0;
  if (skip < -1) throw InvalidInput(located(path, cat("HeaderSize is ", skip, ", must be >= -1")));
  if (skip == -1 && compressed)
    throw InvalidInput(located(path, "HeaderSize = -1 (data at the end of the file) needs uncompressed data"));
  std::string_view bytes;
  if (name == "LOCAL") {
    if (skip != 0) throw InvalidInput(located(path, "HeaderSize is only read with a separate ElementDataFile"));
    bytes = std::string_view(text).substr(data_start);
  } else {
    if (name == "LIST" || name.starts_with("LIST "))
      throw InvalidInput(located(path, "ElementDataFile = LIST (one file per slice) is not supported"));
    if (name.find('%') != std::string::npos)
      throw InvalidInput(located(path, cat("ElementDataFile '", name, "' is a file-name pattern, not supported")));
    const std::filesystem::path data_path = std::filesystem::path(path).parent_path() / name;
    try {
      // A device or a pipe (/dev/zero, /dev/stdin) is refused, not read without end.
      storage = detail::read_text_file(data_path.string(), UINT64_MAX, "a data file");
    } catch (const IoError& e) {
      throw IoError(located(path, cat("ElementDataFile ", e.what())));
    } catch (const InvalidInput& e) {
      throw InvalidInput(located(path, cat("ElementDataFile ", e.what())));
    }
    bytes = storage;
    if (skip == -1) skip = int64_t(bytes.size() >= raw_bytes ? bytes.size() - raw_bytes : 0);
    if (uint64_t(skip) > bytes.size())
      throw InvalidInput(located(path, cat("HeaderSize ", skip, " is beyond the end of ", data_path.string())));
    bytes.remove_prefix(size_t(skip));
  }
  return bytes;
}

} // namespace

Volume read_metaimage(const std::string& path) {
  const std::string text = detail::read_text_file(path, UINT64_MAX, "a MetaImage file");
  const Header h = parse_header(path, text);
  const Fields f(path, h);
  Volume v;
  read_geometry(path, f, v);
  v.world = WorldFrame::lps; // ITK's physical space, whatever AnatomicalOrientation says of the voxel order
  const detail::VoxelType type = element_type(path, f.required("ElementType"));
  if (!f.boolean("BinaryData", true))
    throw InvalidInput(located(path, "BinaryData = False (voxels as text) is not supported"));
  // Absent: the writer's byte order, little-endian on every current machine.
  bool msb = f.boolean("BinaryDataByteOrderMSB", false);
  if (f.find("ElementByteOrderMSB")) {
    const bool element_msb = f.boolean("ElementByteOrderMSB", msb);
    if (f.find("BinaryDataByteOrderMSB") && element_msb != msb)
      throw InvalidInput(located(path, "BinaryDataByteOrderMSB and ElementByteOrderMSB disagree"));
    msb = element_msb;
  }
  const bool compressed = f.boolean("CompressedData", false);
  const uint64_t needed = detail::voxel_data_bytes(path, v, type);
  std::string storage;
  std::string_view bytes = data_bytes(path, f, text, h.data_start, storage, needed, compressed);
  std::string inflated;
  if (compressed) {
    if (f.find("CompressedDataSize")) {
      const int64_t size = f.integer("CompressedDataSize");
      if (size < 1) throw InvalidInput(located(path, cat("CompressedDataSize is ", size, ", must be >= 1")));
      if (uint64_t(size) > bytes.size())
        throw InvalidInput(located(path, cat("truncated: CompressedDataSize is ", size, ", the file holds ",
                                             bytes.size(), " bytes of compressed data")));
      bytes = bytes.substr(0, size_t(size));
    }
    detail::check_inflatable(path, needed, bytes.size());
    inflated = detail::inflate_exactly(path, bytes, size_t(needed));
    bytes = inflated;
  } else {
    detail::check_voxel_data_length(path, needed, bytes.size());
  }
  detail::decode_voxels(v, reinterpret_cast<const unsigned char*>(bytes.data()), type, msb, path);
  return v;
}

} // namespace vm::io
