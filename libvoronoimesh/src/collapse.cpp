#include "voronoimesh/collapse.hpp"

#include "voronoimesh/intersections.hpp"
#include "voronoimesh/smooth.hpp"
#include "voronoimesh/stats.hpp"
#include "voronoimesh/validate.hpp"

#include <algorithm>
#include <cmath>

namespace vm {
namespace {

Vec3 normal(const NodeMesh& m, const std::array<int32_t, 3>& t) {
  const Vec3& a = m.points[size_t(t[0])];
  return (m.points[size_t(t[1])] - a).cross(m.points[size_t(t[2])] - a);
}

/// `m` with every node b of `into` (into[b] = a, or -1) merged into its a:
/// triangles that lose a corner disappear. Appends to `turned` the corners of
/// remaining triangles that would turn over.
void merge(const NodeMesh& m, const std::vector<int32_t>& into, NodeMesh& out, std::vector<int32_t>& turned) {
  out.points = m.points;
  out.domain = m.domain;
  out.phase_names = m.phase_names;
  out.phase_labels = m.phase_labels;
  out.triangles.clear();
  out.pairs.clear();
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    auto tri = m.triangles[t];
    bool moved = false;
    for (int32_t& v : tri)
      if (into[size_t(v)] >= 0) v = into[size_t(v)], moved = true;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
    if (moved && normal(m, tri).dot(normal(m, m.triangles[t])) <= 0) turned.insert(turned.end(), tri.begin(), tri.end());
    out.triangles.push_back(tri);
    out.pairs.push_back(m.pairs[t]);
  }
}

/// Drops nodes no triangle uses and renumbers the rest in order.
void drop_unused_nodes(NodeMesh& m) {
  std::vector<int32_t> id(m.num_nodes(), -1);
  for (const auto& t : m.triangles)
    for (int32_t v : t) id[size_t(v)] = 0;
  std::vector<Vec3> points;
  for (size_t v = 0; v < id.size(); ++v)
    if (id[v] == 0) {
      id[v] = int32_t(points.size());
      points.push_back(m.points[v]);
    }
  for (auto& t : m.triangles)
    for (int32_t& v : t) v = id[size_t(v)];
  m.points = std::move(points);
}

/// Where `trial` (m after merging by `into`) fails: appends the nodes of
/// validation problems and, if asked, the corners of triangles at a merge target
/// that cross a triangle of another surface. Returns false if it fails somewhere
/// no node names (then nothing in the batch can be trusted).
bool find_failures(const NodeMesh& trial, const std::vector<int32_t>& into, bool guard_crossings,
                   std::vector<int32_t>& nodes) {
  // Validation is local: a merge changes only triangles at its target a, whose
  // corners (a and its ring, the "core") are the only nodes whose triangles,
  // edges and fans can change. The triangles at core nodes are validated alone;
  // problems they show only at other nodes are where that cut-out ends, and the
  // mesh around them is as it was (valid). Linear in the mesh only for scans.
  std::vector<uint8_t> target(trial.num_nodes(), 0), core(trial.num_nodes(), 0);
  for (int32_t a : into)
    if (a >= 0) target[size_t(a)] = 1;
  for (const auto& t : trial.triangles)
    if (target[size_t(t[0])] | target[size_t(t[1])] | target[size_t(t[2])])
      for (int32_t v : t) core[size_t(v)] = 1;
  NodeMesh local;
  local.points = trial.points;
  local.domain = trial.domain;
  local.phase_names = trial.phase_names;
  local.phase_labels = trial.phase_labels;
  for (size_t t = 0; t < trial.num_triangles(); ++t) {
    const auto& tri = trial.triangles[t];
    if (core[size_t(tri[0])] | core[size_t(tri[1])] | core[size_t(tri[2])]) {
      local.triangles.push_back(tri);
      local.pairs.push_back(trial.pairs[t]);
    }
  }
  const ValidationReport report = validate(local);
  if (!report.ok() && report.nodes.empty()) return false;
  for (int32_t n : report.nodes)
    if (core[size_t(n)]) nodes.push_back(n);
  if (!guard_crossings) return true;
  std::vector<uint8_t> involved(trial.num_triangles(), 0);
  for (size_t t = 0; t < trial.num_triangles(); ++t)
    for (int32_t v : trial.triangles[t]) involved[t] |= target[size_t(v)];
  const IntersectionReport crossings =
      find_self_intersections(trial, std::numeric_limits<size_t>::max(), involved, false);
  for (const auto& pair : crossings.pairs)
    for (int32_t t : pair) nodes.insert(nodes.end(), trial.triangles[size_t(t)].begin(), trial.triangles[size_t(t)].end());
  return true;
}

} // namespace

size_t collapse_junction_slivers(InterfaceMesh& mesh, const CollapseParams& params) {
  if (params.below_quality <= 0) return 0;
  // Candidates, worst first, found on the OpenMesh faces so that the common case
  // (none) costs one pass and no copy. Face f is triangle f of to_node_mesh().
  const OMesh& om = mesh.omesh();
  const auto& pos = mesh.positions();
  std::vector<std::pair<double, size_t>> slivers;
  for (auto f : om.faces()) {
    const std::array<int32_t, 3> c = mesh.face_nodes(f);
    // Two corners on junctions can be an edge along a junction (a triple curve
    // with nodes bunched where a tiny face ends), which no flip may touch; a
    // sliver with fewer is the flips' to mend.
    if (std::count_if(c.begin(), c.end(), [&](int32_t v) { return junction_order(mesh, v) >= 3; }) < 2) continue;
    const double q = triangle_quality(pos[size_t(c[0])], pos[size_t(c[1])], pos[size_t(c[2])]);
    if (q < params.below_quality) slivers.push_back({q, size_t(f.idx())});
  }
  if (slivers.empty()) return 0;
  std::sort(slivers.begin(), slivers.end());
  NodeMesh m = mesh.to_node_mesh();

  // The edge (b -> a) each sliver would collapse: the shortest whose b has its
  // constraints among a's. Node ids are those of `mesh` throughout (merged()
  // keeps every node), so each choice is judged with the original phases.
  struct Collapse {
    int32_t a, b;
  };
  std::vector<Collapse> chosen;
  // The collapse that claimed each node (its two nodes and their rings), or -1.
  std::vector<int32_t> owner(m.num_nodes(), -1);
  for (const auto& [q, t] : slivers) {
    if (int(chosen.size()) >= params.max_collapses) break;
    const auto& corners = m.triangles[t];
    std::pair<double, Collapse> best{INFINITY, {-1, -1}};
    for (int k = 0; k < 3; ++k) {
      const int32_t u = corners[size_t(k)], w = corners[size_t((k + 1) % 3)];
      const double len = (m.points[size_t(u)] - m.points[size_t(w)]).squaredNorm();
      if (len < best.first && mesh.constraints_within(w, u)) best = {len, {u, w}};
      else if (len < best.first && mesh.constraints_within(u, w)) best = {len, {w, u}};
    }
    const Collapse c = best.second;
    if (c.a < 0 || owner[size_t(c.a)] >= 0 || owner[size_t(c.b)] >= 0) continue;
    // Collapses in one batch must not share a triangle: claim both rings.
    bool clear = true;
    for (int32_t n : {c.a, c.b})
      for (int32_t w : mesh.neighbours(n)) clear = clear && owner[size_t(w)] < 0;
    if (!clear) continue;
    for (int32_t n : {c.a, c.b}) {
      owner[size_t(n)] = int32_t(chosen.size());
      for (int32_t w : mesh.neighbours(n)) owner[size_t(w)] = int32_t(chosen.size());
    }
    chosen.push_back(c);
  }

  // All at once, checked once. Collapses in a batch share no triangle, so each
  // failing node belongs to one collapse's rings: those collapses are dropped
  // and the rest checked again (one or two whole-mesh checks, not one per collapse).
  std::vector<char> active(chosen.size(), 1);
  std::vector<int32_t> into(m.num_nodes(), -1), failed;
  NodeMesh trial;
  size_t done = 0;
  for (size_t left = chosen.size(); left > 0;) {
    std::fill(into.begin(), into.end(), -1);
    for (size_t i = 0; i < chosen.size(); ++i)
      if (active[i]) into[size_t(chosen[i].b)] = chosen[i].a;
    failed.clear();
    merge(m, into, trial, failed);
    const bool blamed = !failed.empty() || find_failures(trial, into, params.guard_crossings, failed);
    if (blamed && failed.empty()) {
      m = std::move(trial);
      done = left;
      break;
    }
    size_t dropped = 0;
    for (int32_t n : failed)
      if (owner[size_t(n)] >= 0 && active[size_t(owner[size_t(n)])]) active[size_t(owner[size_t(n)])] = 0, ++dropped;
    if (!blamed || dropped == 0) break; // a failure no collapse answers for: keep the mesh as it was
    left -= dropped;
  }
  if (done) {
    drop_unused_nodes(m);
    mesh = InterfaceMesh::from_node_mesh(m);
  }
  return done;
}

} // namespace vm
