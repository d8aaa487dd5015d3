#include "mesh/topology.hpp"

#include <algorithm>
#include <utility>

namespace vm::detail {

NodeTriangles node_triangles(size_t num_nodes, const Triangles& tris, const std::vector<char>* usable) {
  NodeTriangles nt;
  nt.off.assign(num_nodes + 1, 0);
  auto use = [&](size_t t) { return usable == nullptr || (*usable)[t] != 0; };
  for (size_t t = 0; t < tris.size(); ++t)
    if (use(t))
      for (int32_t n : tris[t]) ++nt.off[size_t(n) + 1];
  for (size_t n = 0; n < num_nodes; ++n) nt.off[n + 1] += nt.off[n];
  nt.tri.resize(size_t(nt.off[num_nodes]));
  std::vector<int32_t> fill(nt.off.begin(), nt.off.end() - 1);
  // Ascending t per node falls out of filling in triangle order.
  for (size_t t = 0; t < tris.size(); ++t)
    if (use(t))
      for (int32_t n : tris[t]) nt.tri[size_t(fill[size_t(n)]++)] = int32_t(t);
  return nt;
}

EdgeTable edge_table(const Triangles& tris, const NodeTriangles& nt) {
  const size_t num_nodes = nt.off.size() - 1;
  EdgeTable et;
  et.first.assign(num_nodes + 1, 0);
  et.off.push_back(0);
  et.he.reserve(nt.tri.size());
  et.nodes.reserve(nt.tri.size() / 2);
  EdgesAt local;
  for (size_t a = 0; a < num_nodes; ++a) {
    et.first[a] = int32_t(et.nodes.size());
    local.gather(int32_t(a), tris, nt);
    const auto base = int32_t(et.he.size());
    for (size_t i = 0; i < local.size(); ++i) {
      et.nodes.push_back({int32_t(a), local.other(i)});
      et.off.push_back(base + local.halfedges_end(i));
    }
    et.he.insert(et.he.end(), local.halfedges().begin(), local.halfedges().end());
  }
  et.first[num_nodes] = int32_t(et.nodes.size());
  return et;
}

void EdgesAt::gather(int32_t a, const Triangles& tris, const NodeTriangles& nt) {
  // (b, halfedge) packed in one integer that sorts the same, as it sorts faster.
  auto key = [](int32_t b, int32_t h) { return uint64_t(uint32_t(b)) << 32 | uint32_t(h); };
  local_.clear();
  // Each halfedge is gathered once, at its smaller endpoint.
  for (int32_t t : nt.of(size_t(a))) {
    const auto& tri = tris[size_t(t)];
    for (int k = 0; k < 3; ++k) {
      const int32_t from = tri[size_t(k)], to = tri[size_t((k + 1) % 3)];
      const int32_t other = from == a ? to : to == a ? from : -1;
      if (other > a) local_.push_back(key(other, 3 * t + k));
    }
  }
  std::sort(local_.begin(), local_.end());
  other_.clear();
  off_.clear();
  he_.clear();
  for (size_t i = 0; i < local_.size(); ++i) {
    const auto b = int32_t(local_[i] >> 32);
    if (i == 0 || b != other_.back()) {
      other_.push_back(b);
      off_.push_back(int32_t(i));
    }
    he_.push_back(int32_t(uint32_t(local_[i])));
  }
  off_.push_back(int32_t(he_.size()));
}

int64_t EdgeTable::find(int32_t a, int32_t b) const {
  if (a > b) std::swap(a, b);
  if (a < 0 || size_t(a) + 1 >= first.size()) return -1;
  auto lo = nodes.begin() + first[size_t(a)], hi = nodes.begin() + first[size_t(a) + 1];
  auto it = std::lower_bound(lo, hi, b, [](const std::array<int32_t, 2>& e, int32_t v) { return e[1] < v; });
  return it != hi && (*it)[1] == b ? int64_t(it - nodes.begin()) : -1;
}

NodePhases node_phases(const NodeTriangles& nt, const std::vector<PhasePair>& pairs) {
  const size_t num_nodes = nt.off.size() - 1;
  NodePhases np;
  np.off.reserve(num_nodes + 1);
  np.off.push_back(0);
  std::vector<int32_t> local;
  for (size_t n = 0; n < num_nodes; ++n) {
    local.clear();
    for (int32_t t : nt.of(n)) {
      local.push_back(pairs[size_t(t)][0]);
      local.push_back(pairs[size_t(t)][1]);
    }
    std::sort(local.begin(), local.end());
    local.erase(std::unique(local.begin(), local.end()), local.end());
    np.phase.insert(np.phase.end(), local.begin(), local.end());
    np.off.push_back(int32_t(np.phase.size()));
  }
  return np;
}

} // namespace vm::detail
