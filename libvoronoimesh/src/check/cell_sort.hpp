#pragma once
/// @file check/cell_sort.hpp
/// Grid entries sorted by cell, by counting them where a grid has no more
/// cells than a few per entry: half the time of a parallel comparison sort on
/// 2 threads (1M triangles' boxes), and linear.

#include "core/parallel.hpp"

#include <cstdint>
#include <vector>

namespace vm::detail {

/// Sorts grid entries (each with a `key` of its cell and the `tri` it files,
/// in triangle order) by key, then by triangle. `cell(e)` numbers the `cells`
/// keys densely in their order: where they are no more than a few per entry,
/// the entries are counted into their cells (stable, so by triangle within
/// one); else sorted by comparison.
template <class Entry, class Cell> void sort_by_cell_key(std::vector<Entry>& entries, uint64_t cells, Cell cell) {
  if (cells > 4 * uint64_t(entries.size()) + 1024) {
    parallel_sort(entries.begin(), entries.end(),
                  [](const Entry& a, const Entry& b) { return a.key != b.key ? a.key < b.key : a.tri < b.tri; });
    return;
  }
  std::vector<uint32_t> start(cells + 1, 0);
  for (const Entry& e : entries) ++start[cell(e) + 1];
  for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<Entry> sorted(entries.size());
  for (const Entry& e : entries) sorted[start[cell(e)]++] = e;
  entries.swap(sorted);
}

} // namespace vm::detail
