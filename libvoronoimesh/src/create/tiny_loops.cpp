#include "create/tiny_loops.hpp"

#include "mesh/junction_tables.hpp"

#include <algorithm>

namespace vm::detail {

namespace {

/// The closed triple curves of tiny_loop_vertices().
std::vector<TripleCurve> tiny_loops(const std::vector<Vec3>& points, const Triangles& triangles,
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
  Junctions junctions = junctions_from(near_pairs, edge_table(near, nt), node_phases(nt, near_pairs));
  std::erase_if(junctions.curves, [&](const TripleCurve& curve) {
    if (!curve.closed()) return true;
    Vec3 lo = points[size_t(curve.nodes[0])], hi = lo;
    for (const int32_t v : curve.nodes) lo = lo.cwiseMin(points[size_t(v)]), hi = hi.cwiseMax(points[size_t(v)]);
    return (hi - lo).maxCoeff() > extent;
  });
  return std::move(junctions.curves);
}

/// The phase of a tiny loop of three phases that is not on its window: the one
/// surface whose triangles at the loop all lie within the loop's box grown by
/// its size (`window_of`'s bits per pair: 1 a triangle beyond, 2 one within);
/// LoopClosing::kTieAll if not one.
int32_t phase_off_the_window(const TripleCurve& loop, const std::array<uint8_t, 3>& window_of) {
  int32_t off = LoopClosing::kTieAll;
  for (size_t k = 0; k < 3; ++k) {
    if (window_of[k] != 2) continue;
    if (off >= 0) return LoopClosing::kTieAll;
    off = loop.phases[2 - k]; // pair k of (0,1), (0,2), (1,2) leaves out phase 2, 1, 0
  }
  return off;
}

} // namespace

std::vector<int32_t> tiny_loop_vertices(const std::vector<Vec3>& points, const Triangles& triangles,
                                        const std::vector<PhasePair>& pairs, double extent) {
  std::vector<int32_t> vertices;
  for (const TripleCurve& loop : tiny_loops(points, triangles, pairs, extent))
    vertices.insert(vertices.end(), loop.nodes.begin(), loop.nodes.end() - 1);
  std::sort(vertices.begin(), vertices.end());
  return vertices;
}

std::vector<LoopClosing> tiny_loop_closings(const SlabsMesh& mesh, double extent) {
  const std::vector<TripleCurve> loops = tiny_loops(mesh.points, mesh.triangles, mesh.pairs, extent);
  if (loops.empty()) return {};
  std::vector<int32_t> loop_of(mesh.points.size(), -1);
  std::vector<Vec3> lo(loops.size()), hi(loops.size());
  for (size_t l = 0; l < loops.size(); ++l) {
    lo[l] = hi[l] = mesh.points[size_t(loops[l].nodes[0])];
    for (const int32_t v : loops[l].nodes) {
      loop_of[size_t(v)] = int32_t(l);
      lo[l] = lo[l].cwiseMin(mesh.points[size_t(v)]);
      hi[l] = hi[l].cwiseMax(mesh.points[size_t(v)]);
    }
    // Grown by the loop's size, so that the window's vertex on the lattice
    // edge (inside the loop, but not always within its box) counts as within.
    const Vec3 grow = Vec3::Constant((hi[l] - lo[l]).maxCoeff());
    lo[l] -= grow, hi[l] += grow;
  }
  // Per loop and pair of its phases: bit 1 a triangle at the loop beyond its
  // box, bit 2 one within.
  std::vector<std::array<uint8_t, 3>> window_of(loops.size(), {0, 0, 0});
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (const int32_t v : tri) {
      const int32_t l = loop_of[size_t(v)];
      if (l < 0) continue;
      const std::vector<int32_t>& p = loops[size_t(l)].phases;
      if (p.size() != 3) continue;
      const PhasePair pair = mesh.pairs[t];
      const size_t k = pair == PhasePair{p[0], p[1]} ? 0 : pair == PhasePair{p[0], p[2]} ? 1 : 2;
      if (k == 2 && pair != PhasePair{p[1], p[2]}) continue; // not the loop's (no vertex of it has another)
      const bool within = std::all_of(tri.begin(), tri.end(), [&](int32_t w) {
        const Vec3& x = mesh.points[size_t(w)];
        return (x.array() >= lo[size_t(l)].array()).all() && (x.array() <= hi[size_t(l)].array()).all();
      });
      window_of[size_t(l)][k] |= within ? 2 : 1;
    }
  }
  std::vector<LoopClosing> closings;
  for (size_t l = 0; l < loops.size(); ++l) {
    const int32_t phase =
        loops[l].phases.size() == 3 ? phase_off_the_window(loops[l], window_of[l]) : LoopClosing::kTieAll;
    for (const int32_t v : loops[l].nodes) {
      const LimitKey& key = mesh.keys[size_t(v)];
      for (int i = 0; i < key.count; ++i) closings.push_back({key.nodes[size_t(i)], phase});
    }
  }
  std::sort(closings.begin(), closings.end());
  closings.erase(std::unique(closings.begin(), closings.end()), closings.end());
  return closings;
}

} // namespace vm::detail
