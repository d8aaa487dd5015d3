#include "create/tiny_loops.hpp"

#include "mesh/junction_tables.hpp"

#include <algorithm>

namespace vm::detail {

std::vector<int32_t> tiny_loop_vertices(const std::vector<Vec3>& points, const Triangles& triangles,
                                        const std::vector<PhasePair>& pairs, double extent) {
  // Only the triangles with an edge between junction nodes (two pairs or more
  // around them) hold curve edges: the curves of those alone are the mesh's,
  // for a fifth of the tables' time on the liver.
  std::vector<PhasePair> first_pair(points.size(), PhasePair{-1, -1});
  std::vector<char> junction(points.size(), 0);
  for (size_t t = 0; t < triangles.size(); ++t)
    for (const int32_t v : triangles[t]) {
      PhasePair& seen = first_pair[size_t(v)];
      if (seen[0] < 0) seen = pairs[t];
      else if (seen != pairs[t]) junction[size_t(v)] = 1;
    }
  Triangles near;
  std::vector<PhasePair> near_pairs;
  for (size_t t = 0; t < triangles.size(); ++t)
    if (junction[size_t(triangles[t][0])] + junction[size_t(triangles[t][1])] + junction[size_t(triangles[t][2])] >= 2)
      near.push_back(triangles[t]), near_pairs.push_back(pairs[t]);
  const NodeTriangles nt = node_triangles(points.size(), near);
  const Junctions junctions = junctions_from(near_pairs, edge_table(near, nt), node_phases(nt, near_pairs));
  std::vector<int32_t> loops;
  for (const TripleCurve& curve : junctions.curves) {
    if (!curve.closed()) continue;
    Vec3 lo = points[size_t(curve.nodes[0])], hi = lo;
    for (const int32_t v : curve.nodes) lo = lo.cwiseMin(points[size_t(v)]), hi = hi.cwiseMax(points[size_t(v)]);
    if ((hi - lo).maxCoeff() <= extent) loops.insert(loops.end(), curve.nodes.begin(), curve.nodes.end() - 1);
  }
  std::sort(loops.begin(), loops.end());
  return loops;
}

std::vector<int64_t> tiny_loop_nodes(const SlabsMesh& mesh, double extent) {
  std::vector<int64_t> nodes;
  for (const int32_t v : tiny_loop_vertices(mesh.points, mesh.triangles, mesh.pairs, extent)) {
    const LimitKey& key = mesh.keys[size_t(v)];
    nodes.insert(nodes.end(), key.nodes.begin(), key.nodes.begin() + key.count);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

} // namespace vm::detail
