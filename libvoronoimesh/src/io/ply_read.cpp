/// @file io/ply_read.cpp
/// read_ply: a small strict PLY reader for node-level interface meshes. It
/// accepts ascii and both binary byte orders and any scalar types, skips
/// properties and elements it does not need, and checks every count against the
/// bytes left before allocating, so bad input gives an IoError, never a crash.

#include "voronoimesh/io/ply.hpp"

#include "detail/text.hpp"
#include "voronoimesh/errors.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vm::io {

namespace {

using detail::cat;
using detail::parse_number;

enum class Format { ascii, binary_le, binary_be };

enum class Kind { int_signed, int_unsigned, floating };

struct ScalarType {
  int size = 0;
  Kind kind = Kind::int_signed;
};

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

struct Property {
  std::string name;
  ScalarType type;                 ///< the item type for a list
  std::optional<ScalarType> count; ///< set for a list property
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;

  /// Fewest bytes (binary) one item can take: every list empty.
  uint64_t min_bytes() const {
    uint64_t b = 0;
    for (const auto& p : props) b += uint64_t(p.count ? p.count->size : p.type.size);
    return b;
  }
};

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  std::optional<Box> domain;
  std::map<int32_t, std::string> phase_names; ///< by label, from "comment phase <label> <name>"
  size_t body = 0; ///< offset of the first byte after end_header
};

std::vector<std::string_view> split(std::string_view line) {
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

class Reader {
public:
  Reader(std::string path, std::string data) : path_(std::move(path)), data_(std::move(data)) {}

  NodeMesh read() {
    if (data_.empty()) fail("empty file");
    header_ = parse_header();
    const Layout layout = find_layout();
    pos_ = header_.body;
    NodeMesh m;
    for (const Element& e : header_.elements) {
      check_fits(e);
      if (&e == layout.vertex)
        read_vertices(layout, m);
      else if (&e == layout.face)
        read_faces(layout, m);
      else
        for (uint64_t i = 0; i < e.count; ++i)
          for (const auto& p : e.props) skip(e, i, p);
    }
    check_end();
    for (size_t t = 0; t < m.triangles.size(); ++t)
      for (int32_t v : m.triangles[t])
        if (v < 0 || size_t(v) >= m.points.size())
          fail(cat("face ", t, ": vertex index ", v, " out of range (", m.points.size(), " vertices)"));
    compact_phases(m);
    m.domain = header_.domain ? *header_.domain : bounding_box(m.points);
    return m;
  }

private:
  [[noreturn]] void fail(const std::string& what) const { throw IoError(located(path_, what)); }

  // ---- header ------------------------------------------------------------

  Header parse_header() {
    Header h;
    size_t at = 0, line_no = 0;
    bool have_format = false;
    for (;;) {
      const size_t nl = data_.find('\n', at);
      if (nl == std::string::npos) {
        if (line_no == 0 && data_.compare(0, 3, "ply") != 0) fail("not a PLY file (no 'ply' line)");
        fail("header has no end_header line (truncated or not a PLY file)");
      }
      std::string_view line(data_.data() + at, nl - at);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      at = nl + 1;
      if (line_no++ == 0) {
        if (line != "ply") fail("not a PLY file (no 'ply' line)");
        continue;
      }
      const auto w = split(line);
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
        parse_comment(line, w, h);
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

  Property parse_property(std::string_view line, const std::vector<std::string_view>& w) {
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

  /// "comment domain x0 y0 z0 x1 y1 z1" and "comment phase <label> <name>", as
  /// write_ply stores them; any other comment is ignored.
  void parse_comment(std::string_view line, const std::vector<std::string_view>& w, Header& h) {
    if (w.size() == 8 && w[1] == "domain") {
      std::array<double, 6> v{};
      for (size_t i = 0; i < 6; ++i)
        if (!parse_number(w[i + 2], v[i]) || !std::isfinite(v[i])) fail(cat("bad domain comment '", line, "'"));
      h.domain = Box{Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5])};
    } else if (w.size() >= 3 && w[1] == "phase") {
      int32_t label = 0;
      if (!parse_number(w[2], label)) fail(cat("bad phase comment '", line, "'"));
      const size_t name_at = size_t(w[2].data() + w[2].size() - line.data());
      std::string_view name = line.substr(std::min(line.size(), name_at + 1));
      if (!h.phase_names.emplace(label, std::string(name)).second) fail(cat("phase ", label, " is described twice"));
    }
  }

  // ---- body --------------------------------------------------------------

  size_t remaining() const { return data_.size() - pos_; }

  /// Refuses counts that cannot fit in the rest of the file, before anything
  /// is allocated for them.
  void check_fits(const Element& e) {
    uint64_t per_item = header_.format == Format::ascii ? 2 * e.props.size() : e.min_bytes();
    if (per_item == 0) return;
    if (e.count > (uint64_t(remaining()) + 1) / per_item)
      fail(cat("truncated: element '", e.name, "' declares ", e.count, " items but only ", remaining(),
               " bytes remain"));
  }

  /// Reads one scalar of type t; `what` names the item for error messages.
  template <class What>
  double scalar(const ScalarType& t, What&& what) {
    if (header_.format == Format::ascii) return ascii_scalar(t, what);
    if (remaining() < size_t(t.size)) fail(cat("truncated in ", what()));
    unsigned char b[8];
    std::memcpy(b, data_.data() + pos_, size_t(t.size));
    pos_ += size_t(t.size);
    const bool swap = (header_.format == Format::binary_be) != (std::endian::native == std::endian::big);
    if (swap) std::reverse(b, b + t.size);
    switch (t.size) {
    case 1: return t.kind == Kind::int_signed ? double(int8_t(b[0])) : double(b[0]);
    case 2: return t.kind == Kind::int_signed ? double(load<int16_t>(b)) : double(load<uint16_t>(b));
    case 4:
      if (t.kind == Kind::floating) return double(load<float>(b));
      return t.kind == Kind::int_signed ? double(load<int32_t>(b)) : double(load<uint32_t>(b));
    default: return load<double>(b);
    }
  }

  template <class T>
  static T load(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }

  template <class What>
  double ascii_scalar(const ScalarType& t, What&& what) {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    if (pos_ == data_.size()) fail(cat("truncated in ", what()));
    size_t end = pos_;
    while (end < data_.size() && !std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
    std::string_view tok(data_.data() + pos_, end - pos_);
    pos_ = end;
    double v = 0;
    bool ok = false;
    if (t.kind == Kind::floating) {
      ok = parse_number(tok, v);
    } else {
      int64_t i = 0;
      ok = parse_number(tok, i);
      v = double(i);
    }
    if (!ok) fail(cat("bad number '", tok.substr(0, 40), "' in ", what()));
    return v;
  }

  /// An integer-valued scalar that fits int32 (indices, counts, phases).
  template <class What>
  int32_t int_scalar(const ScalarType& t, What&& what) {
    const double v = scalar(t, what);
    if (!(v == std::floor(v)) || v < std::numeric_limits<int32_t>::min() || v > std::numeric_limits<int32_t>::max())
      fail(cat("value ", v, " is not a 32-bit integer in ", what()));
    return int32_t(v);
  }

  void skip(const Element& e, uint64_t i, const Property& p) {
    auto what = [&] { return cat(e.name, " ", i, " property ", p.name); };
    if (!p.count) {
      skip_scalar(p.type, what);
      return;
    }
    const int32_t n = int_scalar(*p.count, what);
    if (n < 0) fail(cat("negative list length in ", what()));
    for (int32_t k = 0; k < n; ++k) skip_scalar(p.type, what);
  }

  template <class What>
  void skip_scalar(const ScalarType& t, What&& what) {
    if (header_.format != Format::ascii && remaining() >= size_t(t.size))
      pos_ += size_t(t.size);
    else
      scalar(t, what); // reads (and checks) the token, or reports truncation
  }

  static const Property* find(const Element& e, std::string_view name) {
    for (const auto& p : e.props)
      if (p.name == name) return &p;
    return nullptr;
  }

  /// The elements and properties read_ply needs, found (or refused) from the
  /// header alone, before any body byte is read.
  struct Layout {
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    std::array<const Property*, 3> xyz{};
    const Property* indices = nullptr;
    const Property* phase0 = nullptr;
    const Property* phase1 = nullptr;
  };

  Layout find_layout() const {
    Layout l;
    for (const Element& e : header_.elements) {
      if (e.name == "vertex" && !l.vertex) l.vertex = &e;
      if (e.name == "face" && !l.face) l.face = &e;
    }
    if (!l.vertex) fail("no vertex element");
    if (!l.face) fail("no face element (not a voronoimesh PLY?)");
    if (l.vertex->count > uint64_t(std::numeric_limits<int32_t>::max())) fail("too many vertices");
    if (l.face->count > uint64_t(std::numeric_limits<int32_t>::max())) fail("too many faces");
    const char* const names[3] = {"x", "y", "z"};
    for (size_t a = 0; a < 3; ++a) {
      l.xyz[a] = find(*l.vertex, names[a]);
      if (!l.xyz[a] || l.xyz[a]->count) fail(cat("vertex property ", names[a], " missing"));
    }
    l.indices = find(*l.face, "vertex_indices");
    if (!l.indices) l.indices = find(*l.face, "vertex_index");
    if (!l.indices || !l.indices->count) fail("face property vertex_indices missing");
    l.phase0 = find(*l.face, "phase0");
    l.phase1 = find(*l.face, "phase1");
    if (!l.phase0 || l.phase0->count) fail("face property phase0 missing (not a voronoimesh PLY?)");
    if (!l.phase1 || l.phase1->count) fail("face property phase1 missing (not a voronoimesh PLY?)");
    return l;
  }

  void read_vertices(const Layout& l, NodeMesh& m) {
    const Element& e = *l.vertex;
    m.points.resize(size_t(e.count));
    for (uint64_t i = 0; i < e.count; ++i) {
      Vec3& p = m.points[size_t(i)];
      for (const auto& prop : e.props) {
        const auto slot = std::find(l.xyz.begin(), l.xyz.end(), &prop);
        if (slot == l.xyz.end())
          skip(e, i, prop);
        else
          p[slot - l.xyz.begin()] = scalar(prop.type, [&] { return cat("vertex ", i); });
      }
    }
  }

  void read_faces(const Layout& l, NodeMesh& m) {
    const Element& e = *l.face;
    m.triangles.resize(size_t(e.count));
    m.pairs.resize(size_t(e.count));
    for (uint64_t i = 0; i < e.count; ++i) {
      auto what = [&] { return cat("face ", i); };
      for (const auto& prop : e.props) {
        if (&prop == l.indices) {
          const int32_t n = int_scalar(*prop.count, what);
          if (n != 3) fail(cat("face ", i, " has ", n, " vertices (only triangles are supported)"));
          for (auto& v : m.triangles[size_t(i)]) v = int_scalar(prop.type, what);
        } else if (&prop == l.phase0) {
          m.pairs[size_t(i)][0] = int_scalar(prop.type, what);
        } else if (&prop == l.phase1) {
          m.pairs[size_t(i)][1] = int_scalar(prop.type, what);
        } else {
          skip(e, i, prop);
        }
      }
    }
  }

  /// Turns the labels in the file (from the phase comments and the faces) into
  /// phase ids 0..N-1 in increasing order, keeping the labels in phase_labels
  /// when they are not 0..N-1 themselves, so writing the mesh again gives the
  /// same labels.
  void compact_phases(NodeMesh& m) const {
    std::vector<int32_t> labels;
    for (const auto& [label, name] : header_.phase_names) labels.push_back(label);
    for (const PhasePair& p : m.pairs) labels.insert(labels.end(), p.begin(), p.end());
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    // Phase ids fit int16 everywhere (PhaseSet).
    if (labels.size() > size_t(std::numeric_limits<int16_t>::max()))
      fail(cat(labels.size(), " distinct phases (at most ", std::numeric_limits<int16_t>::max(), ")"));
    for (PhasePair& p : m.pairs)
      for (int32_t& phase : p) phase = int32_t(std::lower_bound(labels.begin(), labels.end(), phase) - labels.begin());
    const bool named = std::any_of(header_.phase_names.begin(), header_.phase_names.end(),
                                   [](const auto& entry) { return !entry.second.empty(); });
    if (named) {
      m.phase_names.resize(labels.size());
      for (size_t i = 0; i < labels.size(); ++i) {
        const auto it = header_.phase_names.find(labels[i]);
        if (it != header_.phase_names.end()) m.phase_names[i] = it->second;
      }
    }
    for (size_t i = 0; i < labels.size(); ++i)
      if (labels[i] != int32_t(i)) {
        m.phase_labels = labels;
        break;
      }
  }

  void check_end() {
    size_t end = pos_;
    if (header_.format == Format::ascii)
      while (end < data_.size() && std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
    if (end != data_.size()) fail(cat(data_.size() - end, " bytes of unexpected data after the last element"));
  }

  static Box bounding_box(const std::vector<Vec3>& pts) {
    Box b{Vec3::Zero(), Vec3::Zero()};
    if (pts.empty()) return b;
    b.min = b.max = pts[0];
    for (const Vec3& p : pts) {
      b.min = b.min.cwiseMin(p);
      b.max = b.max.cwiseMax(p);
    }
    return b;
  }

  std::string path_;
  std::string data_;
  Header header_;
  size_t pos_ = 0;
};

std::string slurp(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(located(path, "is a directory, not a PLY file"));
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

} // namespace

NodeMesh read_ply(const std::string& path) {
  return Reader(path, slurp(path)).read();
}

} // namespace vm::io
