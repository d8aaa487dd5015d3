/// @file check/validate_interface.cpp
/// validate(InterfaceMesh): the node-level checks plus the patch-split
/// invariants of openmesh-probe.md ("Invariants" 1-5): manifold OpenMesh
/// vertices, boundary edges exactly at junction and domain edges, one OpenMesh
/// edge per patch-interior node-edge, copies and phase sets consistent,
/// point() mirroring the node positions.

#include "voronoimesh/check/validate.hpp"

#include "check/problem_log.hpp"
#include "mesh/topology.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <algorithm>

namespace vm {

namespace {

using detail::cat;

void check_copies(const InterfaceMesh& m, detail::ProblemLog& log) {
  const OMesh& om = m.omesh();
  std::vector<char> listed(om.n_vertices(), 0);
  for (size_t n = 0; n < m.num_nodes(); ++n)
    for (int32_t v : m.copies(int32_t(n))) {
      if (v < 0 || size_t(v) >= om.n_vertices() || listed[size_t(v)]++ || m.node(OMesh::VertexHandle(v)) != int32_t(n))
        log.add({int32_t(n)},
                [&] { return cat("copies: node ", n, " lists OpenMesh vertex ", v, " that is not its own copy"); });
    }
  for (auto vh : om.vertices()) {
    const int32_t n = m.node(vh);
    if (n < 0 || size_t(n) >= m.num_nodes()) {
      log.add({}, [&] { return cat("copies: OpenMesh vertex ", vh.idx(), " has node ", n, " out of range"); });
      continue;
    }
    if (!listed[size_t(vh.idx())])
      log.add({n}, [&] { return cat("copies: OpenMesh vertex ", vh.idx(), " missing from the copies of node ", n); });
    if (!om.is_manifold(vh))
      log.add({n}, [&] { return cat("non-manifold copy: OpenMesh vertex ", vh.idx(), " (node ", n, ")"); });
    const auto& p = om.point(vh);
    const Vec3& x = m.positions()[size_t(n)];
    if (p[0] != x.x() || p[1] != x.y() || p[2] != x.z())
      log.add({n},
              [&] { return cat("stale point: OpenMesh vertex ", vh.idx(), " differs from the position of node ", n); });
  }
}

void check_phase_sets(const InterfaceMesh& m, const detail::NodePhases& np, detail::ProblemLog& log) {
  for (size_t n = 0; n < m.num_nodes(); ++n) {
    const PhaseSet& s = m.phases()[n];
    auto expect = np.of(n);
    const bool same = size_t(phase_count(s)) == expect.size() && std::equal(expect.begin(), expect.end(), s.begin()) &&
                      std::all_of(s.begin() + long(expect.size()), s.end(), [](int16_t p) { return p == -1; });
    if (!same)
      log.add({int32_t(n)}, [&] { return cat("phase set: node ", n, " does not hold the phases of its triangles"); });
  }
}

/// An OpenMesh edge is boundary exactly when its node-edge is not patch
/// interior; a patch-interior node-edge has one OpenMesh edge, any other one
/// OpenMesh edge per triangle.
void check_edges(const InterfaceMesh& m, const NodeMesh& nm, const detail::EdgeTable& et, detail::ProblemLog& log) {
  const OMesh& om = m.omesh();
  std::vector<int32_t> om_edges(et.size(), 0);
  for (auto eh : om.edges()) {
    auto h = om.halfedge_handle(eh, 0);
    const int32_t a = m.node(om.from_vertex_handle(h)), b = m.node(om.to_vertex_handle(h));
    const int64_t e = et.find(a, b);
    if (e < 0) {
      log.add({a, b}, [&] {
        return cat("edge: OpenMesh edge ", eh.idx(), " joins nodes ", a, ", ", b, " that no triangle joins");
      });
      continue;
    }
    ++om_edges[size_t(e)];
    const bool interior = detail::is_patch_interior(et, size_t(e), nm.triangles, nm.pairs);
    if (om.is_boundary(eh) == interior)
      log.add({a, b}, [&] {
        return cat(
            "edge: OpenMesh edge ", eh.idx(), " on node-edge (", a, ", ", b, ") with ", et.halfedges(size_t(e)).size(),
            interior ? " triangles of one patch is boundary" : " triangles (junction or domain) is not boundary");
      });
  }
  for (size_t e = 0; e < et.size(); ++e) {
    const size_t k = et.halfedges(e).size();
    const size_t expect = detail::is_patch_interior(et, e, nm.triangles, nm.pairs) ? 1 : k;
    if (size_t(om_edges[e]) != expect)
      log.add({et.nodes[e][0], et.nodes[e][1]}, [&] {
        return cat("edge: node-edge (", et.nodes[e][0], ", ", et.nodes[e][1], ") with ", k, " triangles has ",
                   om_edges[e], " OpenMesh edges, expected ", expect);
      });
  }
}

} // namespace

ValidationReport validate(const InterfaceMesh& m) {
  const NodeMesh nm = m.to_node_mesh();
  ValidationReport report = validate(nm);
  detail::ProblemLog log(report);
  check_copies(m, log);
  // A built mesh has node ids in range and distinct (from_node_mesh checks),
  // so the tables can take every triangle.
  const detail::NodeTriangles nt = detail::node_triangles(nm.points.size(), nm.triangles);
  check_phase_sets(m, detail::node_phases(nt, nm.pairs), log);
  check_edges(m, nm, detail::edge_table(nm.triangles, nt), log);
  return report;
}

} // namespace vm
