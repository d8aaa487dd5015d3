#include "create/tiny_loops.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>

namespace vm::detail {

namespace {

/// Union-find root of v, halving the path on the way.
int32_t root(std::vector<int32_t>& parent, int32_t v) {
  while (parent[size_t(v)] != v) v = parent[size_t(v)] = parent[size_t(parent[size_t(v)])];
  return v;
}

} // namespace

std::vector<int32_t> tiny_loop_vertices(std::span<const Vec3> points, std::span<const std::array<int32_t, 3>> triangles,
                                        std::span<const PhasePair> pairs, double extent) {
  const size_t n = points.size();
  // A vertex whose triangles hold two or more phase pairs lies on a junction.
  constexpr uint64_t kNone = UINT64_MAX;
  std::vector<uint64_t> first_pair(n, kNone);
  std::vector<uint8_t> junction(n, 0);
  for (size_t t = 0; t < triangles.size(); ++t) {
    const uint64_t pair = uint64_t(uint32_t(pairs[t][0])) << 32 | uint32_t(pairs[t][1]);
    for (const int32_t v : triangles[t]) {
      uint64_t& seen = first_pair[size_t(v)];
      if (seen == kNone) seen = pair;
      else if (seen != pair) junction[size_t(v)] = 1;
    }
  }
  // Edges between junction vertices, once per triangle: three or more
  // triangles make a curve edge (a surface's own edge has two at most).
  std::vector<std::array<int32_t, 2>> sides;
  for (const auto& t : triangles)
    for (int c = 0; c < 3; ++c) {
      const int32_t a = t[size_t(c)], b = t[size_t((c + 1) % 3)];
      if (junction[size_t(a)] && junction[size_t(b)]) sides.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(sides.begin(), sides.end());
  std::vector<int32_t> parent(n), degree(n, 0);
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t i = 0; i < sides.size();) {
    size_t j = i;
    while (j < sides.size() && sides[j] == sides[i]) ++j;
    if (j - i >= 3) {
      const auto [a, b] = sides[i];
      ++degree[size_t(a)], ++degree[size_t(b)];
      parent[size_t(root(parent, a))] = root(parent, b);
    }
    i = j;
  }
  // Per curve component: closed with no branch (every vertex of degree 2), and its box.
  struct Component {
    bool loop = true;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  };
  std::vector<Component> of_root(n);
  for (size_t v = 0; v < n; ++v) {
    if (degree[v] == 0) continue;
    Component& c = of_root[size_t(root(parent, int32_t(v)))];
    c.loop = c.loop && degree[v] == 2;
    c.lo = c.lo.cwiseMin(points[v]), c.hi = c.hi.cwiseMax(points[v]);
  }
  std::vector<int32_t> loops;
  for (size_t v = 0; v < n; ++v) {
    if (degree[v] == 0) continue;
    const Component& c = of_root[size_t(root(parent, int32_t(v)))];
    if (c.loop && (c.hi - c.lo).maxCoeff() <= extent) loops.push_back(int32_t(v));
  }
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
