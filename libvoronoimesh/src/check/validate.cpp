/// @file check/validate.cpp
/// Node-level checks of an interface mesh (check/validate.hpp). Everything is built on
/// the incidence tables of mesh/topology.hpp, so the cost is linear in the
/// triangle count (times small local sorts around nodes and edges). The checks
/// run in parallel over fixed chunks of triangles and of nodes, each chunk
/// logging on its own, and the chunk logs are merged in order: the report is
/// the serial one whatever the number of threads (validate() runs on every
/// mesh create() makes, so it is worth being quick).

#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"

#include "check/problem_log.hpp"
#include "check/validate_part.hpp"
#include "core/parallel.hpp"
#include "core/scale_limits.hpp"
#include "core/union_find.hpp"
#include "mesh/topology.hpp"

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <utility>

namespace vm {

namespace {

using detail::cat;
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

/// Items per chunk of the parallel checks: fixed, so the chunks (and with them
/// the order problems are merged in) never depend on the number of threads, and
/// large enough that a chunk's log and scratch space cost little.
constexpr size_t kTriangleGrain = 8192;
constexpr size_t kNodeGrain = 4096;

/// Bits of the domain box faces (-x, +x, -y, +y, -z, +z) each node lies on,
/// within 1e-9 x the box diagonal.
std::vector<uint8_t> box_faces(const NodeMesh& m) {
  const double tol = 1e-9 * (m.domain.max - m.domain.min).norm();
  std::vector<uint8_t> mask(m.points.size(), 0);
  detail::parallel_for(tbb::blocked_range<size_t>(0, m.points.size(), kNodeGrain), [&](const auto& nodes) {
    for (size_t n = nodes.begin(); n < nodes.end(); ++n)
      for (int a = 0; a < 3; ++a) {
        if (std::abs(m.points[n][a] - m.domain.min[a]) <= tol) mask[n] |= uint8_t(1u << (2 * a));
        if (std::abs(m.points[n][a] - m.domain.max[a]) <= tol) mask[n] |= uint8_t(1u << (2 * a + 1));
      }
  });
  return mask;
}

/// What the node checks share: `usable` marks the triangles with node ids
/// valid and distinct (the only ones `nt` holds), `paired` those also with a
/// valid phase pair; the node checks skip the others.
struct Tables {
  Tables(const NodeMesh& mesh, size_t checked_nodes)
      : m(mesh), checked(checked_nodes), usable(mesh.triangles.size()), paired(mesh.triangles.size(), 0) {}
  const NodeMesh& m;
  size_t checked; ///< nodes 0..checked-1 are checked (validate_first_nodes)
  std::vector<uint8_t> on_box;
  std::vector<char> usable, paired;
  NodeTriangles nt;
};

void check_area(const NodeMesh& m, size_t t, ProblemLog& log) {
  const auto& tri = m.triangles[t];
  const Vec3 &a = m.points[size_t(tri[0])], &b = m.points[size_t(tri[1])], &c = m.points[size_t(tri[2])];
  if (!has_zero_area(a, b, c)) return;
  log.add({tri[0], tri[1], tri[2]}, [&] {
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const bool finite = a.allFinite() && b.allFinite() && c.allFinite();
    return finite ? cat("zero area: triangle ", t, " ", str(tri), ": area ", area, ", longest edge ",
                        std::sqrt(longest2))
                  : cat("zero area: triangle ", t, " ", str(tri), ": non-finite coordinate");
  });
}

/// Node ids, area and phase pair of triangle t; sets tables.paired[t].
void check_triangle(Tables& tables, size_t t, ProblemLog& log) {
  const NodeMesh& m = tables.m;
  const size_t nn = m.points.size(), num_phases = m.phase_names.size();
  const auto& tri = m.triangles[t];
  bool in_range = true;
  for (int32_t v : tri)
    if (v < 0 || size_t(v) >= nn) {
      in_range = false;
      log.add({}, [&] {
        return cat("node out of range: triangle ", t, " ", str(tri), " has node ", v, " (", nn, " nodes)");
      });
    }
  if (!in_range) return;
  if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
    log.add({tri[0], tri[1], tri[2]}, [&] { return cat("repeated node: triangle ", t, " ", str(tri)); });
    return;
  }
  check_area(m, t, log);
  if (t >= m.pairs.size()) return;
  const auto& p = m.pairs[t];
  if (p[0] < 0 || p[0] >= p[1] || (num_phases > 0 && size_t(p[1]) >= num_phases)) {
    log.add({tri[0], tri[1], tri[2]}, [&] {
      return cat("bad pair: triangle ", t, " has pair ", str(p), " (need 0 <= p < q",
                 num_phases > 0 ? cat(" < ", num_phases, ")") : std::string(")"));
    });
    return;
  }
  // The outside phase of a closed mesh is its last.
  if (m.outside_phase >= 0 && p[1] > m.outside_phase) {
    log.add({tri[0], tri[1], tri[2]}, [&] {
      return cat("bad pair: triangle ", t, " has pair ", str(p), " beyond the outside phase ", m.outside_phase);
    });
    return;
  }
  tables.paired[t] = 1;
}

/// The checks made at each node, for the nodes of one chunk. Each kind of
/// problem goes to its own log, so that the kinds can be listed one after the
/// other as if each had its own pass over the nodes (check_in_chunks), while
/// one pass reads each node's triangles once. Scratch space is reused from node
/// to node.
class NodeChecks {
public:
  NodeChecks(const Tables& tables, ProblemLog& duplicates, ProblemLog& edges, ProblemLog& fans)
      : t_(tables), m_(tables.m), duplicates_(duplicates), edges_log_(edges), fans_(fans) {}

  void check(size_t n) {
    if (t_.nt.of(n).empty())
      fans_.add({int32_t(n)}, [&] { return cat("unused node: ", n, " is a corner of no triangle"); });
    duplicates_at(n);
    if (closed_fan(n)) return;
    edges_at(n);
    fans_at(n);
  }

private:
  /// Triangles on the same three nodes. Each is found at its smallest node a;
  /// sorting by (b, c, triangle) there, nodes in order, lists them in the order
  /// of their sorted node triples (a, b, c) over the whole mesh.
  void duplicates_at(size_t a) {
    dups_.clear();
    for (int32_t t : t_.nt.of(a)) {
      const auto [prev, next] = neighbours(t, a);
      if (prev > int32_t(a) && next > int32_t(a)) dups_.push_back({std::min(prev, next), std::max(prev, next), t});
    }
    if (dups_.size() < 2) return;
    std::sort(dups_.begin(), dups_.end());
    for (size_t i = 0; i < dups_.size();) {
      size_t j = i + 1;
      while (j < dups_.size() && dups_[j][0] == dups_[i][0] && dups_[j][1] == dups_[i][1]) ++j;
      if (j - i > 1) {
        const std::array<int32_t, 3> nodes{int32_t(a), dups_[i][0], dups_[i][1]};
        duplicates_.add({nodes[0], nodes[1], nodes[2]}, [&] {
          std::vector<int32_t> ts;
          for (size_t k = i; k < j; ++k) ts.push_back(dups_[k][2]);
          return cat("duplicate triangle: triangles ", list(ts), " on nodes ", str(nodes));
        });
      }
      i = j;
    }
  }

  /// Fast path for the common node inside one patch: true when all its
  /// triangles are paired, with the same pair, and their corners (prev, next)
  /// form one cycle, each corner's next the prev of the following one (a
  /// closed fan). Then each phase sees one fan (the second one the same cycle
  /// reversed), and each edge {n, b} has two triangles of that pair running
  /// along it in opposite directions: fans_at() and edges_at() would log nothing.
  bool closed_fan(size_t n) {
    links_.clear();
    const PhasePair* pair = nullptr;
    for (int32_t t : t_.nt.of(n)) {
      const PhasePair& p = m_.pairs[size_t(t)];
      if (!t_.paired[size_t(t)] || (pair && (p[0] != (*pair)[0] || p[1] != (*pair)[1]))) return false;
      pair = &p;
      links_.push_back(neighbours(t, n));
    }
    std::sort(links_.begin(), links_.end());
    for (size_t i = 1; i < links_.size(); ++i)
      if (links_[i].first == links_[i - 1].first) return false;
    // With distinct prevs each corner has at most one successor; a walk from the
    // first corner that first comes back to it after k steps has visited all k
    // corners, each once.
    const size_t k = links_.size();
    for (size_t x = 0, step = 1; step <= k; ++step) {
      const int32_t next = links_[x].second;
      auto it = std::lower_bound(links_.begin(), links_.end(), next,
                                 [](const std::pair<int32_t, int32_t>& c, int32_t v) { return c.first < v; });
      if (it == links_.end() || it->first != next) return false;
      x = size_t(it - links_.begin());
      if (x == 0) return step == k;
    }
    return k == 0;
  }

  /// The edges {a, b} with b > a: over all nodes in order, every edge once, in
  /// the order of edge_table().
  void edges_at(size_t a) {
    edges_.gather(int32_t(a), m_.triangles, t_.nt);
    for (size_t i = 0; i < edges_.size(); ++i) check_edge({int32_t(a), edges_.other(i)}, edges_.halfedges(i));
  }

  bool paired(int32_t halfedge) const { return t_.paired[size_t(detail::he_triangle(halfedge))] != 0; }

  /// Per phase, each edge must be used once in each direction by the phase's
  /// outward-oriented triangles (once in total on the domain box); a junction
  /// edge must be carried by one cycle of distinct pairs.
  void check_edge(const std::array<int32_t, 2>& edge, std::span<const int32_t> halfedges) {
    // Most edges lie inside one patch, which is all right: skip the sorting below.
    if (halfedges.size() == 2 && paired(halfedges[0]) && paired(halfedges[1]) &&
        detail::is_patch_interior(halfedges, m_.triangles, m_.pairs))
      return;
    const int32_t a = edge[0], b = edge[1]; // not a structured binding: clang 14 cannot capture one
    const bool on_box = (t_.on_box[size_t(a)] & t_.on_box[size_t(b)]) != 0;
    uses_.clear();
    tris_.clear();
    for (int32_t h : halfedges) {
      const int32_t t = detail::he_triangle(h);
      tris_.push_back(t);
      if (!t_.paired[size_t(t)]) continue;
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
        edges_log_.add({a, b}, [&] {
          std::vector<int32_t> ts;
          for (size_t k = i; k < j; ++k) ts.push_back(uses_[k][2]);
          return cat(kind, ": phase ", uses_[i][0], ", edge ", str(edge), " used ", fwd, "x ", a, "->", b, " and ",
                     bwd, "x back (triangles ", list(ts), ")", on_box ? "" : ", not on the domain box");
        });
      }
      i = j;
    }
    if (tris_.size() >= 3 && uses_.size() == 2 * tris_.size()) check_junction(edge, on_box);
  }

  /// Phases are the vertices and triangles the edges of a small graph around
  /// the junction edge; it must be one cycle (every phase on two triangles), or
  /// on the domain box possibly one path (the two end phases on one triangle).
  void check_junction(const std::array<int32_t, 2>& edge, bool on_box) {
    size_t ends = 0;
    for (size_t i = 0; i < phase_ids_.size(); ++i) {
      const size_t d = degree_[i];
      if (d == 2) continue;
      if (on_box && d == 1 && ++ends <= 2) continue;
      return report_junction(edge, cat("phase ", phase_ids_[i], " on ", d, " of them"));
    }
    if (ends == 1) return report_junction(edge, "the chain of pairs does not close");
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
    if (components != 1) report_junction(edge, cat(components, " separate cycles of pairs"));
  }

  void report_junction(const std::array<int32_t, 2>& edge, const std::string& why) {
    edges_log_.add({edge[0], edge[1]}, [&] {
      std::string pairs;
      for (int32_t t : tris_) pairs += cat(" ", t, str(m_.pairs[size_t(t)]));
      return cat("junction: edge ", str(edge), " with ", tris_.size(), " triangles (triangle(pair):", pairs,
                 "): ", why);
    });
  }

  /// The outward triangles of each phase around node n must form one fan.
  void fans_at(size_t n) {
    corners_.clear();
    for (int32_t t : t_.nt.of(n)) {
      if (!t_.paired[size_t(t)]) continue;
      const auto [prev, next] = neighbours(t, n);
      // As seen by pair[0] the fan runs prev -> n -> next; pair[1] sees it reversed.
      corners_.push_back({m_.pairs[size_t(t)][0], prev, next, t});
      corners_.push_back({m_.pairs[size_t(t)][1], next, prev, t});
    }
    std::sort(corners_.begin(), corners_.end());
    size_t phases = 0;
    for (size_t i = 0; i < corners_.size();) {
      size_t j = i;
      while (j < corners_.size() && corners_[j][0] == corners_[i][0]) ++j;
      ++phases;
      const size_t fans = count_fans(i, j);
      if (fans > 1)
        fans_.add({int32_t(n)}, [&] {
          std::vector<int32_t> ts;
          for (size_t k = i; k < j; ++k) ts.push_back(corners_[k][3]);
          return cat("non-manifold node: phase ", corners_[i][0], " at node ", n, " has ", fans,
                     " separate fans (triangles ", list(ts), ")");
        });
      i = j;
    }
    // A mesh node holds at most kMaxPhasesAtNode phases: create repairs the
    // lattice where snapping tied more at one place (4,000 grains on a 96^3
    // grid: nine), and a merge that would make such a node is refused.
    if (phases > kMaxPhasesAtNode)
      fans_.add({int32_t(n)}, [&] {
        return cat("too many phases: ", phases, " meet at node ", n, " (at most ", kMaxPhasesAtNode, ")");
      });
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

  /// The nodes before and after node n in triangle t.
  std::pair<int32_t, int32_t> neighbours(int32_t t, size_t n) const {
    const auto& tri = m_.triangles[size_t(t)];
    if (tri[0] == int32_t(n)) return {tri[2], tri[1]};
    if (tri[1] == int32_t(n)) return {tri[0], tri[2]};
    return {tri[1], tri[0]};
  }

  const Tables& t_;
  const NodeMesh& m_;
  ProblemLog &duplicates_, &edges_log_, &fans_;
  // Scratch reused across the chunk's nodes and edges.
  std::vector<std::array<int32_t, 3>> dups_; // (b, c, triangle)
  std::vector<std::pair<int32_t, int32_t>> links_; // (prev, next) of closed_fan()
  detail::EdgesAt edges_;
  std::vector<std::array<int32_t, 3>> uses_; // (phase, forward, triangle)
  std::vector<int32_t> tris_;
  std::vector<int32_t> phase_ids_;              // distinct phases on the current edge, sorted
  std::vector<size_t> degree_;                  // triangles of each of them
  std::vector<std::array<int32_t, 4>> corners_; // (phase, in, out, triangle)
};

void check_triangles(Tables& tables, ProblemLog& log) {
  detail::check_in_chunks<1>(tables.m.triangles.size(), kTriangleGrain, log,
                             [&](size_t begin, size_t end, auto& reports) {
                               ProblemLog part(reports[0]);
                               for (size_t t = begin; t < end; ++t) {
                                 const auto& tri = tables.m.triangles[t];
                                 if (tables.checked < tables.m.points.size() &&
                                     size_t(std::min({tri[0], tri[1], tri[2]})) >= tables.checked)
                                   continue;
                                 check_triangle(tables, t, part);
                               }
                             });
}

/// Duplicates are listed first, then edge problems, then fan problems.
void check_nodes(const Tables& tables, ProblemLog& log) {
  detail::check_in_chunks<3>(tables.checked, kNodeGrain, log, [&](size_t begin, size_t end, auto& reports) {
    ProblemLog duplicates(reports[0]), edges(reports[1]), fans(reports[2]);
    NodeChecks checks(tables, duplicates, edges, fans);
    for (size_t n = begin; n < end; ++n) checks.check(n);
  });
}

/// False (and a problem logged) when the mesh's scale lies outside what the
/// checks and the improvement handle (core/scale_limits.hpp). (Coordinates that are not finite are the
/// triangles' problems, reported with them.)
bool check_scale(const NodeMesh& m, ProblemLog& log) {
  double largest = 0;
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Vec3& p : m.points) {
    if (!p.allFinite()) continue;
    largest = std::max(largest, p.cwiseAbs().maxCoeff());
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double extent = largest > 0 || lo.allFinite() ? (hi - lo).maxCoeff() : 0;
  if (largest > detail::kFarthestCoordinate || (extent > 0 && extent < detail::kFinestLength)) {
    log.add({}, [&] {
      return cat("scale: the mesh spans ", extent, " with coordinates up to ", largest,
                 "; voronoimesh works on meshes between ", detail::kFinestLength, " and ", detail::kFarthestCoordinate,
                 " in size (scale it into that range)");
    });
    return false;
  }
  return true;
}

void check_node_mesh(const NodeMesh& m, size_t checked, ProblemLog& log) {
  if (!check_scale(m, log)) return; // every other check would fail at this scale
  const size_t num_tris = m.triangles.size(), num_nodes = m.points.size();
  if (m.pairs.size() != num_tris)
    log.add({}, [&] { return cat("size mismatch: ", num_tris, " triangles but ", m.pairs.size(), " phase pairs"); });
  Tables tables(m, checked);
  detail::parallel_for(tbb::blocked_range<size_t>(0, num_tris, kTriangleGrain), [&](const auto& tris) {
    for (size_t t = tris.begin(); t < tris.end(); ++t)
      tables.usable[t] = detail::well_formed(m.triangles[t], num_nodes);
  });
  // Building the node-triangle table is serial, so it runs alongside the triangle checks.
  detail::parallel_invoke([&] { tables.nt = detail::node_triangles(num_nodes, m.triangles, &tables.usable); },
                          [&] {
                            tables.on_box = box_faces(m);
                            check_triangles(tables, log);
                          });
  check_nodes(tables, log);
}

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
  {
    ProblemLog log(report); // sorts the nodes when it goes
    check_node_mesh(m, m.points.size(), log);
  }
  return report;
}

ValidationReport detail::validate_first_nodes(const NodeMesh& m, size_t checked) {
  ValidationReport report;
  {
    ProblemLog log(report);
    check_node_mesh(m, std::min(checked, m.points.size()), log);
  }
  return report;
}

void require_valid(const NodeMesh& m, const std::string& what) {
  const ValidationReport report = validate(m);
  if (!report.ok())
    throw TopologyError(what + " failed validation (" + std::to_string(report.problem_count) +
                        " problems; please report this with the input), first: " + report.problems.front());
}

} // namespace vm

namespace vm {

bool has_zero_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double area = 0.5 * (b - a).cross(c - a).norm();
  const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return !(area > 1e-12 * longest2 && std::isfinite(area) && std::isfinite(longest2));
}

} // namespace vm
