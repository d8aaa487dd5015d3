#pragma once
/// @file core/parallel.hpp
/// The library's parallel calls: every tbb::parallel_* call goes through
/// these, so that ThreadSanitizer builds can tell TSan what TBB guarantees
/// (core/tbb_sanitizer.hpp). In other builds each is the TBB call itself.

#include "core/tbb_sanitizer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <cstddef>

namespace vm::detail {

#ifdef VM_TSAN_TBB
using ParallelCall = tsan::ParallelCall;
#else
/// Outside TSan builds a call hands TBB the functions themselves.
struct ParallelCall {
  template <class F> const F& task(const F& f) const { return f; }
};
#endif

/// tbb::parallel_for(range, body).
template <class Range, class Body> void parallel_for(const Range& range, const Body& body) {
  const ParallelCall call;
  tbb::parallel_for(range, call.task(body));
}

/// tbb::parallel_for(first, last, f): f(i) for each i in [first, last).
template <class Index, class F> void parallel_for(Index first, Index last, const F& f) {
  const ParallelCall call;
  tbb::parallel_for(first, last, call.task(f));
}

/// tbb::parallel_reduce(range, identity, body, join), the functional form.
template <class Range, class Value, class Body, class Join>
Value parallel_reduce(const Range& range, const Value& identity, const Body& body, const Join& join) {
  const ParallelCall call;
  return tbb::parallel_reduce(range, identity, call.task(body), call.task(join));
}

/// tbb::parallel_sort(first, last, less). The sort is all TBB's code, run
/// unrecorded in TSan builds: `less` may only read the two items it compares.
template <class It, class Less> void parallel_sort(It first, It last, const Less& less) {
  [[maybe_unused]] const ParallelCall call;
  tbb::parallel_sort(first, last, less);
}

/// tbb::parallel_invoke(fs...).
template <class... Fs> void parallel_invoke(const Fs&... fs) {
  const ParallelCall call;
  tbb::parallel_invoke(call.task(fs)...);
}

/// Parallel loop over independent indices. Blocked ranges keep TBB's per-task
/// cost off per-element work; each index is handled on its own, so results do
/// not depend on how the range is split. Fewer than two grains of indices run
/// as one task: loops over chunks, blocks or slices pass a grain of 1.
template <class F> void parallel_for_each_index(size_t n, F&& f, size_t grain = 512) {
  detail::parallel_for(tbb::blocked_range<size_t>(0, n, grain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

} // namespace vm::detail
