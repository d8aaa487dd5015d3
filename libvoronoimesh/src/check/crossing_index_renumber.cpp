/// @file check/crossing_index_renumber.cpp
/// CrossingIndex::renumber(): carrying the index over to a mesh rebuilt from
/// the one it knows (collapses, remeshing), without filing it anew: only the
/// slot maps and the filings' node and fan ids change.

#include "check/crossing_index.hpp"

#include "core/parallel.hpp"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <atomic>

namespace vm::detail {

void CrossingIndex::renumber(std::span<const int32_t> old_triangle, std::span<const int32_t> old_node,
                             std::span<const Triangle> corner_fans) {
  last_triangles_.clear(); // without an index, the mesh must settle again
  settled_calls_ = 0;
  if (filed_.empty()) return;
  // The number of old node and fan ids, in one parallel pass over the filings
  // (grain maps renumber after the junction-sliver collapses of every iteration).
  using Counts = std::array<int32_t, 2>;
  const auto [filed_nodes, old_fans] = detail::parallel_reduce(
      tbb::blocked_range<size_t>(0, filed_.size(), 4096), Counts{0, 0},
      [&](const tbb::blocked_range<size_t>& r, Counts c) {
        for (size_t slot = r.begin(); slot < r.end(); ++slot) {
          const Filing& f = filed_[slot];
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
  // that went two ways maps to none (its triangles are filed again). In
  // parallel (serial, it was half of a renumbering on 1,000 grains): each
  // corner's vote is compared and set at once, and the outcome, one fan or
  // none, does not depend on the order of the votes.
  constexpr int32_t kUnseen = -2;
  std::vector<int32_t> new_fan(size_t(old_fans), kUnseen);
  if (!corner_fans.empty())
    detail::parallel_for_each_index(old_triangle.size(), [&](size_t t) {
      if (old_triangle[t] < 0) return;
      const Filing& f = filed_[size_t(slot_of_[size_t(old_triangle[t])])];
      for (size_t k = 0; k < 3; ++k) {
        if (f.fans[k] < 0) continue;
        std::atomic_ref<int32_t> to(new_fan[size_t(f.fans[k])]);
        const int32_t vote = corner_fans[t][k];
        for (int32_t seen = to.load(std::memory_order_relaxed); seen != vote && seen != -1;)
          if (to.compare_exchange_weak(seen, seen == kUnseen ? vote : -1, std::memory_order_relaxed)) break;
      }
    });
  auto fan_of = [&](int32_t old) { return old < 0 || new_fan[size_t(old)] < 0 ? -1 : new_fan[size_t(old)]; };

  // Triangles gone free their slots; kept ones keep theirs, so the cells and
  // lists stay as they are; new ones take free slots, lowest first, then new
  // ones (not filed: they are filed at the next call).
  std::vector<uint8_t> kept(slot_of_.size(), 0);
  for (int32_t old : old_triangle)
    if (old >= 0) kept[size_t(old)] = 1;
  for (size_t old = 0; old < slot_of_.size(); ++old)
    if (!kept[old]) free_slot(slot_of_[old]);
  std::vector<int32_t> slot_of(old_triangle.size());
  size_t next_free = 0;
  for (size_t t = 0; t < old_triangle.size(); ++t) {
    if (old_triangle[t] >= 0) {
      slot_of[t] = slot_of_[size_t(old_triangle[t])];
      continue;
    }
    while (next_free < triangle_of_.size() && triangle_of_[next_free] >= 0) ++next_free;
    if (next_free == triangle_of_.size())
      filed_.push_back(Filing::none()), triangle_of_.push_back(-1), near_.add_list();
    slot_of[t] = int32_t(next_free++);
  }
  slot_of_ = std::move(slot_of);
  std::fill(triangle_of_.begin(), triangle_of_.end(), -1);
  for (size_t t = 0; t < slot_of_.size(); ++t) triangle_of_[size_t(slot_of_[t])] = int32_t(t);
  detail::parallel_for(tbb::blocked_range<size_t>(0, filed_.size(), 4096), [&](const auto& r) {
    for (size_t slot = r.begin(); slot < r.end(); ++slot) {
      for (int32_t& n : filed_[slot].nodes) n = n < 0 ? -1 : new_node[size_t(n)];
      for (int32_t& f : filed_[slot].fans) f = fan_of(f);
    }
  });
  fans_stale_ = true;
}

void CrossingIndex::renumber_after_removal(std::span<const int32_t> removed,
                                           std::span<const std::pair<int32_t, int32_t>> moved) {
  last_triangles_.clear(); // as renumber()
  settled_calls_ = 0;
  if (filed_.empty()) return;
  for (const int32_t t : removed) free_slot(slot_of_[size_t(t)]);
  // Slots read before any is written: a triangle may move into the index
  // another one moves out of.
  std::vector<int32_t> slots;
  for (const auto& [was, now] : moved) slots.push_back(slot_of_[size_t(was)]);
  for (size_t i = 0; i < moved.size(); ++i) {
    slot_of_[size_t(moved[i].second)] = slots[i];
    triangle_of_[size_t(slots[i])] = moved[i].second;
  }
  slot_of_.resize(slot_of_.size() - removed.size());
  fans_stale_ = true; // the fans hold triangle ids
}

} // namespace vm::detail
