#pragma once
/// @file core/unset_vector.hpp
/// A std::vector whose new items are left unset, for a parallel loop to write.
///
/// std::vector<T>(n) of a plain struct zeroes its n items in the calling
/// thread before any loop runs; on large arrays the kernel zeroes each fresh
/// page on first touch as well, and both happen in that one thread. On 1M
/// triangles the grid entries of one crossing search (about 50 MB) took
/// 0.3 s so, with the other core idle. Left unset, the pages are first touched
/// by the threads that fill them.

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace vm::detail {

/// std::allocator, but an item made without arguments is default-initialized
/// (left unset for trivial types) rather than value-initialized (zeroed).
template <class T> struct DefaultInitAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <class U> struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  template <class U> void construct(U* at) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(at)) U;
  }
  template <class U, class... Args> void construct(U* at, Args&&... args) {
    ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
  }
};

/// A vector whose resize() and size constructor leave trivial items unset:
/// every item must be written before it is read.
template <class T> using UnsetVector = std::vector<T, DefaultInitAllocator<T>>;

/// Sizes `v` to n items that are all about to be written: where it must grow
/// its memory, nothing it held is moved over first (a serial copy into fresh
/// pages), and no item is set.
template <class T> void resize_to_overwrite(UnsetVector<T>& v, size_t n) {
  if (n > v.capacity()) v.clear();
  v.resize(n);
}

} // namespace vm::detail
