#pragma once
/// @file core/key_set.hpp
/// Open addressing of 64-bit keys (grid cells packed or hashed into one
/// word): the probe the crossing index's cell hash and KeySet share, and
/// KeySet, a set asked only whether it holds a key. A lookup is one or two
/// cache lines where a binary search of a sorted list is twenty (the search
/// for triangles near flagged ones asks it once per cell of every triangle).

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

/// A free slot of an open-addressed key table (check/crossing_index.cpp's
/// cell hash, KeySet); a table holds no such key (KeySet keeps it aside).
inline constexpr uint64_t kFreeSlot = ~uint64_t(0);

/// The slot of key k in `slots` (open addressing, linear probing; a power of
/// two of them, kFreeSlot where free, some free): where k is, else the free
/// slot where it goes.
inline size_t slot_of(std::span<const uint64_t> slots, uint64_t k) {
  const size_t mask = slots.size() - 1;
  size_t s = mix64(k) & mask;
  while (slots[s] != k && slots[s] != kFreeSlot) s = (s + 1) & mask;
  return s;
}

/// The distinct keys of a list, for lookups only (built once, then read from
/// any number of threads).
class KeySet {
public:
  /// @param keys the keys, in any order, repeats allowed
  explicit KeySet(std::span<const uint64_t> keys) {
    size_t capacity = 64;
    while (capacity < 2 * keys.size()) capacity *= 2;
    slots_.assign(capacity, kFreeSlot);
    for (uint64_t k : keys) {
      if (k == kFreeSlot) holds_free_slot_key_ = true;
      else slots_[slot_of(slots_, k)] = k;
    }
  }
  /// True when `k` was among the keys.
  bool contains(uint64_t k) const { return k == kFreeSlot ? holds_free_slot_key_ : slots_[slot_of(slots_, k)] == k; }

private:
  std::vector<uint64_t> slots_;
  bool holds_free_slot_key_ = false; ///< that key has no slot: it marks free ones
};

} // namespace vm::detail
