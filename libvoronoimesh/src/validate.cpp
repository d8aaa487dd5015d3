/// @file validate.cpp
/// Node-level checks of an interface mesh (validate.hpp). Everything is built on
/// the incidence tables of detail/topology.hpp, so the cost is linear in the
/// triangle count (times small local sorts around nodes and edges).

#include "voronoimesh/validate.hpp"

#include "detail/problem_log.hpp"
#include "detail/topology.hpp"
#include "detail/union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace vm {

namespace {

using detail::cat;
using detail::EdgeTable;
using detail::NodeTriangles;
using detail::ProblemLog;

// (Strings are built by appending: GCC 12 gives false -Wrestrict warnings on
// "literal" + std::string chains.)
template <size_t N>
std::string str(const std::array<int32_t, N>& ids) {
  std::string s = "(";
  for (size_t i = 0; i < N; ++i) {
    if (i) s += ", ";
    s += std::to_string(ids[i]);
  }
  s += ")";
  return s;
}
/// "t1 t2 t3", at most 8 ids.
template <class Ids>
std::string list(const Ids& ids) {
  std::string s;
  size_t i = 0;
  for (auto id : ids) {
    if (i == 8) return s += " ...";
    if (i++) s += " ";
    s += std::to_string(id);
  }
  return s;
}

/// Bits of the domain box faces (-x, +x, -y, +y, -z, +z) each node lies on,
/// within 1e-9 x the box diagonal.
std::vector<uint8_t> box_faces(const NodeMesh& m) {
  const double tol = 1e-9 * (m.domain.max - m.domain.min).norm();
  std::vector<uint8_t> mask(m.points.size(), 0);
  for (size_t n = 0; n < m.points.size(); ++n)
    for (int a = 0; a < 3; ++a) {
      if (std::abs(m.points[n][a] - m.domain.min[a]) <= tol) mask[n] |= uint8_t(1u << (2 * a));
      if (std::abs(m.points[n][a] - m.domain.max[a]) <= tol) mask[n] |= uint8_t(1u << (2 * a + 1));
    }
  return mask;
}

class NodeMeshChecker {
public:
  NodeMeshChecker(const NodeMesh& m, ProblemLog& log) : m_(m), log_(log), on_box_(box_faces(m)) {}

  void run() {
    check_triangles();
    check_duplicates();
    const NodeTriangles nt = detail::node_triangles(m_.points.size(), m_.triangles, &usable_);
    const EdgeTable et = detail::edge_table(m_.triangles, nt);
    for (size_t e = 0; e < et.size(); ++e) check_edge(et, e);
    for (size_t n = 0; n < m_.points.size(); ++n) check_fans(nt, n);
  }

private:
  /// Per-triangle checks; fills usable_ (node ids valid and distinct) and
  /// paired_ (also a valid phase pair): later checks skip the others.
  void check_triangles() {
    const size_t nt = m_.triangles.size(), nn = m_.points.size();
    if (m_.pairs.size() != nt)
      log_.add({}, [&] { return cat("size mismatch: ", nt, " triangles but ", m_.pairs.size(), " phase pairs"); });
    usable_.assign(nt, 0);
    paired_.assign(nt, 0);
    const size_t num_phases = m_.phase_names.size();
    for (size_t t = 0; t < nt; ++t) {
      const auto& tri = m_.triangles[t];
      bool in_range = true;
      for (int32_t v : tri)
        if (v < 0 || size_t(v) >= nn) {
          in_range = false;
          log_.add({}, [&] {
            return cat("node out of range: triangle ", t, " ", str(tri), " has node ", v, " (", nn, " nodes)");
          });
        }
      if (!in_range) continue;
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
        log_.add({tri[0], tri[1], tri[2]}, [&] { return cat("repeated node: triangle ", t, " ", str(tri)); });
        continue;
      }
      usable_[t] = 1;
      check_area(t);
      if (t >= m_.pairs.size()) continue;
      const auto& p = m_.pairs[t];
      if (p[0] < 0 || p[0] >= p[1] || (num_phases > 0 && size_t(p[1]) >= num_phases)) {
        log_.add({tri[0], tri[1], tri[2]}, [&] {
          return cat("bad pair: triangle ", t, " has pair ", str(p), " (need 0 <= p < q",
                     num_phases > 0 ? cat(" < ", num_phases, ")") : std::string(")"));
        });
        continue;
      }
      paired_[t] = 1;
    }
  }

  void check_area(size_t t) {
    const auto& tri = m_.triangles[t];
    const Vec3 &a = m_.points[size_t(tri[0])], &b = m_.points[size_t(tri[1])], &c = m_.points[size_t(tri[2])];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (area > 1e-12 * longest2 && std::isfinite(area) && std::isfinite(longest2)) return;
    log_.add({tri[0], tri[1], tri[2]}, [&] {
      const bool finite = a.allFinite() && b.allFinite() && c.allFinite();
      return finite ? cat("zero area: triangle ", t, " ", str(tri), ": area ", area, ", longest edge ",
                          std::sqrt(longest2))
                    : cat("zero area: triangle ", t, " ", str(tri), ": non-finite coordinate");
    });
  }

  void check_duplicates() {
    std::vector<std::pair<std::array<int32_t, 3>, int32_t>> keys;
    keys.reserve(m_.triangles.size());
    for (size_t t = 0; t < m_.triangles.size(); ++t)
      if (usable_[t]) {
        auto k = m_.triangles[t];
        std::sort(k.begin(), k.end());
        keys.emplace_back(k, int32_t(t));
      }
    std::sort(keys.begin(), keys.end());
    for (size_t i = 0; i < keys.size();) {
      size_t j = i + 1;
      while (j < keys.size() && keys[j].first == keys[i].first) ++j;
      if (j - i > 1)
        log_.add({keys[i].first[0], keys[i].first[1], keys[i].first[2]}, [&] {
          std::vector<int32_t> ts;
          for (size_t k = i; k < j; ++k) ts.push_back(keys[k].second);
          return cat("duplicate triangle: triangles ", list(ts), " on nodes ", str(keys[i].first));
        });
      i = j;
    }
  }

  /// Per phase, each edge must be used once in each direction by the phase's
  /// outward-oriented triangles (once in total on the domain box); a junction
  /// edge must be carried by one cycle of distinct pairs.
  void check_edge(const EdgeTable& et, size_t e) {
    const auto [a, b] = et.nodes[e];
    const bool on_box = (on_box_[size_t(a)] & on_box_[size_t(b)]) != 0;
    uses_.clear();
    tris_.clear();
    for (int32_t h : et.halfedges(e)) {
      const int32_t t = detail::he_triangle(h);
      tris_.push_back(t);
      if (!paired_[size_t(t)]) continue;
      // Triangle t runs a->b (forward) or b->a; pair[0] sees it as is, pair[1] reversed.
      const bool forward = detail::he_from(m_.triangles, h) == a;
      uses_.push_back({m_.pairs[size_t(t)][0], forward ? 1 : 0, t});
      uses_.push_back({m_.pairs[size_t(t)][1], forward ? 0 : 1, t});
    }
    std::sort(uses_.begin(), uses_.end());
    phase_ids_.clear();
    degree_.clear();
    for (size_t i = 0; i < uses_.size();) {
      size_t j = i, fwd = 0, bwd = 0;
      for (; j < uses_.size() && uses_[j][0] == uses_[i][0]; ++j) (uses_[j][1] ? fwd : bwd)++;
      phase_ids_.push_back(uses_[i][0]);
      degree_.push_back(fwd + bwd);
      if (!(fwd == 1 && bwd == 1) && !(on_box && fwd + bwd == 1)) {
        const char* kind = fwd + bwd == 1 ? "open boundary" : fwd + bwd == 2 ? "orientation" : "non-manifold edge";
        log_.add({a, b}, [&] {
          std::vector<int32_t> ts;
          for (size_t k = i; k < j; ++k) ts.push_back(uses_[k][2]);
          return cat(kind, ": phase ", uses_[i][0], ", edge ", str(et.nodes[e]), " used ", fwd, "x ", a, "->", b,
                     " and ", bwd, "x back (triangles ", list(ts), ")", on_box ? "" : ", not on the domain box");
        });
      }
      i = j;
    }
    if (tris_.size() >= 3 && uses_.size() == 2 * tris_.size()) check_junction(et, e, on_box);
  }

  /// Phases are the vertices and triangles the edges of a small graph around
  /// the junction edge; it must be one cycle (every phase on two triangles), or
  /// on the domain box possibly one path (the two end phases on one triangle).
  void check_junction(const EdgeTable& et, size_t e, bool on_box) {
    size_t ends = 0;
    for (size_t i = 0; i < phase_ids_.size(); ++i) {
      const size_t d = degree_[i];
      if (d == 2) continue;
      if (on_box && d == 1 && ++ends <= 2) continue;
      return report_junction(et, e, cat("phase ", phase_ids_[i], " on ", d, " of them"));
    }
    if (ends == 1) return report_junction(et, e, "the chain of pairs does not close");
    auto local = [&](int32_t phase) {
      return int32_t(std::lower_bound(phase_ids_.begin(), phase_ids_.end(), phase) - phase_ids_.begin());
    };
    detail::UnionFind uf(phase_ids_.size());
    size_t components = phase_ids_.size();
    for (int32_t t : tris_) {
      const int32_t x = uf.find(local(m_.pairs[size_t(t)][0])), y = uf.find(local(m_.pairs[size_t(t)][1]));
      if (x != y) --components;
      uf.unite(x, y);
    }
    if (components != 1) report_junction(et, e, cat(components, " separate cycles of pairs"));
  }

  void report_junction(const EdgeTable& et, size_t e, const std::string& why) {
    log_.add({et.nodes[e][0], et.nodes[e][1]}, [&] {
      std::string pairs;
      for (int32_t t : tris_) pairs += cat(" ", t, str(m_.pairs[size_t(t)]));
      return cat("junction: edge ", str(et.nodes[e]), " with ", tris_.size(), " triangles (triangle(pair):", pairs,
                 "): ", why);
    });
  }

  /// The outward triangles of each phase around node n must form one fan.
  void check_fans(const NodeTriangles& nt, size_t n) {
    corners_.clear();
    for (int32_t t : nt.of(n)) {
      if (!paired_[size_t(t)]) continue;
      const auto& tri = m_.triangles[size_t(t)];
      const size_t c = size_t(std::find(tri.begin(), tri.end(), int32_t(n)) - tri.begin());
      const int32_t next = tri[(c + 1) % 3], prev = tri[(c + 2) % 3];
      // As seen by pair[0] the fan runs prev -> n -> next; pair[1] sees it reversed.
      corners_.push_back({m_.pairs[size_t(t)][0], prev, next, t});
      corners_.push_back({m_.pairs[size_t(t)][1], next, prev, t});
    }
    std::sort(corners_.begin(), corners_.end());
    for (size_t i = 0; i < corners_.size();) {
      size_t j = i;
      while (j < corners_.size() && corners_[j][0] == corners_[i][0]) ++j;
      const size_t fans = count_fans(i, j);
      if (fans > 1)
        log_.add({int32_t(n)}, [&] {
          std::vector<int32_t> ts;
          for (size_t k = i; k < j; ++k) ts.push_back(corners_[k][3]);
          return cat("non-manifold node: phase ", corners_[i][0], " at node ", n, " has ", fans,
                     " separate fans (triangles ", list(ts), ")");
        });
      i = j;
    }
  }

  /// Fans among corners_[i, j) (sorted by in-neighbour): corner x continues
  /// into corner y when x's out-neighbour is y's in-neighbour.
  size_t count_fans(size_t i, size_t j) {
    detail::UnionFind uf(j - i);
    size_t components = j - i;
    for (size_t x = i; x < j; ++x) {
      auto it = std::lower_bound(corners_.begin() + long(i), corners_.begin() + long(j), corners_[x][2],
                                 [](const std::array<int32_t, 4>& c, int32_t v) { return c[1] < v; });
      for (; it != corners_.begin() + long(j) && (*it)[1] == corners_[x][2]; ++it) {
        const int32_t u = int32_t(x - i), v = int32_t(it - corners_.begin() - long(i));
        if (uf.find(u) != uf.find(v)) --components;
        uf.unite(u, v);
      }
    }
    return components;
  }

  const NodeMesh& m_;
  ProblemLog& log_;
  std::vector<uint8_t> on_box_;
  std::vector<char> usable_, paired_;
  // Scratch reused across edges and nodes.
  std::vector<std::array<int32_t, 3>> uses_; // (phase, forward, triangle)
  std::vector<int32_t> tris_;
  std::vector<int32_t> phase_ids_;              // distinct phases on the current edge, sorted
  std::vector<size_t> degree_;                  // triangles of each of them
  std::vector<std::array<int32_t, 4>> corners_; // (phase, in, out, triangle)
};

} // namespace

std::string ValidationReport::summary() const {
  std::string s;
  for (const auto& p : problems) s += p + "\n";
  if (problem_count > problems.size())
    s += detail::cat("... and ", problem_count - problems.size(), " more problems\n");
  return s;
}

ValidationReport validate(const NodeMesh& m) {
  ValidationReport report;
  ProblemLog log(report);
  NodeMeshChecker(m, log).run();
  return report;
}

} // namespace vm
