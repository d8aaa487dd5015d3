#include "voronoimesh/collapse.hpp"

#include "voronoimesh/smooth.hpp"
#include "voronoimesh/stats.hpp"
#include "voronoimesh/validate.hpp"

#include <algorithm>

namespace vm {
namespace {

/// True when node b's phases and box faces are all among node a's.
bool covers(const InterfaceMesh& m, int32_t a, int32_t b) {
  if (m.box_faces()[size_t(b)] & ~m.box_faces()[size_t(a)]) return false;
  const PhaseSet &pa = m.phases()[size_t(a)], &pb = m.phases()[size_t(b)];
  for (int i = 0; i < phase_count(pb); ++i)
    if (std::find(pa.begin(), pa.begin() + phase_count(pa), pb[size_t(i)]) == pa.begin() + phase_count(pa)) return false;
  return true;
}

Vec3 normal(const NodeMesh& m, const std::array<int32_t, 3>& t) {
  const Vec3& a = m.points[size_t(t[0])];
  return (m.points[size_t(t[1])] - a).cross(m.points[size_t(t[2])] - a);
}

/// `m` with node b merged into node a: triangles on both disappear. Returns false
/// (leaving `out` unspecified) if a remaining triangle would turn over.
bool merged(const NodeMesh& m, int32_t a, int32_t b, NodeMesh& out) {
  out.points = m.points;
  out.domain = m.domain;
  out.phase_names = m.phase_names;
  out.triangles.clear();
  out.pairs.clear();
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    auto tri = m.triangles[t];
    const bool has_a = std::find(tri.begin(), tri.end(), a) != tri.end();
    const bool has_b = std::find(tri.begin(), tri.end(), b) != tri.end();
    if (has_a && has_b) continue;
    if (has_b) {
      const Vec3 before = normal(m, tri);
      std::replace(tri.begin(), tri.end(), b, a);
      if (normal(m, tri).dot(before) <= 0) return false;
    }
    out.triangles.push_back(tri);
    out.pairs.push_back(m.pairs[t]);
  }
  return true;
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

} // namespace

size_t collapse_junction_slivers(InterfaceMesh& mesh, const CollapseParams& params) {
  if (params.below_quality <= 0) return 0;
  // Candidates, worst first, found on the OpenMesh faces so that the common case
  // (none) costs one pass and no copy. Face f is triangle f of to_node_mesh().
  const OMesh& om = mesh.omesh();
  const auto& pos = mesh.positions();
  std::vector<std::pair<double, size_t>> slivers;
  for (auto f : om.faces()) {
    std::array<int32_t, 3> c;
    auto h = om.halfedge_handle(f);
    for (auto& n : c) {
      n = mesh.node(om.to_vertex_handle(h));
      h = om.next_halfedge_handle(h);
    }
    if (std::any_of(c.begin(), c.end(), [&](int32_t v) { return junction_order(mesh, v) < 3; })) continue;
    const double q = triangle_quality(pos[size_t(c[0])], pos[size_t(c[1])], pos[size_t(c[2])]);
    if (q < params.below_quality) slivers.push_back({q, size_t(f.idx())});
  }
  if (slivers.empty()) return 0;
  std::sort(slivers.begin(), slivers.end());
  NodeMesh m = mesh.to_node_mesh();

  // Node ids stay those of `mesh` until the end (merged() keeps every node), so
  // each collapse is judged with the original phases. Triangle indices refer to
  // the original triangles; one with a node merged away is left alone.
  const std::vector<std::array<int32_t, 3>> original = m.triangles;
  std::vector<char> gone(m.num_nodes(), 0);
  size_t done = 0;
  NodeMesh trial;
  for (const auto& [q, t] : slivers) {
    if (int(done) >= params.max_collapses) break;
    const auto& corners = original[t];
    if (std::any_of(corners.begin(), corners.end(), [&](int32_t v) { return gone[size_t(v)]; })) continue;
    // Edges (b -> a) that may collapse, shortest first.
    std::vector<std::pair<double, std::pair<int32_t, int32_t>>> edges;
    for (int k = 0; k < 3; ++k) {
      const int32_t u = corners[size_t(k)], w = corners[size_t((k + 1) % 3)];
      const double len = (m.points[size_t(u)] - m.points[size_t(w)]).squaredNorm();
      if (covers(mesh, u, w)) edges.push_back({len, {u, w}});
      else if (covers(mesh, w, u)) edges.push_back({len, {w, u}});
    }
    std::sort(edges.begin(), edges.end());
    for (const auto& [len, e] : edges) {
      if (!merged(m, e.first, e.second, trial) || !validate(trial).ok()) continue;
      m = trial;
      gone[size_t(e.second)] = 1;
      ++done;
      break;
    }
  }
  if (done) {
    drop_unused_nodes(m);
    mesh = InterfaceMesh::from_node_mesh(m);
  }
  return done;
}

} // namespace vm
