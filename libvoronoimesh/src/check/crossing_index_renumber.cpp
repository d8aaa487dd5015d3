/// @file check/crossing_index_renumber.cpp
/// CrossingIndex::renumber(): carrying the index over to a mesh rebuilt from
/// the one it knows (collapses, remeshing), without filing it anew.

#include "check/crossing_index.hpp"

#include "core/parallel.hpp"

#include <tbb/blocked_range.h>

#include <algorithm>

namespace vm::detail {

void CrossingIndex::renumber(std::span<const int32_t> old_triangle, std::span<const int32_t> old_node,
                             std::span<const Triangle> corner_fans) {
  last_triangles_.clear(); // without an index, the mesh must settle again
  settled_calls_ = 0;
  if (filed_.empty()) return;
  std::vector<int32_t> new_triangle(filed_.size(), -1);
  for (size_t t = 0; t < old_triangle.size(); ++t)
    if (old_triangle[t] >= 0) new_triangle[size_t(old_triangle[t])] = int32_t(t);
  // The number of old node and fan ids, in one parallel pass over the filings
  // (grain maps renumber after the junction-sliver collapses of every iteration).
  using Counts = std::array<int32_t, 2>;
  const auto [filed_nodes, old_fans] = detail::parallel_reduce(
      tbb::blocked_range<size_t>(0, filed_.size(), 4096), Counts{0, 0},
      [&](const tbb::blocked_range<size_t>& r, Counts c) {
        for (size_t t = r.begin(); t < r.end(); ++t) {
          const Filing& f = filed_[t];
          c = {std::max({c[0], f.nodes[0] + 1, f.nodes[1] + 1, f.nodes[2] + 1}),
               std::max({c[1], f.fans[0] + 1, f.fans[1] + 1, f.fans[2] + 1})};
        }
        return c;
      },
      [](const Counts& a, const Counts& b) { return Counts{std::max(a[0], b[0]), std::max(a[1], b[1])}; });
  int32_t old_nodes = filed_nodes;
  for (int32_t n : old_node) old_nodes = std::max(old_nodes, n + 1);
  std::vector<int32_t> new_node(size_t(old_nodes), -1);
  for (size_t n = 0; n < old_node.size(); ++n)
    if (old_node[n] >= 0) new_node[size_t(old_node[n])] = int32_t(n);
  // Old fan ids to new ones, through the corners of kept triangles; a fan
  // that went two ways maps to none (its triangles are filed again).
  constexpr int32_t kUnseen = -2;
  std::vector<int32_t> new_fan(size_t(old_fans), kUnseen);
  for (size_t t = 0; t < old_triangle.size() && !corner_fans.empty(); ++t)
    for (size_t k = 0; k < 3 && old_triangle[t] >= 0; ++k) {
      const int32_t old = filed_[size_t(old_triangle[t])].fans[k];
      if (old < 0) continue;
      int32_t& to = new_fan[size_t(old)];
      to = to == kUnseen || to == corner_fans[t][k] ? corner_fans[t][k] : -1;
    }
  auto fan_of = [&](int32_t old) { return old < 0 || new_fan[size_t(old)] < 0 ? -1 : new_fan[size_t(old)]; };

  std::vector<Filing> filed(old_triangle.size()); // new triangles: not filed
  detail::parallel_for(tbb::blocked_range<size_t>(0, filed.size(), 4096), [&](const auto& r) {
    for (size_t t = r.begin(); t < r.end(); ++t) {
      if (old_triangle[t] < 0) continue;
      filed[t] = filed_[size_t(old_triangle[t])];
      for (int32_t& n : filed[t].nodes) n = new_node[size_t(n)];
      for (int32_t& f : filed[t].fans) f = fan_of(f);
    }
  });
  filed_ = std::move(filed);
  level_count_.assign(level_count_.size(), 0);
  for (const Filing& f : filed_)
    if (f.level >= 0) ++level_count_[size_t(f.level)];
  // List by list in parallel: grain maps renumber after the junction-sliver
  // collapses of every iteration.
  detail::parallel_for(tbb::blocked_range<size_t>(0, cells_.count(), 1024), [&](const auto& lists) {
    cells_.map_items(
        [&](CellEntry e) {
          e.id = new_triangle[size_t(e.id)];
          return e;
        },
        lists.begin(), lists.end());
  });
  // Lists by new triangle: each old list where it is, mapped (ids keep their
  // order). Copying them all cost time and memory on grain maps, which collapse
  // junction slivers in every iteration (1,000 grains at 128^3, 20 iterations,
  // 2 threads: 83 s and 2.26 GB peak with the copy, 72 s and 2.0 GB without).
  near_.keep_lists(old_triangle);
  detail::parallel_for(tbb::blocked_range<size_t>(0, near_.count(), 1024), [&](const auto& lists) {
    near_.map_items([&](Neighbour s) { return Neighbour{new_triangle[size_t(s.id)], fan_of(s.fan)}; }, lists.begin(),
                    lists.end());
  });
  fans_stale_ = true;
}

} // namespace vm::detail
