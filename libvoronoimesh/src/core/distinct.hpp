#pragma once
/// @file core/distinct.hpp
/// The distinct values of a large array of labels (a volume's voxels).

#include <algorithm>
#include <cstdint>
#include <span>
#include <unordered_set>
#include <vector>

namespace vm::detail {

/// The distinct values of `labels`, sorted. Runs of equal labels cost one
/// lookup, and only the distinct values are sorted, not the array.
inline std::vector<int32_t> distinct(std::span<const int32_t> labels) {
  std::unordered_set<int32_t> seen;
  int32_t last = 0;
  bool any = false;
  for (int32_t l : labels)
    if (!any || l != last) seen.insert(l), last = l, any = true;
  std::vector<int32_t> out(seen.begin(), seen.end());
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace vm::detail
