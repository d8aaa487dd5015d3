/// @file check/stats.cpp
/// Counts (surfaces, triple curves, quadruple points) and quality measures of a
/// node-level interface mesh.

#include "voronoimesh/check/stats.hpp"

#include "check/surface_corners.hpp"
#include "core/union_find.hpp"
#include "mesh/angle.hpp"
#include "mesh/junction_tables.hpp"
#include "mesh/node_rings.hpp"
#include "mesh/topology.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <tuple>

namespace vm {

namespace {

using detail::angle_deg;
using detail::EdgeTable;
using detail::Triangles;

/// detail::measured_triangles() of a mesh.
std::vector<char> measured_triangles(const NodeMesh& m) {
  return detail::measured_triangles(m.triangles, m.pairs.size(), m.points.size());
}

/// The measured triangles (measured_triangles()), each node's measured triangles and their edges: what
/// compute_stats(), count_folds() and sharpest_folds() walk.
struct MeasuredTables {
  std::vector<char> usable;
  detail::NodeTriangles nt;
  EdgeTable et;
  explicit MeasuredTables(const NodeMesh& m)
      : usable(measured_triangles(m)), nt(detail::node_triangles(m.points.size(), m.triangles, &usable)),
        et(detail::edge_table(m.triangles, nt)) {}
};

/// Number of distinct representatives among the items with `keep` set.
template <class Keep>
size_t count_classes(detail::UnionFind& uf, size_t n, Keep keep) {
  size_t count = 0;
  for (size_t i = 0; i < n; ++i)
    if (keep(i) && uf.find(int32_t(i)) == int32_t(i)) ++count;
  return count;
}

/// Calls f(e, t, s) for each pair of triangles t, s that join one surface
/// across edge e: the edge carries exactly two triangles of their phase pair.
template <class F> void for_each_surface_edge(const NodeMesh& m, const EdgeTable& et, F&& f) {
  std::vector<std::pair<PhasePair, int32_t>> on_edge;
  for (size_t e = 0; e < et.size(); ++e) {
    on_edge.clear();
    for (int32_t h : et.halfedges(e)) {
      const int32_t t = detail::he_triangle(h);
      on_edge.emplace_back(m.pairs[size_t(t)], t);
    }
    std::sort(on_edge.begin(), on_edge.end());
    for (size_t i = 0; i < on_edge.size();) {
      size_t j = i + 1;
      while (j < on_edge.size() && on_edge[j].first == on_edge[i].first) ++j;
      if (j - i == 2) f(e, on_edge[i].second, on_edge[i + 1].second);
      i = j;
    }
  }
}

/// Patches: triangles of one pair joined through edges that carry exactly
/// two triangles of that pair.
size_t count_surfaces(const NodeMesh& m, const EdgeTable& et, const std::vector<char>& usable) {
  detail::UnionFind uf(m.triangles.size());
  for_each_surface_edge(m, et, [&](size_t, int32_t t, int32_t s) { uf.unite(t, s); });
  return count_classes(uf, m.triangles.size(), [&](size_t t) { return usable[t] != 0; });
}

/// Calls f(e, t, s, turn) for each surface edge e whose two triangles t, s
/// have normals more than MeshStats::kFoldDeg apart (MeshStats::folds), turn
/// being that angle's cosine. Both normals point into the pair's second phase,
/// so on a smooth surface they nearly agree.
template <class F> void for_each_fold(const NodeMesh& m, const EdgeTable& et, F&& f) {
  const double cos_fold = std::cos(MeshStats::kFoldDeg * std::numbers::pi / 180);
  auto normal = [&](int32_t t) {
    const auto& tri = m.triangles[size_t(t)];
    const Vec3& a = m.points[size_t(tri[0])];
    return Vec3((m.points[size_t(tri[1])] - a).cross(m.points[size_t(tri[2])] - a).normalized());
  };
  for_each_surface_edge(m, et, [&](size_t e, int32_t t, int32_t s) {
    const double turn = normal(t).dot(normal(s));
    if (turn < cos_fold) f(e, t, s, turn);
  });
}

size_t folds_of(const NodeMesh& m, const EdgeTable& et) {
  size_t folds = 0;
  for_each_fold(m, et, [&](size_t, int32_t, int32_t, double) { ++folds; });
  return folds;
}

/// Node `n` of `m` as a corner: where it is and what meets there.
TriangleCorner corner_of(const NodeMesh& m, const detail::NodePhases& np, const std::vector<uint8_t>& box, int32_t n) {
  const auto phases = np.of(size_t(n));
  return {n, m.points[size_t(n)], {phases.begin(), phases.end()}, std::popcount(unsigned(box[size_t(n)]))};
}

void quality_stats(const NodeMesh& m, const std::vector<char>& usable, MeshStats& s) {
  double sum = 0, interface_sum = 0;
  size_t counted = 0;
  const bool closed = m.outside_phase >= 0;
  if (closed) s.interface_min_quality = std::numeric_limits<double>::infinity();
  std::vector<double> qualities;
  qualities.reserve(m.triangles.size());
  s.min_quality = std::numeric_limits<double>::infinity();
  s.min_angle_deg = std::numeric_limits<double>::infinity();
  s.max_angle_deg = 0;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    if (!usable[t]) continue;
    const auto& tri = m.triangles[t];
    const Vec3 &a = m.points[size_t(tri[0])], &b = m.points[size_t(tri[1])], &c = m.points[size_t(tri[2])];
    const double q = triangle_quality(a, b, c);
    s.min_quality = std::min(s.min_quality, q);
    qualities.push_back(q);
    sum += q;
    ++counted;
    if (closed && (m.pairs[t][0] == m.outside_phase || m.pairs[t][1] == m.outside_phase)) {
      ++s.box_triangles;
    } else if (closed) {
      s.interface_min_quality = std::min(s.interface_min_quality, q);
      interface_sum += q;
    }
    s.below_half += q < 0.5;
    s.slivers += q < MeshStats::kSliverQuality;
    double smallest = 180;
    for (double angle : {angle_deg(b - a, c - a), angle_deg(c - b, a - b), angle_deg(a - c, b - c)}) {
      s.min_angle_deg = std::min(s.min_angle_deg, angle);
      s.max_angle_deg = std::max(s.max_angle_deg, angle);
      smallest = std::min(smallest, angle);
    }
    // Round-off can put an equilateral triangle's smallest angle a hair over 60.
    const auto bin = std::min(size_t(smallest / MeshStats::kAngleBinDeg), s.smallest_angles.size() - 1);
    ++s.smallest_angles[bin];
  }
  if (closed && counted == s.box_triangles) s.interface_min_quality = 0;
  if (closed && counted > s.box_triangles) s.interface_mean_quality = interface_sum / double(counted - s.box_triangles);
  if (counted == 0) {
    s.min_quality = s.min_angle_deg = 0;
    return;
  }
  s.mean_quality = sum / double(counted);
  auto p01 = qualities.begin() + std::ptrdiff_t(qualities.size() / 100);
  std::nth_element(qualities.begin(), p01, qualities.end());
  s.quality_p01 = *p01;
}

void edge_stats(const NodeMesh& m, const EdgeTable& et, MeshStats& s) {
  if (et.size() == 0) return;
  double sum2 = 0;
  s.min_edge = std::numeric_limits<double>::infinity();
  s.max_edge = 0;
  for (const auto& [a, b] : et.nodes) {
    const double len = (m.points[size_t(a)] - m.points[size_t(b)]).norm();
    s.min_edge = std::min(s.min_edge, len);
    s.max_edge = std::max(s.max_edge, len);
    sum2 += len * len;
  }
  s.rms_edge = std::sqrt(sum2 / double(et.size()));
}

} // namespace

MeshStats compute_stats(const NodeMesh& m) {
  MeshStats s;
  s.vertices = m.points.size();
  s.triangles = m.triangles.size();
  // Malformed triangles (bad ids, no pair) are left out of every count; validate() reports them.
  const MeasuredTables tables(m);
  const auto& [usable, nt, et] = tables;
  std::vector<int32_t> phases;
  for (size_t t = 0; t < m.triangles.size(); ++t)
    if (usable[t]) phases.insert(phases.end(), m.pairs[t].begin(), m.pairs[t].end());
  std::sort(phases.begin(), phases.end());
  s.phases = size_t(std::unique(phases.begin(), phases.end()) - phases.begin());

  const detail::NodePhases np = detail::node_phases(nt, m.pairs);
  s.surfaces = count_surfaces(m, et, usable);
  s.folds = folds_of(m, et);
  const Junctions junctions = detail::junctions_from(m.pairs, et, np);
  s.triple_curves = junctions.curves.size();
  s.quadruple_points = junctions.quadruple_points.size();
  for (int32_t n : junctions.quadruple_points) s.higher_order_points += junctions.order(size_t(n)) >= 5;
  quality_stats(m, usable, s);
  edge_stats(m, et, s);
  const detail::CornerSummary corners =
      detail::summarize_corners(m, nt, np, detail::box_faces_of(m.points, m.domain), MeshStats::kSharpCornerDeg);
  s.smallest_corner_deg = corners.smallest.angle_deg;
  s.sharp_corners = corners.sharp;
  return s;
}

size_t count_folds(const NodeMesh& m) { return folds_of(m, MeasuredTables(m).et); }

std::vector<WorstTriangle> worst_triangles(const NodeMesh& m, size_t count) {
  if (count == 0) return {}; // `stats` without --worst: no pass over the triangles
  const std::vector<char> usable = measured_triangles(m);
  std::vector<double> quality(m.triangles.size(), 0);
  std::vector<size_t> order;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    if (!usable[t]) continue;
    const auto& tri = m.triangles[t];
    quality[t] = triangle_quality(m.points[size_t(tri[0])], m.points[size_t(tri[1])], m.points[size_t(tri[2])]);
    order.push_back(t);
  }
  count = std::min(count, order.size());
  const auto by_quality = [&](size_t a, size_t b) { return std::tie(quality[a], a) < std::tie(quality[b], b); };
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(count), order.end(), by_quality);
  order.resize(count);

  // What meets at their corners: the node tables compute_stats() builds.
  const detail::NodeTriangles nt = detail::node_triangles(m.points.size(), m.triangles, &usable);
  const detail::NodePhases np = detail::node_phases(nt, m.pairs);
  const std::vector<uint8_t> box = detail::box_faces_of(m.points, m.domain);
  std::vector<WorstTriangle> worst;
  for (size_t t : order) {
    WorstTriangle w;
    w.triangle = t;
    w.quality = quality[t];
    w.pair = m.pairs[t];
    const auto& tri = m.triangles[t];
    w.min_angle_deg = 180;
    size_t smallest = 0;
    for (size_t k = 0; k < 3; ++k) {
      const Vec3& a = m.points[size_t(tri[k])];
      const Vec3 &b = m.points[size_t(tri[(k + 1) % 3])], &c = m.points[size_t(tri[(k + 2) % 3])];
      if (const double angle = angle_deg(b - a, c - a); angle < w.min_angle_deg) w.min_angle_deg = angle, smallest = k;
      w.corners[k] = corner_of(m, np, box, tri[k]);
    }
    // Its surface's corner at that node, if t alone fills it.
    for (const detail::SurfaceCorner& c : detail::corners_at(m, nt, np, box, tri[smallest]))
      if (c.triangles.size() == 1 && c.triangles[0] == int32_t(t)) w.corner_node = c.node, w.corner_deg = c.angle_deg;
    worst.push_back(std::move(w));
  }
  return worst;
}

std::vector<Fold> sharpest_folds(const NodeMesh& m, size_t count) {
  if (count == 0) return {}; // `stats` without --folds: no second edge table
  const MeasuredTables tables(m);
  struct Found {
    double turn; // the normals' cosine: the sharper, the lower
    size_t edge;
    int32_t t, s;
  };
  std::vector<Found> found;
  for_each_fold(m, tables.et, [&](size_t e, int32_t t, int32_t s, double turn) { found.push_back({turn, e, t, s}); });
  count = std::min(count, found.size());
  const auto sharper = [](const Found& a, const Found& b) {
    return std::tie(a.turn, a.edge) < std::tie(b.turn, b.edge);
  };
  std::partial_sort(found.begin(), found.begin() + std::ptrdiff_t(count), found.end(), sharper);
  found.resize(count);

  const detail::NodePhases np = detail::node_phases(tables.nt, m.pairs);
  const std::vector<uint8_t> box = detail::box_faces_of(m.points, m.domain);
  std::vector<Fold> folds;
  for (const Found& f : found) {
    const auto [a, b] = tables.et.nodes[f.edge];
    folds.push_back({std::acos(std::clamp(f.turn, -1.0, 1.0)) * (180.0 / std::numbers::pi),
                     m.pairs[size_t(f.t)],
                     {size_t(f.t), size_t(f.s)},
                     {corner_of(m, np, box, a), corner_of(m, np, box, b)}});
  }
  return folds;
}

namespace {

/// Phase `p` as `m`'s files show it: its label, after its name where it has one.
std::string phase_text(const NodeMesh& m, int32_t p) {
  const std::string label = std::to_string(m.label_of(p));
  const bool named = size_t(p) < m.phase_names.size() && !m.phase_names[size_t(p)].empty();
  return named ? m.phase_names[size_t(p)] + " (" + label + ")" : label;
}

/// "  node N at (x, y, z): triple curve of a, b, c, on a box face\n"
std::string corner_text(const TriangleCorner& c, const NodeMesh& m) {
  const size_t n = c.phases.size();
  std::string what = n <= 2 ? "surface" : n == 3 ? "triple curve" : std::to_string(n) + "-phase point";
  std::string list;
  for (int32_t p : c.phases) list += (list.empty() ? "" : ", ") + phase_text(m, p);
  what += " of " + list;
  if (c.box_faces) what += c.box_faces == 1 ? ", on a box face" : ", on " + std::to_string(c.box_faces) + " box faces";
  char buf[128];
  std::snprintf(buf, sizeof buf, "  node %d at (%.6g, %.6g, %.6g): ", c.node, c.position.x(), c.position.y(),
                c.position.z());
  return buf + what + "\n";
}

} // namespace

std::string to_text(std::span<const WorstTriangle> worst, const NodeMesh& m) {
  std::string out;
  char buf[192];
  for (const WorstTriangle& w : worst) {
    const auto& c = w.corners;
    std::snprintf(buf, sizeof buf, "triangle %zu: q %.4f, smallest angle %.2f deg, between %s and %s; edges %.4g %.4g %.4g\n",
                  w.triangle, w.quality, w.min_angle_deg, phase_text(m, w.pair[0]).c_str(),
                  phase_text(m, w.pair[1]).c_str(), (c[1].position - c[0].position).norm(),
                  (c[2].position - c[1].position).norm(), (c[0].position - c[2].position).norm());
    out += buf;
    for (const TriangleCorner& corner : c) out += corner_text(corner, m);
    if (w.corner_node >= 0) {
      std::snprintf(buf, sizeof buf,
                    "  its smallest angle is its surface's whole corner at node %d, a junction point: no "
                    "triangulation does better there while the point and its curves stay where they are\n",
                    w.corner_node);
      out += buf;
    }
  }
  return out;
}

std::string to_text(std::span<const Fold> folds, const NodeMesh& m) {
  std::string out;
  char buf[192];
  for (const Fold& f : folds) {
    std::snprintf(buf, sizeof buf,
                  "edge %d-%d: turns %.1f deg, between %s and %s; length %.4g, triangles %zu and %zu\n",
                  f.ends[0].node, f.ends[1].node, f.turn_deg, phase_text(m, f.pair[0]).c_str(),
                  phase_text(m, f.pair[1]).c_str(), (f.ends[1].position - f.ends[0].position).norm(),
                  f.triangles[0], f.triangles[1]);
    out += buf;
    for (const TriangleCorner& end : f.ends) out += corner_text(end, m);
  }
  return out;
}

std::string to_text(const MeshStats& s) {
  std::string out;
  auto line = [&out](const char* label, const std::string& value) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%-22s %s\n", label, value.c_str());
    out += buf;
  };
  auto num = [](const char* fmt, auto... v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, fmt, v...);
    return std::string(buf);
  };
  line("vertices", std::to_string(s.vertices));
  line("triangles", std::to_string(s.triangles));
  line("phases", std::to_string(s.phases));
  line("surfaces", std::to_string(s.surfaces));
  line("triple curves", std::to_string(s.triple_curves));
  line("quadruple points", std::to_string(s.quadruple_points));
  line("higher-order points", std::to_string(s.higher_order_points));
  line("quality min/1%/mean", num("%.4f / %.4f / %.4f", s.min_quality, s.quality_p01, s.mean_quality));
  if (s.box_triangles > 0)
    line("interfaces min/mean", num("%.4f / %.4f (q without the %zu triangles on the box faces)",
                                    s.interface_min_quality, s.interface_mean_quality, s.box_triangles));
  line("quality < 0.5", std::to_string(s.below_half));
  line("slivers (q < 0.1)", std::to_string(s.slivers));
  line("folds", std::to_string(s.folds) + " surface edges turning more than " +
                    std::to_string(int(MeshStats::kFoldDeg)) + " deg");
  line("angle min / max", num("%.2f / %.2f deg", s.min_angle_deg, s.max_angle_deg));
  std::string bounds, counts; // "<10/<20/.../<=60", "a / b / ..."
  const size_t bins = s.smallest_angles.size();
  for (size_t i = 0; i < bins; ++i) {
    bounds += i == 0 ? "<" : i + 1 < bins ? "/<" : "/<=";
    bounds += std::to_string((i + 1) * MeshStats::kAngleBinDeg);
    counts += i == 0 ? "" : " / ";
    counts += std::to_string(s.smallest_angles[i]);
  }
  line("smallest angle", bounds + " deg: " + counts + " triangles");
  line("smallest corner", s.smallest_corner_deg < 180
                              ? num("%.2f deg, %zu below %d deg (the smallest angle can be no larger there)",
                                    s.smallest_corner_deg, s.sharp_corners, int(MeshStats::kSharpCornerDeg))
                              : std::string("none below 180 deg"));
  line("edge min / max / rms", num("%.6g / %.6g / %.6g", s.min_edge, s.max_edge, s.rms_edge));
  if (s.self_intersections) line("self-intersections", std::to_string(*s.self_intersections) + " triangle pairs");
  return out;
}

std::string to_json(const MeshStats& s, std::span<const WorstTriangle> worst, const NodeMesh* m,
                    std::span<const Fold> folds,
                    std::span<const std::pair<std::string, std::string>> more) {
  nlohmann::ordered_json j = {
      {"vertices", s.vertices},
      {"triangles", s.triangles},
      {"phases", s.phases},
      {"surfaces", s.surfaces},
      {"triple_curves", s.triple_curves},
      {"quadruple_points", s.quadruple_points},
      {"higher_order_points", s.higher_order_points},
      {"min_quality", s.min_quality},
      {"mean_quality", s.mean_quality},
      {"quality_p01", s.quality_p01},
      {"below_half", s.below_half},
      {"slivers", s.slivers},
      {"folds", s.folds},
      {"min_angle_deg", s.min_angle_deg},
      {"max_angle_deg", s.max_angle_deg},
      {"smallest_angle_bin_deg", MeshStats::kAngleBinDeg},
      {"smallest_angles", s.smallest_angles},
      {"smallest_corner_deg", s.smallest_corner_deg},
      {"sharp_corner_deg", MeshStats::kSharpCornerDeg},
      {"sharp_corners", s.sharp_corners},
      {"min_edge", s.min_edge},
      {"max_edge", s.max_edge},
      {"rms_edge", s.rms_edge},
  };
  if (s.box_triangles > 0) {
    j["box_triangles"] = s.box_triangles;
    j["interface_min_quality"] = s.interface_min_quality;
    j["interface_mean_quality"] = s.interface_mean_quality;
  }
  if (s.self_intersections) j["self_intersections"] = *s.self_intersections;
  auto label = [&](int32_t p) { return m ? m->label_of(p) : p; };
  auto corners_json = [&](std::span<const TriangleCorner> corners) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const TriangleCorner& c : corners) {
      std::vector<int32_t> phases;
      for (int32_t p : c.phases) phases.push_back(label(p));
      list.push_back({{"node", c.node},
                      {"position", {c.position.x(), c.position.y(), c.position.z()}},
                      {"phases", phases},
                      {"box_faces", c.box_faces}});
    }
    return list;
  };
  if (!worst.empty()) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const WorstTriangle& w : worst)
      list.push_back({{"triangle", w.triangle},
                      {"quality", w.quality},
                      {"min_angle_deg", w.min_angle_deg},
                      {"pair", {label(w.pair[0]), label(w.pair[1])}},
                      {"corners", corners_json(w.corners)},
                      {"corner_node", w.corner_node},
                      {"corner_deg", w.corner_node >= 0 ? nlohmann::ordered_json(w.corner_deg) : nullptr}});
    j["worst_triangles"] = list;
  }
  if (!folds.empty()) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const Fold& f : folds)
      list.push_back({{"turn_deg", f.turn_deg},
                      {"pair", {label(f.pair[0]), label(f.pair[1])}},
                      {"triangles", f.triangles},
                      {"ends", corners_json(f.ends)}});
    j["sharpest_folds"] = list;
  }
  for (const auto& [key, text] : more) j[key] = nlohmann::ordered_json::parse(text);
  return j.dump(2);
}

} // namespace vm
