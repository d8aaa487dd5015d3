/// @file io/ply_format.cpp
/// The PLY header parser and scalar decoding behind read_ply and labelled PLY
/// point clouds.

#include "io/ply_format.hpp"

#include "core/input_file.hpp"
#include "core/memory.hpp"
#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/write_mesh.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace vm::io::ply {

namespace {

using detail::cat;
using detail::parse_number;

std::optional<ScalarType> scalar_type(std::string_view name) {
  if (name == "char" || name == "int8") return ScalarType{1, Kind::int_signed};
  if (name == "uchar" || name == "uint8") return ScalarType{1, Kind::int_unsigned};
  if (name == "short" || name == "int16") return ScalarType{2, Kind::int_signed};
  if (name == "ushort" || name == "uint16") return ScalarType{2, Kind::int_unsigned};
  if (name == "int" || name == "int32") return ScalarType{4, Kind::int_signed};
  if (name == "uint" || name == "uint32") return ScalarType{4, Kind::int_unsigned};
  if (name == "float" || name == "float32") return ScalarType{4, Kind::floating};
  if (name == "double" || name == "float64") return ScalarType{8, Kind::floating};
  return std::nullopt;
}

template <class T>
T load(const unsigned char* b) {
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

std::string slurp(const std::string& path) {
  detail::refuse_beyond_memory(double(detail::require_regular_file(path)), path, "reading it");
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f) throw IoError(located(path, cat("cannot open: ", std::strerror(errno))));
  const std::streamoff size = f.tellg();
  if (size < 0) throw IoError(located(path, "cannot determine the file size"));
  std::string data(size_t(size), '\0');
  f.seekg(0);
  f.read(data.data(), std::streamsize(size));
  if (f.gcount() != std::streamsize(size)) throw IoError(located(path, cat("read failed: ", std::strerror(errno))));
  return data;
}

/// "not a PLY file", and for a mesh format voronoimesh writes (a .msh or .vtu
/// given to stats or smooth) that meshes are read back from PLY only.
std::string not_a_ply(const std::string& path) {
  const std::string extension = detail::lower(std::filesystem::path(path).extension().string());
  const auto& writable = output_extensions();
  if (extension == ".ply" || std::find(writable.begin(), writable.end(), extension) == writable.end())
    return "not a PLY file (no 'ply' line)";
  return cat("a ", extension, " file, not a PLY: voronoimesh reads meshes back from PLY only (mesh with -o NAME.ply, "
             "which keeps the phases, their names and the grid spacing)");
}

} // namespace

uint64_t Element::min_bytes() const {
  uint64_t b = 0;
  for (const auto& p : props) b += uint64_t(p.count ? p.count->size : p.type.size);
  return b;
}

const Property* Element::find(std::string_view n) const {
  for (const auto& p : props)
    if (p.name == n) return &p;
  return nullptr;
}

const Element* Header::element(std::string_view n) const {
  for (const auto& e : elements)
    if (e.name == n) return &e;
  return nullptr;
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) words.push_back(line.substr(i, j - i));
    i = j;
  }
  return words;
}

File::File(const std::string& path) : path_(path), data_(slurp(path)) {
  if (data_.empty()) fail("empty file");
  header_ = parse_header();
  pos_ = header_.body;
}

void File::fail(const std::string& what) const { throw IoError(located(path_, what)); }

// ---- header ----------------------------------------------------------------

Header File::parse_header() {
  Header h;
  size_t at = 0, line_no = 0;
  bool have_format = false;
  for (;;) {
    const size_t nl = data_.find('\n', at);
    if (nl == std::string::npos) {
      if (line_no == 0 && data_.compare(0, 3, "ply") != 0) fail(not_a_ply(path_));
      fail("header has no end_header line (truncated or not a PLY file)");
    }
    std::string_view line(data_.data() + at, nl - at);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    at = nl + 1;
    if (line_no++ == 0) {
      if (line != "ply") fail(not_a_ply(path_));
      continue;
    }
    const auto w = split_words(line);
    if (w.empty()) continue;
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() != 3) fail(cat("bad format line '", line, "'"));
      if (w[1] == "ascii")
        h.format = Format::ascii;
      else if (w[1] == "binary_little_endian")
        h.format = Format::binary_le;
      else if (w[1] == "binary_big_endian")
        h.format = Format::binary_be;
      else
        fail(cat("unknown PLY format '", w[1], "'"));
      if (w[2].substr(0, 2) != "1.") fail(cat("unsupported PLY version '", w[2], "'"));
      have_format = true;
    } else if (w[0] == "comment") {
      h.comments.emplace_back(line);
    } else if (w[0] == "obj_info") {
      continue;
    } else if (w[0] == "element") {
      Element e;
      if (w.size() != 3 || !parse_number(w[2], e.count)) fail(cat("bad element line '", line, "'"));
      e.name = std::string(w[1]);
      h.elements.push_back(std::move(e));
    } else if (w[0] == "property") {
      if (h.elements.empty()) fail(cat("property before any element: '", line, "'"));
      h.elements.back().props.push_back(parse_property(line, w));
    } else {
      fail(cat("unexpected header line '", line, "'"));
    }
  }
  if (!have_format) fail("header has no format line");
  h.body = at;
  return h;
}

Property File::parse_property(std::string_view line, const std::vector<std::string_view>& w) {
  Property p;
  if (w.size() == 3 && w[1] != "list") {
    auto t = scalar_type(w[1]);
    if (!t) fail(cat("unknown property type in '", line, "'"));
    p.type = *t;
    p.name = std::string(w[2]);
  } else if (w.size() == 5 && w[1] == "list") {
    auto c = scalar_type(w[2]), t = scalar_type(w[3]);
    if (!c || !t || c->kind == Kind::floating) fail(cat("bad list property '", line, "'"));
    p.count = *c;
    p.type = *t;
    p.name = std::string(w[4]);
  } else {
    fail(cat("bad property line '", line, "'"));
  }
  return p;
}

// ---- body ------------------------------------------------------------------

void File::read_body(const std::function<bool(const Element&)>& read) {
  pos_ = header_.body;
  for (const Element& e : header_.elements) {
    check_fits(e);
    // An element without properties takes no bytes, whatever its count (a
    // corrupt header's 10^10 items must not be skipped one by one).
    if (!read(e) && !e.props.empty())
      for (uint64_t i = 0; i < e.count; ++i)
        for (const auto& p : e.props) skip(e, i, p);
  }
  check_end();
}

/// Refuses counts that cannot fit in the rest of the file, before anything is
/// allocated for them.
void File::check_fits(const Element& e) {
  const uint64_t per_item = header_.format == Format::ascii ? 2 * e.props.size() : e.min_bytes();
  if (per_item == 0) return;
  if (e.count > (uint64_t(remaining()) + 1) / per_item)
    fail(cat("truncated: element '", e.name, "' declares ", e.count, " items but only ", remaining(), " bytes remain"));
}

File::Status File::read_scalar(const ScalarType& t, double& v, std::string_view& bad) {
  if (header_.format == Format::ascii) return ascii_scalar(t, v, bad);
  if (remaining() < size_t(t.size)) return Status::truncated;
  unsigned char b[8];
  std::memcpy(b, data_.data() + pos_, size_t(t.size));
  pos_ += size_t(t.size);
  const bool swap = (header_.format == Format::binary_be) != (std::endian::native == std::endian::big);
  if (swap) std::reverse(b, b + t.size);
  switch (t.size) {
  case 1: v = t.kind == Kind::int_signed ? double(int8_t(b[0])) : double(b[0]); break;
  case 2: v = t.kind == Kind::int_signed ? double(load<int16_t>(b)) : double(load<uint16_t>(b)); break;
  case 4:
    if (t.kind == Kind::floating)
      v = double(load<float>(b));
    else
      v = t.kind == Kind::int_signed ? double(load<int32_t>(b)) : double(load<uint32_t>(b));
    break;
  default: v = load<double>(b);
  }
  return Status::ok;
}

File::Status File::ascii_scalar(const ScalarType& t, double& v, std::string_view& bad) {
  while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
  if (pos_ == data_.size()) return Status::truncated;
  size_t end = pos_;
  while (end < data_.size() && !std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
  const std::string_view tok(data_.data() + pos_, end - pos_);
  pos_ = end;
  bool ok = false;
  if (t.kind == Kind::floating) {
    ok = parse_number(tok, v);
  } else {
    int64_t i = 0;
    ok = parse_number(tok, i);
    v = double(i);
  }
  bad = tok;
  return ok ? Status::ok : Status::bad_number;
}

bool is_int32(double v) {
  return v == std::floor(v) && v >= std::numeric_limits<int32_t>::min() && v <= std::numeric_limits<int32_t>::max();
}

void File::not_int32(double v, const std::string& what) const {
  fail(cat("value ", v, " is not a 32-bit integer in ", what));
}

void File::skip(const Element& e, uint64_t i, const Property& p) {
  const auto what = [&] { return cat(e.name, " ", i, " property ", p.name); };
  const auto skip_scalar = [&](const ScalarType& t) {
    if (header_.format != Format::ascii && remaining() >= size_t(t.size))
      pos_ += size_t(t.size);
    else
      scalar(t, what); // reads (and checks) the token, or reports truncation
  };
  if (!p.count) {
    skip_scalar(p.type);
    return;
  }
  const int32_t n = int_scalar(*p.count, what);
  if (n < 0) fail(cat("negative list length in ", what()));
  for (int32_t k = 0; k < n; ++k) skip_scalar(p.type);
}

void File::check_end() {
  size_t end = pos_;
  if (header_.format == Format::ascii)
    while (end < data_.size() && std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
  if (end != data_.size()) fail(cat(data_.size() - end, " bytes of unexpected data after the last element"));
}

} // namespace vm::io::ply
