#pragma once
/// @file core/indices_where.hpp
/// The indices that pass a test, tested in parallel and listed in increasing
/// order: the list a serial scan makes, for any thread count. For scans of a
/// whole mesh that pick out a few of its triangles or nodes, which serial took
/// 10-20 ms each on 1M triangles, on one core while the other waited.

#include "core/parallel.hpp"
#include "core/unset_vector.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vm::detail {

/// The i in [0, n) for which keep(i) is true, increasing, into `out` (its
/// memory reused: a caller that asks again and again keeps one list, instead of
/// fresh memory each time). keep is called once for each index, from any
/// thread, and may only read shared data.
template <class Index, class Keep> void indices_where(size_t n, const Keep& keep, std::vector<Index>& out) {
  // Each block counts its own, then writes from its place in the list.
  constexpr size_t kBlock = size_t(1) << 14;
  const size_t blocks = (n + kBlock - 1) / kBlock;
  // Each flag is written below by the task of its block (zeroed first, in this
  // thread, they were a serial pass over fresh memory in every whole-mesh check).
  UnsetVector<uint8_t> kept(n);
  std::vector<size_t> start(blocks + 1, 0);
  parallel_for_each_index(
      blocks,
      [&](size_t b) {
        size_t count = 0;
        for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) count += kept[i] = keep(i) ? 1 : 0;
        start[b + 1] = count;
      },
      1);
  for (size_t b = 0; b < blocks; ++b) start[b + 1] += start[b];
  out.resize(start[blocks]);
  parallel_for_each_index(
      blocks,
      [&](size_t b) {
        size_t at = start[b];
        for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i)
          if (kept[i]) out[at++] = Index(i);
      },
      1);
}

/// The i in [0, n) for which keep(i) is true, increasing, as a new list.
template <class Index = int32_t, class Keep> std::vector<Index> indices_where(size_t n, const Keep& keep) {
  std::vector<Index> out;
  indices_where(n, keep, out);
  return out;
}

} // namespace vm::detail
