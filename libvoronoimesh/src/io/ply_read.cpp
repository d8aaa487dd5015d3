/// @file io/ply_read.cpp
/// read_ply: node-level interface meshes from PLY (the container itself,
/// ascii or binary, any scalar types, is io/ply_format.hpp). Elements and
/// properties it does not need are skipped.

#include "voronoimesh/io/ply.hpp"

#include "core/text.hpp"
#include "io/ply_format.hpp"
#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <cmath>
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
using ply::Element;
using ply::Property;

/// What write_ply stores in comments.
struct Comments {
  std::optional<Box> domain;
  double grid_spacing = 0;
  std::map<int32_t, std::string> phase_names; ///< by label, from "comment phase <label> <name>"
  std::map<int32_t, Rgb> phase_colors;        ///< by label, from "comment phase_color <label> <r> <g> <b>"
};

class Reader {
public:
  explicit Reader(const std::string& path) : file_(path) {}

  NodeMesh read() {
    for (const std::string& line : file_.header().comments) parse_comment(line);
    const Layout layout = find_layout();
    NodeMesh m;
    file_.read_body([&](const Element& e) {
      if (&e == layout.vertex)
        read_vertices(layout, m);
      else if (&e == layout.face)
        read_faces(layout, m);
      else
        return false;
      return true;
    });
    for (size_t t = 0; t < m.triangles.size(); ++t)
      for (int32_t v : m.triangles[t])
        if (v < 0 || size_t(v) >= m.points.size())
          fail(cat("face ", t, ": vertex index ", v, " out of range (", m.points.size(), " vertices)"));
    compact_phases(m);
    m.domain = comments_.domain ? *comments_.domain : bounding_box(m.points);
    m.grid_spacing = comments_.grid_spacing;
    m.outside_phase = outside_phase(m);
    return m;
  }

private:
  [[noreturn]] void fail(const std::string& what) const { file_.fail(what); }

  /// "comment domain x0 y0 z0 x1 y1 z1", "comment grid_spacing <h>",
  /// "comment phase <label> <name>" and "comment phase_color <label> <r> <g> <b>",
  /// as write_ply stores them; any other comment is ignored.
  void parse_comment(std::string_view line) {
    const auto w = ply::split_words(line);
    if (w.size() == 8 && w[1] == "domain") {
      std::array<double, 6> v{};
      for (size_t i = 0; i < 6; ++i)
        if (!parse_number(w[i + 2], v[i]) || !std::isfinite(v[i])) fail(cat("bad domain comment '", line, "'"));
      comments_.domain = Box{Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5])};
    } else if (w.size() >= 2 && w[1] == "grid_spacing") {
      double h = 0;
      if (w.size() != 3 || !parse_number(w[2], h) || !std::isfinite(h) || h <= 0)
        fail(cat("bad grid_spacing comment '", line, "' (expected one positive number)"));
      comments_.grid_spacing = h;
    } else if (w.size() >= 3 && w[1] == "phase") {
      int32_t label = 0;
      if (!parse_number(w[2], label)) fail(cat("bad phase comment '", line, "'"));
      const size_t name_at = size_t(w[2].data() + w[2].size() - line.data());
      std::string_view name = line.substr(std::min(line.size(), name_at + 1));
      if (!comments_.phase_names.emplace(label, std::string(name)).second) fail(cat("phase ", label, " is described twice"));
    } else if (w.size() >= 2 && w[1] == "phase_color") {
      int32_t label = 0;
      Rgb rgb{};
      bool ok = w.size() == 6 && parse_number(w[2], label);
      for (size_t c = 0; ok && c < 3; ++c) ok = parse_number(w[c + 3], rgb[c]) && rgb[c] >= 0 && rgb[c] <= 1;
      if (!ok) fail(cat("bad phase_color comment '", line, "' (expected a label and three numbers in [0, 1])"));
      if (!comments_.phase_colors.emplace(label, rgb).second) fail(cat("phase ", label, " has two colours"));
    }
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
    l.vertex = file_.header().element("vertex");
    l.face = file_.header().element("face");
    if (!l.vertex) fail("no vertex element");
    if (!l.face) fail("no face element (not a voronoimesh PLY?)");
    if (l.vertex->count > uint64_t(std::numeric_limits<int32_t>::max())) fail("too many vertices");
    if (l.face->count > uint64_t(std::numeric_limits<int32_t>::max())) fail("too many faces");
    const char* const names[3] = {"x", "y", "z"};
    for (size_t a = 0; a < 3; ++a) {
      l.xyz[a] = l.vertex->find(names[a]);
      if (!l.xyz[a] || l.xyz[a]->count) fail(cat("vertex property ", names[a], " missing"));
    }
    l.indices = l.face->find("vertex_indices");
    if (!l.indices) l.indices = l.face->find("vertex_index");
    if (!l.indices || !l.indices->count) fail("face property vertex_indices missing");
    l.phase0 = l.face->find("phase0");
    l.phase1 = l.face->find("phase1");
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
          file_.skip(e, i, prop);
        else
          p[slot - l.xyz.begin()] = file_.scalar(prop.type, [&] { return cat("vertex ", i); });
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
          const int32_t n = file_.int_scalar(*prop.count, what);
          if (n != 3) fail(cat("face ", i, " has ", n, " vertices (only triangles are supported)"));
          for (auto& v : m.triangles[size_t(i)]) v = file_.int_scalar(prop.type, what);
        } else if (&prop == l.phase0) {
          m.pairs[size_t(i)][0] = file_.int_scalar(prop.type, what);
        } else if (&prop == l.phase1) {
          m.pairs[size_t(i)][1] = file_.int_scalar(prop.type, what);
        } else {
          file_.skip(e, i, prop);
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
    for (const auto& [label, name] : comments_.phase_names) labels.push_back(label);
    for (const PhasePair& p : m.pairs) labels.insert(labels.end(), p.begin(), p.end());
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    if (labels.size() > kMaxPhases) fail(cat(labels.size(), " distinct phases (at most ", kMaxPhases, ")"));
    for (PhasePair& p : m.pairs)
      for (int32_t& phase : p) phase = int32_t(std::lower_bound(labels.begin(), labels.end(), phase) - labels.begin());
    const bool named = std::any_of(comments_.phase_names.begin(), comments_.phase_names.end(),
                                   [](const auto& entry) { return !entry.second.empty(); });
    if (named) {
      m.phase_names.resize(labels.size());
      for (size_t i = 0; i < labels.size(); ++i) {
        const auto it = comments_.phase_names.find(labels[i]);
        if (it != comments_.phase_names.end()) m.phase_names[i] = it->second;
      }
    }
    for (const auto& [label, rgb] : comments_.phase_colors) {
      const auto at = std::lower_bound(labels.begin(), labels.end(), label);
      if (at == labels.end() || *at != label) fail(cat("phase_color comment for label ", label, ", which no phase has"));
      const size_t phase = size_t(at - labels.begin());
      if (m.phase_colors.size() <= phase) m.phase_colors.resize(phase + 1);
      m.phase_colors[phase] = rgb;
    }
    for (size_t i = 0; i < labels.size(); ++i)
      if (labels[i] != int32_t(i)) {
        m.phase_labels = labels;
        break;
      }
  }

  /// The outside phase of a closed mesh, or -1. A PLY tells it only by the last
  /// phase's name, kOutsidePhaseName, which a scene may also give a phase of its
  /// own: so the phase is the outside one only where every triangle it bounds
  /// lies in a face of the domain box (the own phase's triangles lie inside).
  static int32_t outside_phase(const NodeMesh& m) {
    if (m.phase_names.empty() || m.phase_names.back() != kOutsidePhaseName) return -1;
    const auto last = int32_t(m.phase_names.size() - 1);
    const double tolerance = 1e-9 * (m.domain.max - m.domain.min).norm();
    auto box_faces = [&](const Vec3& p) {
      unsigned faces = 0;
      for (int a = 0; a < 3; ++a) {
        if (std::abs(p[a] - m.domain.min[a]) <= tolerance) faces |= 1u << (2 * a);
        if (std::abs(p[a] - m.domain.max[a]) <= tolerance) faces |= 1u << (2 * a + 1);
      }
      return faces;
    };
    for (size_t t = 0; t < m.triangles.size(); ++t) {
      if (m.pairs[t][1] != last) continue;
      const auto& tri = m.triangles[t];
      const auto& p = m.points;
      if ((box_faces(p[size_t(tri[0])]) & box_faces(p[size_t(tri[1])]) & box_faces(p[size_t(tri[2])])) == 0) return -1;
    }
    return last;
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

  ply::File file_;
  Comments comments_;
};

} // namespace

NodeMesh read_ply(const std::string& path) {
  return Reader(path).read();
}

} // namespace vm::io
