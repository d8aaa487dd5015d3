#pragma once
/// @file limit_key_index.hpp
/// Numbers distinct limit points in order of first appearance. create() looks up
/// every corner of every triangle it cuts (millions), so this is an open-
/// addressing table of 32-bit ids into the caller's vector of keys, with each
/// key's hash kept beside its id: no allocation per key (std::unordered_map's
/// node of a 112-byte key cost a third of the memory of create) and a key is
/// compared only when the hashes agree.

#include "create/limit_key.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace vm::detail {

class LimitKeyIndex {
public:
  /// Room for `n` keys without growing.
  void reserve(size_t n) {
    size_t capacity = 16;
    while (capacity < 2 * n) capacity *= 2;
    if (capacity > slots_.size()) rehash(capacity);
  }

  /// The id of `key` among `keys`, the keys inserted so far (keys[id] is the key
  /// of id). If absent, `key` gets id keys.size() and inserted is true: the
  /// caller then appends it to `keys`.
  std::pair<int32_t, bool> insert(const LimitKey& key, const std::vector<LimitKey>& keys) {
    if (2 * (size_ + 1) > slots_.size()) rehash(slots_.empty() ? 16 : 2 * slots_.size());
    const uint32_t h = spread(LimitKeyHash{}(key));
    Slot& slot = slots_[slot_of(h, key, keys)];
    if (slot.id >= 0) return {slot.id, false};
    slot = {h, int32_t(keys.size())};
    ++size_;
    return {slot.id, true};
  }

  /// Files `key` as id `id` without looking for it: for keys known to be
  /// distinct, numbered by the caller (a slab's own keys, by position).
  void add(const LimitKey& key, int32_t id) {
    if (2 * (size_ + 1) > slots_.size()) rehash(slots_.empty() ? 16 : 2 * slots_.size());
    const uint32_t h = spread(LimitKeyHash{}(key));
    slots_[free_slot(h)] = {h, id};
    ++size_;
  }

  /// The id of `key` among `keys` (as insert() or add() numbered them), or -1 if absent.
  int32_t find(const LimitKey& key, const std::vector<LimitKey>& keys) const {
    if (slots_.empty()) return -1;
    return slots_[slot_of(spread(LimitKeyHash{}(key)), key, keys)].id;
  }

private:
  struct Slot {
    uint32_t hash = 0;
    int32_t id = -1; ///< -1: empty
  };

  /// LimitKeyHash mixes its inputs into the high bits only slowly; the table
  /// indexes by the low bits, so they are mixed again (MurmurHash3's finalizer).
  static uint32_t spread(uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return uint32_t(h);
  }

  /// The slot holding `key` (hash h), or the empty one where it would go.
  size_t slot_of(uint32_t h, const LimitKey& key, const std::vector<LimitKey>& keys) const {
    const size_t mask = slots_.size() - 1;
    size_t s = h & mask;
    while (slots_[s].id >= 0 && !(slots_[s].hash == h && keys[size_t(slots_[s].id)] == key)) s = (s + 1) & mask;
    return s;
  }

  /// The first empty slot from hash h on.
  size_t free_slot(uint32_t h) const {
    const size_t mask = slots_.size() - 1;
    size_t s = h & mask;
    while (slots_[s].id >= 0) s = (s + 1) & mask;
    return s;
  }

  void rehash(size_t capacity) {
    std::vector<Slot> old(capacity);
    old.swap(slots_);
    for (const Slot& slot : old)
      if (slot.id >= 0) slots_[free_slot(slot.hash)] = slot;
  }

  std::vector<Slot> slots_;
  size_t size_ = 0;
};

} // namespace vm::detail
