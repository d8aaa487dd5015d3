/// @file check/crossing_index_rebuild.cpp
/// CrossingIndex::rebuild(): filing every triangle anew, when the mesh has
/// settled enough to keep an index (once a run, or after a large change).

#include "check/crossing_index.hpp"

#include "check/cell_sort.hpp"
#include "core/huge_pages.hpp"
#include "core/parallel.hpp"
#include "core/unset_vector.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <numeric>

namespace vm::detail {

// A rebuild fills 0.5-0.6 GB of fresh memory on 1,000 grains (filings, cell
// entries and their sort, the pairs, the lists' pools): its large arrays ask
// for huge pages (core/huge_pages.hpp). On 4 KiB pages its 220k page faults
// were about half of its 4.2 s.
void CrossingIndex::rebuild(std::span<const Triangle> triangles, std::span<const Triangle> corner_fans) {
  const size_t n = triangles.size();
  rebuilt_ = true;
  fans_stale_ = false;
  set_grid();
  const size_t levels = inverse_cell_size_.size();
  fans_.build(triangles, corner_fans);
  slot_of_.resize(n);
  std::iota(slot_of_.begin(), slot_of_.end(), 0);
  triangle_of_ = slot_of_;

  // The cells, from every triangle's (key, id) entries sorted.
  filed_.clear(); // each written below, by the thread of its triangle
  resize_on_huge_pages(filed_, n);
  std::vector<uint32_t> offset(n + 1, 0);
  detail::parallel_for_each_index(n, [&](size_t t) {
    filed_[t] = filing_for(boxes_[t], triangles[t], corner_fans.empty() ? Triangle{-1, -1, -1} : corner_fans[t]);
    uint32_t cells = 0;
    for_cells(filed_[t], [&](uint64_t) { ++cells; });
    offset[t + 1] = cells;
  });
  for (size_t t = 0; t < n; ++t) offset[t + 1] += offset[t];
  level_count_.assign(levels, 0);
  Bounds reach{Vec3::Constant(std::numeric_limits<double>::infinity()),
               Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (const Filing& f : filed_) {
    ++level_count_[size_t(f.level)];
    const Bounds box = f.box.bounds();
    reach = {reach.lo.cwiseMin(box.lo), reach.hi.cwiseMax(box.hi)};
  }
  struct Entry {
    uint64_t key;
    int32_t tri;
  };
  detail::UnsetVector<Entry> entries; // each written below, by the thread of its triangle
  resize_on_huge_pages(entries, offset[n]);
  detail::parallel_for_each_index(n, [&](size_t t) {
    uint32_t e = offset[t];
    for_cells(filed_[t], [&](uint64_t k) { entries[e++] = {k, int32_t(t)}; });
  });
  // In key order (level, then i, j, k), the cells the filing boxes reach in
  // each level numbered densely (check/cell_sort.hpp).
  std::vector<uint64_t> level_start(levels + 1, 0);
  std::vector<std::array<int64_t, 3>> lowest(levels), across(levels);
  for (size_t l = 0; l < levels; ++l) {
    uint64_t cells = 0;
    if (level_count_[l]) {
      lowest[l] = cell_of(reach.lo, int(l));
      const auto highest = cell_of(reach.hi, int(l));
      for (size_t a = 0; a < 3; ++a) across[l][a] = highest[a] - lowest[l][a] + 1;
      cells = uint64_t(across[l][0]) * uint64_t(across[l][1]) * uint64_t(across[l][2]);
    }
    level_start[l + 1] = level_start[l] + cells;
  }
  sort_by_cell_key(entries, level_start.back(), [&](const Entry& e) {
    const size_t l = key_level(e.key); // not the filing's: a cache miss per call, and the sort calls it four times
    const auto c = key_cell(e.key);
    return level_start[l] + uint64_t(((c[0] - lowest[l][0]) * across[l][1] + c[1] - lowest[l][1]) * across[l][2] +
                                      c[2] - lowest[l][2]);
  });
  std::vector<size_t> first;
  for (size_t e = 0; e < entries.size(); ++e)
    if (e == 0 || entries[e].key != entries[e - 1].key) first.push_back(e);
  first.push_back(entries.size());
  keys_.clear();
  cell_of_key_.clear();
  cells_ = {};
  grow_table(first.size() - 1); // sized once, not grown by doubling as cells are added
  for (size_t c = 0; c + 1 < first.size(); ++c) find_or_add(entries[first[c]].key); // cells numbered in key order
  std::vector<uint32_t> sizes(first.size() - 1);
  for (size_t c = 0; c < sizes.size(); ++c) sizes[c] = uint32_t(first[c + 1] - first[c]);
  cells_.assign(sizes, advise_huge_pages_of_items<CellEntry>);
  detail::parallel_for_each_index(sizes.size(), [&](size_t c) {
    const auto filed = cells_.at(c);
    for (size_t i = 0; i < filed.size(); ++i) {
      const int32_t t = entries[first[c] + i].tri;
      filed[i] = cell_entry(t, filed_[size_t(t)]);
    }
  });

  // The lists: every pair of overlapping filing boxes that shares no fan, as
  // near() would find each, but found all at once as a one-off check finds
  // its candidates (a search through the cells per triangle took 1.0 of 1.7 s
  // on 1M triangles), kept by the thread that found it unless in a fan (most
  // pairs are, and are never stored), then dealt to both triangles' lists (in
  // whatever order the threads deal them) and sorted. The fans are read from
  // a compact copy: from the filings they were a cache miss each.
  UnsetVector<Triangle> fans; // each written below
  resize_on_huge_pages(fans, n);
  detail::parallel_for_each_index(n, [&](size_t t) { fans[t] = filed_[t].fans; });
  tbb::enumerable_thread_specific<std::vector<BoxPair>> pairs;
  {
    UnsetVector<Bounds> filing; // each written below
    resize_on_huge_pages(filing, n);
    detail::parallel_for_each_index(n, [&](size_t t) { filing[t] = filed_[t].box.bounds(); });
    for_each_overlapping_box_pair(filing, {}, [&](std::span<const BoxPair> some) {
      std::vector<BoxPair>& kept = pairs.local();
      for (const BoxPair& pair : some)
        if (!share_a_fan(fans[size_t(pair[0])], fans[size_t(pair[1])])) push_back_on_huge_pages(kept, pair);
    });
  }
  auto for_each_pair = [&](auto&& f) {
    for (const auto& part : pairs) detail::parallel_for_each_index(part.size(), [&](size_t i) { f(part[i]); });
  };
  std::vector<std::atomic<uint32_t>> dealt(n);
  detail::parallel_for_each_index(n, [&](size_t t) { dealt[t].store(0, std::memory_order_relaxed); });
  for_each_pair([&](const BoxPair& pair) {
    for (int32_t t : pair) dealt[size_t(t)].fetch_add(1, std::memory_order_relaxed);
  });
  std::vector<uint32_t> count(n);
  detail::parallel_for_each_index(n, [&](size_t t) {
    count[t] = dealt[t].load(std::memory_order_relaxed);
    dealt[t].store(0, std::memory_order_relaxed);
  });
  near_ = {};
  near_.assign(count, advise_huge_pages_of_items<int32_t>);
  for_each_pair([&](const BoxPair& pair) {
    const auto [t, s] = pair;
    near_.at(size_t(t))[dealt[size_t(t)].fetch_add(1, std::memory_order_relaxed)] = s;
    near_.at(size_t(s))[dealt[size_t(s)].fetch_add(1, std::memory_order_relaxed)] = t;
  });
  detail::parallel_for_each_index(n, [&](size_t t) {
    const auto list = near_.at(t);
    std::sort(list.begin(), list.end());
  });
}

} // namespace vm::detail
