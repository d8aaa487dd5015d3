#pragma once
/// @file core/key_set.hpp
/// A set of 64-bit keys (grid cells packed or hashed into one word) asked
/// only whether it holds a key: open addressing in one flat array, so a
/// lookup is one or two cache lines where a binary search of a sorted list
/// is twenty (the search for triangles near flagged ones asks it once per cell
/// of every triangle of the mesh).

#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// splitmix64's finaliser: every bit of x moves every bit of the result, so
/// the low bits of packed cell coordinates spread over a table.
inline uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// The distinct keys of a list, for lookups only (built once, then read from
/// any number of threads).
class KeySet {
public:
  /// @param keys the keys, in any order, repeats allowed
  explicit KeySet(std::span<const uint64_t> keys) {
    size_t capacity = 64;
    while (capacity < 2 * keys.size()) capacity *= 2;
    slots_.assign(capacity, kEmpty);
    mask_ = capacity - 1;
    for (uint64_t k : keys) {
      if (k == kEmpty) {
        holds_empty_ = true;
        continue;
      }
      size_t s = mix64(k) & mask_;
      while (slots_[s] != kEmpty && slots_[s] != k) s = (s + 1) & mask_;
      slots_[s] = k;
    }
  }
  /// True when `k` was among the keys.
  bool contains(uint64_t k) const {
    if (k == kEmpty) return holds_empty_;
    for (size_t s = mix64(k) & mask_;; s = (s + 1) & mask_) {
      if (slots_[s] == k) return true;
      if (slots_[s] == kEmpty) return false;
    }
  }

private:
  static constexpr uint64_t kEmpty = ~uint64_t(0); ///< a free slot; the key itself is kept aside
  std::vector<uint64_t> slots_;
  size_t mask_ = 0;
  bool holds_empty_ = false;
};

} // namespace vm::detail
