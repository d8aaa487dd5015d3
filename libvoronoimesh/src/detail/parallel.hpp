#pragma once
/// @file detail/parallel.hpp
/// Parallel loops over independent indices. Blocked ranges keep TBB's per-task
/// cost off per-element work; each index is handled on its own, so results do
/// not depend on how the range is split.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>

namespace vm::detail {

template <class F> void parallel_for_each_index(size_t n, F&& f, size_t grain = 512) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

} // namespace vm::detail
