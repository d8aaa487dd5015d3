#include "voronoimesh/improve/collapse.hpp"

#include "improve/collapse_peers.hpp"

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace vm {
namespace {

using detail::CollapsePeers;
using detail::SliverCollapse;

Vec3 normal(const NodeMesh& m, const std::array<int32_t, 3>& t) {
  const Vec3& a = m.points[size_t(t[0])];
  return (m.points[size_t(t[1])] - a).cross(m.points[size_t(t[2])] - a);
}

/// `m` with every node b of `into` (into[b] = a, or -1) merged into its a:
/// triangles that lose a corner disappear. Appends to `turned` the corners of
/// remaining triangles that would turn over.
void merge(const NodeMesh& m, const std::vector<int32_t>& into, NodeMesh& out, std::vector<int32_t>& turned,
           std::vector<int32_t>& kept_triangles) {
  kept_triangles.clear();
  out = m.empty_like();
  out.points = m.points;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    auto tri = m.triangles[t];
    bool moved = false;
    for (int32_t& v : tri)
      if (into[size_t(v)] >= 0) v = into[size_t(v)], moved = true;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
    if (moved && normal(m, tri).dot(normal(m, m.triangles[t])) <= 0) turned.insert(turned.end(), tri.begin(), tri.end());
    out.triangles.push_back(tri);
    out.pairs.push_back(m.pairs[t]);
    kept_triangles.push_back(int32_t(t));
  }
}

/// Drops nodes no triangle uses and renumbers the rest in order; appends the
/// old index of each kept node to `kept`.
void drop_unused_nodes(NodeMesh& m, std::vector<int32_t>& kept) {
  std::vector<int32_t> id(m.num_nodes(), -1);
  for (const auto& t : m.triangles)
    for (int32_t v : t) id[size_t(v)] = 0;
  std::vector<Vec3> points;
  for (size_t v = 0; v < id.size(); ++v)
    if (id[v] == 0) {
      id[v] = int32_t(points.size());
      points.push_back(m.points[v]);
      kept.push_back(int32_t(v));
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
                   CollapsePeers* peers, std::vector<int32_t>& nodes) {
  // Validation is local: a merge changes only triangles at its target a, whose
  // corners (a and its ring, the "core") are the only nodes whose triangles,
  // edges and fans can change. The triangles at core nodes are validated alone;
  // problems they show only at other nodes are where that cut-out ends, and the
  // mesh around them is as it was (valid). Linear in the mesh only for scans.
  std::vector<uint8_t> target(trial.num_nodes(), 0), core(trial.num_nodes(), 0);
  for (int32_t a : into)
    if (a >= 0 && (!peers || peers->answers_for(a))) target[size_t(a)] = 1; // another rank checks its own
  for (const auto& t : trial.triangles)
    if (target[size_t(t[0])] | target[size_t(t[1])] | target[size_t(t[2])])
      for (int32_t v : t) core[size_t(v)] = 1;
  NodeMesh local = trial.empty_like();
  local.points = trial.points;
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

/// The collapses of one batch, chosen from every sliver worst first (ties by
/// triangle), at most `max` of them, that share no triangle: each claims its
/// two nodes and their rings. `claimed` gets the collapse claiming each id.
std::vector<std::pair<int64_t, int64_t>> choose(std::vector<SliverCollapse> slivers, int max,
                                                std::unordered_map<int64_t, int32_t>& claimed) {
  std::sort(slivers.begin(), slivers.end(), [](const SliverCollapse& x, const SliverCollapse& y) {
    return std::tie(x.quality, x.triangle) < std::tie(y.quality, y.triangle);
  });
  std::vector<std::pair<int64_t, int64_t>> chosen;
  for (const SliverCollapse& s : slivers) {
    if (int(chosen.size()) >= max) break;
    if (s.a < 0 || std::any_of(s.claims.begin(), s.claims.end(), [&](int64_t n) { return claimed.count(n); }))
      continue;
    for (int64_t n : s.claims) claimed[n] = int32_t(chosen.size());
    chosen.push_back({s.a, s.b});
  }
  return chosen;
}

/// The slivers this rank answers for, with the collapse each would make.
std::vector<SliverCollapse> find_slivers(const InterfaceMesh& mesh, const CollapseParams& params, CollapsePeers* peers,
                                         std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids) {
  // Found on the OpenMesh faces so that the common case (none) costs one pass
  // and no copy. Face f is triangle f of to_node_mesh().
  const OMesh& om = mesh.omesh();
  const auto& pos = mesh.positions();
  std::vector<SliverCollapse> slivers;
  for (auto f : om.faces()) {
    const std::array<int32_t, 3> c = mesh.face_nodes(f);
    if (peers && !peers->answers_for(*std::min_element(c.begin(), c.end()))) continue;
    // Two corners on junctions can be an edge along a junction (a triple curve
    // with nodes bunched where a tiny face ends), which no flip may touch; a
    // sliver with fewer is the flips' to mend.
    if (std::count_if(c.begin(), c.end(), [&](int32_t v) { return junction_order(mesh, v) >= 3; }) < 2) continue;
    const double q = triangle_quality(pos[size_t(c[0])], pos[size_t(c[1])], pos[size_t(c[2])]);
    if (q >= params.below_quality) continue;
    // The edge (b -> a) to collapse: the shortest whose b has its constraints
    // among a's, judged with the original phases.
    std::pair<double, std::array<int32_t, 2>> best{INFINITY, {-1, -1}};
    for (int k = 0; k < 3; ++k) {
      const int32_t u = c[size_t(k)], w = c[size_t((k + 1) % 3)];
      const double len = (pos[size_t(u)] - pos[size_t(w)]).squaredNorm();
      if (len < best.first && mesh.constraints_within(w, u)) best = {len, {u, w}};
      else if (len < best.first && mesh.constraints_within(u, w)) best = {len, {w, u}};
    }
    SliverCollapse s{q, triangle_ids[size_t(f.idx())], -1, -1, {}};
    const auto [a, b] = best.second;
    if (a >= 0) {
      s.a = node_ids[size_t(a)];
      s.b = node_ids[size_t(b)];
      for (int32_t n : {a, b}) {
        s.claims.push_back(node_ids[size_t(n)]);
        for (int32_t w : mesh.neighbours(n)) s.claims.push_back(node_ids[size_t(w)]);
      }
    }
    slivers.push_back(std::move(s));
  }
  return slivers;
}

size_t collapse(InterfaceMesh& mesh, const CollapseParams& params, CollapsePeers* peers,
                std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids, detail::CollapseKept& kept) {
  if (params.below_quality <= 0) return 0;
  std::vector<SliverCollapse> slivers = find_slivers(mesh, params, peers, node_ids, triangle_ids);
  if (peers) slivers = peers->all(slivers);
  if (slivers.empty()) return 0;
  std::unordered_map<int64_t, int32_t> claimed; // id -> the collapse claiming it
  const std::vector<std::pair<int64_t, int64_t>> chosen = choose(std::move(slivers), params.max_collapses, claimed);
  // Ids back to this mesh's nodes (ids ascend with the nodes).
  auto local = [&](int64_t id) {
    const auto at = std::lower_bound(node_ids.begin(), node_ids.end(), id);
    return at != node_ids.end() && *at == id ? int32_t(at - node_ids.begin()) : -1;
  };
  NodeMesh m = mesh.to_node_mesh();

  // All at once, checked once. Collapses in a batch share no triangle, so each
  // failing node belongs to one collapse's rings: those collapses are dropped
  // and the rest checked again (one or two whole-mesh checks, not one per collapse).
  std::vector<char> active(chosen.size(), 1);
  std::vector<int32_t> into(m.num_nodes(), -1), failed, kept_triangles;
  NodeMesh trial;
  size_t done = 0;
  for (size_t left = chosen.size(); left > 0;) {
    std::fill(into.begin(), into.end(), -1);
    for (size_t i = 0; i < chosen.size(); ++i)
      if (const int32_t a = local(chosen[i].first), b = local(chosen[i].second); active[i] && a >= 0 && b >= 0)
        into[size_t(b)] = a;
    failed.clear();
    merge(m, into, trial, failed, kept_triangles);
    if (peers) std::erase_if(failed, [&](int32_t n) { return !peers->answers_for(n); });
    // Triangles that turn over are failures enough; only without them is the
    // merged mesh validated (by every rank, if any rank saw them).
    bool blamed = peers ? peers->any(!failed.empty()) : !failed.empty();
    if (!blamed) blamed = find_failures(trial, into, params.guard_crossings, peers, failed);
    if (peers) blamed = !peers->any(!blamed);
    std::vector<int64_t> failed_ids;
    for (int32_t n : failed) failed_ids.push_back(node_ids[size_t(n)]);
    if (peers) failed_ids = peers->all(failed_ids);
    if (blamed && failed_ids.empty()) {
      m = std::move(trial);
      done = left;
      break;
    }
    size_t dropped = 0;
    for (int64_t id : failed_ids)
      if (const auto c = claimed.find(id); c != claimed.end() && active[size_t(c->second)])
        active[size_t(c->second)] = 0, ++dropped;
    if (!blamed || dropped == 0) break; // a failure no collapse answers for: keep the mesh as it was
    left -= dropped;
  }
  if (done) {
    kept.triangles = kept_triangles;
    drop_unused_nodes(m, kept.nodes);
    mesh = InterfaceMesh::from_node_mesh(m);
    if (params.guard) params.guard->renumbered(mesh, kept.triangles, kept.nodes);
  }
  return done;
}

} // namespace

size_t collapse_junction_slivers(InterfaceMesh& mesh, const CollapseParams& params) {
  std::vector<int64_t> ids(std::max(mesh.num_nodes(), mesh.num_triangles()));
  std::iota(ids.begin(), ids.end(), 0);
  detail::CollapseKept kept;
  return collapse(mesh, params, nullptr, std::span(ids).first(mesh.num_nodes()),
                  std::span(ids).first(mesh.num_triangles()), kept);
}

namespace detail {

size_t collapse_junction_slivers(InterfaceMesh& mesh, const CollapseParams& params, CollapsePeers& peers,
                                 std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids,
                                 CollapseKept& kept) {
  return collapse(mesh, params, &peers, node_ids, triangle_ids, kept);
}

} // namespace detail

} // namespace vm
