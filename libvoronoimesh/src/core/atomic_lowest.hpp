#pragma once
/// @file core/atomic_lowest.hpp
/// The lowest of values offered from many threads at once: the minimum does
/// not depend on the order they come in, so neither does the result.

namespace vm::detail {

/// Lowers `lowest` (a std::atomic or a std::atomic_ref) to `value` if that is
/// smaller than what it holds.
template <class Atomic, class T> void lower_atomically(Atomic&& lowest, T value) {
  for (auto seen = lowest.load(); value < seen && !lowest.compare_exchange_weak(seen, value);) {
  }
}

} // namespace vm::detail
