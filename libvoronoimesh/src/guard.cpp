#include "voronoimesh/guard.hpp"

#include "detail/box_pairs.hpp"
#include "detail/field_orientation.hpp"
#include "detail/parallel.hpp"
#include "detail/triangle_pair.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vm {
namespace {

using detail::Bounds;
using detail::Triangle;

/// The candidate margin, as a share of the median triangle size: a larger one
/// keeps more pairs but finds them again less often.
constexpr double kMarginShare = 0.15;
/// When more than this share of the triangles changed since the pairs were
/// found, they are all found again rather than patched.
constexpr double kPatchShare = 0.05;

bool share_node(const Triangle& a, const Triangle& b) {
  for (int32_t v : a)
    if (v == b[0] || v == b[1] || v == b[2]) return true;
  return false;
}

Bounds grown(Bounds b, double by) {
  b.lo.array() -= by;
  b.hi.array() += by;
  return b;
}

/// A lower bound on the distance between triangles a and b without a common
/// node: the gap between their boxes, or between one's plane and the other's
/// corners when those all lie on one side; 0 if neither separates them.
/// `slack` is taken off, so rounding can never make a touching pair look apart.
double separation(std::span<const Vec3> p, const Triangle& a, const Triangle& b, double slack) {
  const Bounds ba = detail::triangle_bounds(p, a), bb = detail::triangle_bounds(p, b);
  double gap = 0;
  for (int k = 0; k < 3; ++k) gap = std::max({gap, bb.lo[k] - ba.hi[k], ba.lo[k] - bb.hi[k]});
  auto plane_gap = [&](const Triangle& t, const Triangle& o) {
    const Vec3& origin = p[size_t(t[0])];
    const Vec3 n = (p[size_t(t[1])] - origin).cross(p[size_t(t[2])] - origin);
    const double length = n.norm();
    if (!(length > 0)) return 0.0;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int32_t v : o) {
      const double d = n.dot(p[size_t(v)] - origin) / length;
      lo = std::min(lo, d), hi = std::max(hi, d);
    }
    return lo > 0 ? lo : hi < 0 ? -hi : 0.0;
  };
  gap = std::max({gap, plane_gap(a, b), plane_gap(b, a)});
  return gap > slack ? gap - slack : 0.0;
}

/// True when the fan of OpenMesh vertex v (its triangles in one patch) is
/// certainly embedded: seen along the sum of its normals, every triangle turns
/// the right way (so each spans a sector of less than half a turn at v, and
/// the sectors follow each other around v), and no sector but the first and
/// the closing one reaches the first edge's direction, so the sectors go round
/// once at most: that view is one to one, and no two triangles of the fan can
/// meet except where they share nodes. Decided in floating point with margins
/// far above rounding; a fan it cannot vouch for is tested pair by pair.
bool fan_is_embedded(const InterfaceMesh& mesh, OMesh::VertexHandle v) {
  const OMesh& om = mesh.omesh();
  const auto& p = mesh.positions();
  const Vec3& centre = p[size_t(mesh.node(v))];
  // The fan's edges from v in turning order; open fans start at a boundary edge.
  thread_local std::vector<Vec3> edges;
  edges.clear();
  auto start = om.halfedge_handle(v);
  if (!start.is_valid()) return false;
  // OpenMesh keeps a boundary vertex's outgoing halfedge on the boundary: the
  // fan starts at the edge after it, turning.
  if (om.is_boundary(v)) start = om.opposite_halfedge_handle(om.prev_halfedge_handle(start));
  for (auto h = start;;) {
    edges.push_back(p[size_t(mesh.node(om.to_vertex_handle(h)))] - centre);
    if (om.is_boundary(h)) break; // reached the other side of an open fan
    h = om.opposite_halfedge_handle(om.prev_halfedge_handle(h)); // next edge, turning
    if (h == start) break;
  }
  const bool closed = !om.is_boundary(v);
  const size_t sectors = closed ? edges.size() : edges.size() - 1;
  size_t faces = 0;
  for ([[maybe_unused]] auto f : om.vf_range(v)) ++faces;
  if (sectors == 0 || sectors != faces) return false; // not one fan: leave it to the exact tests
  auto edge = [&](size_t i) -> const Vec3& { return edges[i % edges.size()]; };
  Vec3 axis = Vec3::Zero();
  for (size_t i = 0; i < sectors; ++i) axis += edge(i).cross(edge(i + 1));
  // "x > margin |a| |b| |axis|" with squares, as sqrt costs more than the rest.
  constexpr double kMargin2 = 1e-24;
  const double axis2 = axis.squaredNorm();
  thread_local std::vector<double> length2;
  length2.resize(edges.size());
  for (size_t i = 0; i < edges.size(); ++i) length2[i] = edges[i].squaredNorm();
  auto clearly_positive = [&](double x, double a2, double b2) { return x > 0 && x * x > kMargin2 * a2 * b2 * axis2; };
  auto clearly_negative = [&](double x, double a2, double b2) { return x < 0 && x * x > kMargin2 * a2 * b2 * axis2; };
  for (size_t i = 0; i < sectors; ++i)
    if (!clearly_positive(edge(i).cross(edge(i + 1)).dot(axis), length2[i], length2[(i + 1) % edges.size()]))
      return false;
  // Sector i must clearly miss the first edge's direction: one of its sides
  // clearly turns the other way (margins count as holding it).
  const Vec3& first = edge(0);
  for (size_t i = 1; i < (closed ? sectors - 1 : sectors); ++i) {
    const size_t next = (i + 1) % edges.size();
    if (!clearly_negative(edge(i).cross(first).dot(axis), length2[i], length2[0]) &&
        !clearly_negative(first.cross(edge(next)).dot(axis), length2[0], length2[next]))
      return false;
  }
  return true;
}

} // namespace

/// The kept pairs. Positions are measured from `anchor`, where the nodes were
/// when the pairs were found: a pair left out had boxes more than 2 margins
/// apart then, so it cannot meet while every node stays within a margin of its
/// anchor. A pair's clearance is a lower bound on its distance at the anchors
/// (less what its nodes had moved when it was measured), so while the nodes'
/// distances from their anchors add up to less, it cannot meet either.
struct CrossingGuard::State {
  const PhaseField* field = nullptr;
  bool built = false;
  uint64_t version = 0;
  std::vector<Triangle> tris; ///< the mesh's triangles as of `version`
  std::vector<Triangle> corner_copies; ///< the OpenMesh vertex of each corner of tris
  std::vector<uint8_t> embedded;       ///< per OpenMesh vertex: fan_is_embedded, for fans checked this round
  std::vector<PhasePair> pairs;
  std::vector<int32_t> watched; ///< triangles with a junction corner (field check)
  std::vector<Vec3> anchor;
  double margin = 0, slack = 0;
  std::vector<detail::BoxPair> candidates;
  std::vector<double> clearance; ///< per candidate; negative: shares a node, always tested
  std::vector<double> drift;     ///< per triangle: farthest corner from its anchor
  std::vector<uint8_t> outdated; ///< per triangle: changed by flips, its pairs not found yet

  void sync(const InterfaceMesh& mesh);
  void find_all(const InterfaceMesh& mesh);
  void find_for(const InterfaceMesh& mesh, const std::vector<uint8_t>& changed);
  void measure_drift(std::span<const Vec3> p);
  void refresh_drifted(const InterfaceMesh& mesh);
  /// Triangles t and u (sharing a node) lie in one fan that fan_is_embedded vouched for.
  bool in_embedded_fan(int32_t t, int32_t u) const {
    for (size_t k = 0; k < 3; ++k) {
      const int32_t copy = corner_copies[size_t(t)][k];
      if (!embedded[size_t(copy)]) continue;
      for (size_t j = 0; j < 3; ++j)
        if (corner_copies[size_t(u)][j] == copy) return true;
    }
    return false;
  }
  double clearance_of(std::span<const Vec3> p, const Triangle& a, const Triangle& b) const {
    return share_node(a, b) ? -1.0 : separation(p, a, b, slack);
  }
};

void CrossingGuard::State::sync(const InterfaceMesh& mesh) {
  if (built && mesh.topology_version() == version) return;
  const size_t nt = mesh.num_triangles();
  std::vector<Triangle> now(nt);
  corner_copies.resize(nt);
  const OMesh& om = mesh.omesh();
  detail::parallel_for_each_index(nt, [&](size_t t) {
    // As InterfaceMesh::face_nodes walks the face, keeping the copies too.
    auto h = om.halfedge_handle(OMesh::FaceHandle(int(t)));
    for (size_t k = 0; k < 3; ++k) {
      const auto v = om.to_vertex_handle(h);
      now[t][k] = mesh.node(v);
      corner_copies[t][k] = v.idx();
      h = om.next_halfedge_handle(h);
    }
  });
  embedded.assign(om.n_vertices(), 0);
  const bool renumbered = !built || nt != tris.size() || mesh.num_nodes() != anchor.size();
  std::vector<uint8_t> changed(nt, 1);
  if (!renumbered)
    detail::parallel_for_each_index(nt, [&](size_t t) {
      Triangle a = now[t], b = tris[t];
      std::sort(a.begin(), a.end()), std::sort(b.begin(), b.end());
      changed[t] = a != b;
    });
  tris = std::move(now);
  pairs.resize(nt);
  detail::parallel_for_each_index(nt, [&](size_t t) { pairs[t] = mesh.pair(OMesh::FaceHandle(int(t))); });
  watched.clear();
  if (field)
    for (size_t t = 0; t < nt; ++t)
      if (detail::touches_junction(mesh, tris[t])) watched.push_back(int32_t(t));
  version = mesh.topology_version();
  if (renumbered) find_all(mesh);
  else outdated = std::move(changed); // found once the move is known, with the drifted ones
  built = true;
}

void CrossingGuard::State::find_all(const InterfaceMesh& mesh) {
  const auto& p = mesh.positions();
  anchor = p;
  const size_t nt = tris.size();
  std::vector<Bounds> boxes(nt);
  std::vector<double> extent(nt);
  detail::parallel_for_each_index(nt, [&](size_t t) {
    boxes[t] = detail::triangle_bounds(p, tris[t]);
    extent[t] = (boxes[t].hi - boxes[t].lo).maxCoeff();
  });
  double scale = 0;
  for (const Vec3& x : p) scale = std::max(scale, x.cwiseAbs().maxCoeff());
  slack = 1e-12 * std::max(scale, 1e-300);
  if (nt > 0) {
    auto mid = extent.begin() + ptrdiff_t(nt / 2);
    std::nth_element(extent.begin(), mid, extent.end());
    margin = kMarginShare * *mid;
  }
  detail::parallel_for_each_index(nt, [&](size_t t) { boxes[t] = grown(boxes[t], margin); });
  candidates = detail::overlapping_box_pairs(boxes);
  clearance.resize(candidates.size());
  detail::parallel_for_each_index(candidates.size(), [&](size_t i) {
    clearance[i] = clearance_of(p, tris[size_t(candidates[i][0])], tris[size_t(candidates[i][1])]);
  });
}

void CrossingGuard::State::find_for(const InterfaceMesh& mesh, const std::vector<uint8_t>& changed) {
  // Nodes are up to a margin from their anchors now and may go up to another
  // before the pairs are all found again, so boxes grow by 2 margins here.
  const auto& p = mesh.positions();
  measure_drift(p);
  const size_t nt = tris.size();
  std::vector<Bounds> boxes(nt);
  detail::parallel_for_each_index(nt, [&](size_t t) { boxes[t] = grown(detail::triangle_bounds(p, tris[t]), 2 * margin); });
  const std::vector<int32_t> near = detail::boxes_near(boxes, changed);
  std::vector<Bounds> local(near.size());
  for (size_t i = 0; i < near.size(); ++i) local[i] = boxes[size_t(near[i])];
  std::vector<detail::BoxPair> found = detail::overlapping_box_pairs(local);
  std::erase_if(found, [&](detail::BoxPair& pair) {
    pair = {near[size_t(pair[0])], near[size_t(pair[1])]};
    return !changed[size_t(pair[0])] && !changed[size_t(pair[1])];
  });
  // Drop the changed triangles' old pairs, then add their new ones.
  size_t kept = 0;
  for (size_t i = 0; i < candidates.size(); ++i)
    if (!changed[size_t(candidates[i][0])] && !changed[size_t(candidates[i][1])]) {
      candidates[kept] = candidates[i];
      clearance[kept++] = clearance[i];
    }
  candidates.resize(kept);
  clearance.resize(kept);
  candidates.insert(candidates.end(), found.begin(), found.end());
  clearance.resize(candidates.size());
  detail::parallel_for_each_index(found.size(), [&](size_t i) {
    const auto [t, s] = found[i];
    const double c = clearance_of(p, tris[size_t(t)], tris[size_t(s)]);
    clearance[kept + i] = c < 0 ? c : std::max(0.0, c - drift[size_t(t)] - drift[size_t(s)]);
  });
}

void CrossingGuard::State::refresh_drifted(const InterfaceMesh& mesh) {
  // Nodes past half a margin from their anchors are anchored where they are
  // now and their triangles' pairs found again (with those flips changed), so
  // no node ever gets a margin away.
  const auto& p = mesh.positions();
  std::vector<uint8_t> far(p.size());
  detail::parallel_for_each_index(p.size(), [&](size_t n) { far[n] = (p[n] - anchor[n]).norm() > 0.5 * margin; });
  std::vector<uint8_t> stale(tris.size());
  outdated.resize(tris.size());
  detail::parallel_for_each_index(tris.size(), [&](size_t t) {
    stale[t] = outdated[t] | far[size_t(tris[t][0])] | far[size_t(tris[t][1])] | far[size_t(tris[t][2])];
  });
  std::fill(outdated.begin(), outdated.end(), 0);
  const auto count = size_t(std::count(stale.begin(), stale.end(), 1));
  if (double(count) > kPatchShare * double(tris.size())) find_all(mesh);
  else if (count > 0) {
    for (size_t n = 0; n < p.size(); ++n)
      if (far[n]) anchor[n] = p[n];
    find_for(mesh, stale);
  }
  measure_drift(p);
}

void CrossingGuard::State::measure_drift(std::span<const Vec3> p) {
  std::vector<double> node(p.size());
  detail::parallel_for_each_index(p.size(), [&](size_t n) { node[n] = (p[n] - anchor[n]).norm(); });
  drift.resize(tris.size());
  detail::parallel_for_each_index(tris.size(), [&](size_t t) {
    const Triangle& tri = tris[t];
    drift[t] = std::max({node[size_t(tri[0])], node[size_t(tri[1])], node[size_t(tri[2])]});
  });
}

CrossingGuard::CrossingGuard(const PhaseField* field) : state_(std::make_unique<State>()) { state_->field = field; }
CrossingGuard::~CrossingGuard() = default;
CrossingGuard::CrossingGuard(CrossingGuard&&) noexcept = default;
CrossingGuard& CrossingGuard::operator=(CrossingGuard&&) noexcept = default;

GuardReport CrossingGuard::commit(InterfaceMesh& mesh, std::vector<Vec3>& delta) {
  State& s = *state_;
  s.sync(mesh);
  GuardReport report;
  const std::vector<Vec3> before = mesh.positions();
  const auto& tris = s.tris;
  std::vector<uint8_t> agreed(s.watched.size()), turned(s.watched.size());
  auto agrees = [&](std::span<const Vec3> p, size_t i) {
    const auto t = size_t(s.watched[i]);
    return detail::agrees_with_field(p, tris[t], s.pairs[t], *s.field);
  };
  detail::parallel_for_each_index(s.watched.size(), [&](size_t i) { agreed[i] = agrees(before, i); });
  mesh.move_nodes(delta);
  const auto& p = mesh.positions();
  s.refresh_drifted(mesh);
  std::vector<uint8_t> moved(mesh.num_nodes()), changed(mesh.num_nodes());
  detail::parallel_for_each_index(moved.size(), [&](size_t n) { changed[n] = moved[n] = !delta[n].isZero(0); });
  std::vector<uint8_t> involved(tris.size());
  std::vector<int8_t> axis(tris.size());
  tbb::enumerable_thread_specific<std::vector<int32_t>> crossing;
  while (true) {
    // Only triangles changed since the last check can have started to cross.
    detail::parallel_for_each_index(involved.size(), [&](size_t t) {
      const auto& tri = tris[t];
      involved[t] = changed[size_t(tri[0])] | changed[size_t(tri[1])] | changed[size_t(tri[2])];
      if (involved[t]) axis[t] = detail::projection_axis(p[size_t(tri[0])], p[size_t(tri[1])], p[size_t(tri[2])]);
    });
    detail::parallel_for_each_index(s.watched.size(), [&](size_t i) {
      turned[i] = agreed[i] && !agrees(p, i);
    });
    // Fans with a changed triangle: certified fans spare their pairs the exact test.
    const OMesh& om = mesh.omesh();
    detail::parallel_for_each_index(om.n_vertices(), [&](size_t c) {
      const auto v = OMesh::VertexHandle(int(c));
      bool touched = false;
      for (auto f : om.vf_range(v)) touched = touched || involved[size_t(f.idx())];
      if (touched) s.embedded[c] = fan_is_embedded(mesh, v);
    });
    ++report.rounds;
    for (auto& found : crossing) found.clear();
    detail::parallel_for_each_index(s.candidates.size(), [&](size_t i) {
      const auto [t, u] = s.candidates[i];
      if (!involved[size_t(t)] && !involved[size_t(u)]) return;
      double& c = s.clearance[i];
      const double drift = s.drift[size_t(t)] + s.drift[size_t(u)];
      if (c > drift) return; // cannot have met: apart by more than the nodes have moved
      if (c < 0 && s.in_embedded_fan(t, u)) return;
      auto axis_of = [&](int32_t f) {
        const auto& tri = tris[size_t(f)];
        return involved[size_t(f)] ? axis[size_t(f)]
                                   : detail::projection_axis(p[size_t(tri[0])], p[size_t(tri[1])], p[size_t(tri[2])]);
      };
      if (detail::intersect_improperly(p, tris[size_t(t)], tris[size_t(u)], axis_of(t), axis_of(u))) {
        auto& found = crossing.local();
        found.push_back(t), found.push_back(u);
      } else if (c >= 0) {
        c = std::max(0.0, s.clearance_of(p, tris[size_t(t)], tris[size_t(u)]) - drift);
      }
    }, 256);
    std::vector<int32_t> culprits;
    for (const auto& found : crossing) culprits.insert(culprits.end(), found.begin(), found.end());
    for (size_t i = 0; i < s.watched.size(); ++i)
      if (turned[i]) culprits.push_back(s.watched[i]);
    std::fill(changed.begin(), changed.end(), 0);
    std::vector<int32_t> undo;
    for (int32_t t : culprits)
      for (int32_t n : tris[size_t(t)])
        if (moved[size_t(n)]) {
          moved[size_t(n)] = 0;
          changed[size_t(n)] = 1;
          undo.push_back(n);
        }
    if (undo.empty()) break; // clean, or only what the mesh had before the move
    std::vector<Vec3> back(undo.size());
    for (size_t i = 0; i < undo.size(); ++i) {
      back[i] = before[size_t(undo[i])];
      delta[size_t(undo[i])].setZero();
    }
    mesh.place_nodes(undo, back);
    s.measure_drift(p);
    report.undone_nodes += undo.size();
  }
  return report;
}

GuardReport commit_without_crossings(InterfaceMesh& mesh, std::vector<Vec3>& delta, const PhaseField* field) {
  return CrossingGuard(field).commit(mesh, delta);
}

} // namespace vm
