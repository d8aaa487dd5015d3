#pragma once
/// @file core/huge_pages.hpp
/// Large arrays on transparent huge pages. Every fresh 4 KiB page costs a page
/// fault at its first touch, and on the virtual machines we run on a fault is
/// dear: writing 97 MB of fresh memory took 0.27 s, against 0.02-0.2 s on huge
/// pages (2 MiB, one fault each; the slow end when the kernel must first
/// gather them). Debian's kernels hand out huge pages only where a program asks
/// for them (THP "madvise" mode), and glibc does not ask unless a tunable in
/// the environment tells it to; so the arrays of voxels and lattice nodes ask
/// for themselves, before they are first touched. The liver (bench/race.sh):
/// 109k page faults -> 29k, reading 0.8-1.0 -> 0.54-0.67 s, sampling and
/// creating 1.0-1.25 -> 0.75-0.92 s.

#include "core/parallel.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace vm::detail {

/// Asks the kernel to back the whole 2 MiB pages inside [data, data + bytes)
/// with huge pages when they are first touched. A hint: where it is refused
/// (no THP, a kernel that says never) the memory is as it would have been.
inline void advise_huge_pages(const void* data, size_t bytes) {
#ifdef MADV_HUGEPAGE
  constexpr uintptr_t kHugePage = uintptr_t(2) << 20;
  const auto begin = (uintptr_t(data) + kHugePage - 1) & ~(kHugePage - 1);
  const auto end = (uintptr_t(data) + bytes) & ~(kHugePage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

/// Makes room in `v` (a std::vector or std::basic_string) for n elements, the
/// room past its size on huge pages where the memory is fresh: reserve()
/// allocates without touching, so the advice comes first.
template <class Container> void reserve_on_huge_pages(Container& v, size_t n) {
  if (n > v.capacity()) {
    v.reserve(n);
    advise_huge_pages(v.data() + v.size(), (n - v.size()) * sizeof(*v.data()));
  }
}

/// Fresh memory past this many bytes is first touched by every thread
/// (touch_in_parallel()).
constexpr size_t kTouchInParallel = size_t(16) << 20;

/// Writes zeros over [data, data + bytes) from every thread, a 2 MiB block a
/// task: the kernel clears each fresh page in the thread that first touches it,
/// and a resize() that fills a large vector does that in one thread. On the
/// liver (its voxels, 100 MB, and its label field's arrays) "read and phase
/// functions" took 0.20-0.36 s, median 0.32, and now 0.19-0.27 s, median 0.21
/// (10 alternated runs; the CT-like volume's the same either way).
inline void touch_in_parallel(void* data, size_t bytes) {
  constexpr size_t kBlock = size_t(2) << 20;
  auto* begin = static_cast<unsigned char*>(data);
  parallel_for(size_t(0), (bytes + kBlock - 1) / kBlock, [&](size_t b) {
    std::memset(begin + b * kBlock, 0, std::min(kBlock, bytes - b * kBlock));
  });
}

/// Resizes `v` to n elements (`fill`s past its old size) with its new
/// elements on huge pages where the memory is fresh (reserve_on_huge_pages()),
/// first touched by every thread where they are many (touch_in_parallel(); for
/// elements that bytes may stand for before they are made).
template <class Container, class... Fill>
void resize_on_huge_pages(Container& v, size_t n, const Fill&... fill) {
  const bool fresh = n > v.capacity();
  reserve_on_huge_pages(v, n);
  using Item = std::remove_cvref_t<decltype(*v.data())>;
  if (fresh && std::is_trivially_copyable_v<Item> && (n - v.size()) * sizeof(Item) >= kTouchInParallel)
    touch_in_parallel(v.data() + v.size(), (n - v.size()) * sizeof(Item));
  v.resize(n, fill...);
}

/// advise_huge_pages() for `count` items of T from `data`.
template <class T> void advise_huge_pages_of_items(const T* data, size_t count) {
  advise_huge_pages(data, count * sizeof(T));
}

/// v.push_back(item), where v grows (doubling) into memory on huge pages.
template <class Container, class Item> void push_back_on_huge_pages(Container& v, const Item& item) {
  if (v.size() == v.capacity()) {
    const size_t room = std::max<size_t>(2 * v.capacity(), size_t(1) << 16);
    v.reserve(room);
    advise_huge_pages(v.data() + v.size(), (room - v.size()) * sizeof(*v.data()));
  }
  v.push_back(item);
}

/// Replaces the contents of `v` by n copies of `value`, on huge pages where the memory is fresh.
template <class Container, class Value>
void assign_on_huge_pages(Container& v, size_t n, const Value& value) {
  v.clear();
  resize_on_huge_pages(v, n, value);
}

} // namespace vm::detail
