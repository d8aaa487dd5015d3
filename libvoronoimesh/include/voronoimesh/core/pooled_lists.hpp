#pragma once
/// @file core/pooled_lists.hpp
/// Many short lists that change one item at a time, in one pool: each list a
/// range with room to grow, moved to the end of the pool when it outgrows its
/// room (the space it leaves is reused only when the lists are assigned anew).
/// For the meshes' node adjacency, the crossing index's cells and neighbour
/// lists and the fans' corners, where one vector per list would cost an
/// allocation each.

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// The id a list item is found and sorted by: an int32_t is its own id.
/// @param item a list item
/// @return its id
inline int32_t id_of(int32_t item) { return item; }
/// The id a list item is found and sorted by: its member `id`.
/// @param item a list item
/// @return its id
template <class T> int32_t id_of(const T& item) { return item.id; }

/// Lists of T (an int32_t, or a struct with an int32_t `id`) in one pool.
template <class T> class PooledLists {
public:
  /// Lists of the given sizes, each with room for a third more; fill them through at().
  /// @param sizes the size of each list
  void assign(std::span<const uint32_t> sizes) {
    assign(sizes, [](const T*, size_t) {});
  }
  /// assign(), calling `fresh(data, count)` on the pool's memory after it is
  /// allocated and before it is first touched (to ask for huge pages).
  /// @param sizes the size of each list
  /// @param fresh called with the pool's address and room, in items
  template <class Fresh> void assign(std::span<const uint32_t> sizes, Fresh&& fresh) {
    range_.resize(sizes.size());
    uint32_t end = 0;
    for (size_t i = 0; i < sizes.size(); ++i) {
      range_[i] = {end, sizes[i], sizes[i] + sizes[i] / 3 + 2};
      end += range_[i].capacity;
    }
    // Room at the end for lists that outgrow their place: without it, the first
    // list moved after an assign copies the whole pool (100 ms of a 300k-triangle
    // crossing index, paid again after every rebuild).
    pool_.clear();
    pool_.reserve(end + end / 4 + 64);
    fresh(pool_.data(), pool_.capacity());
    pool_.assign(end, T{});
  }
  /// The items of a list.
  /// @param list the list's index
  /// @return its items, to read or change in place
  std::span<T> at(size_t list) { return {pool_.data() + range_[list].begin, range_[list].size}; }
  /// The items of a list.
  /// @param list the list's index
  /// @return its items
  std::span<const T> at(size_t list) const { return {pool_.data() + range_[list].begin, range_[list].size}; }
  /// A new empty list at the end.
  /// @return its index
  size_t add_list() {
    range_.push_back({});
    return range_.size() - 1;
  }
  /// Appends an item to a list.
  /// @param list the list's index
  /// @param item the item
  void push(size_t list, const T& item) {
    if (range_[list].size == range_[list].capacity) reserve(list, 2 * range_[list].capacity + 4);
    Range& r = range_[list];
    pool_[r.begin + r.size++] = item;
  }
  /// Makes room in a list for at least `capacity` items: a list with less is
  /// moved to the end of the pool. Not while other threads use the lists.
  /// @param list     the list's index
  /// @param capacity the room wanted
  void reserve(size_t list, size_t capacity) {
    Range& r = range_[list];
    if (r.capacity >= capacity) return;
    pool_.resize(pool_.size() + capacity);
    std::copy_n(pool_.begin() + r.begin, r.size, pool_.end() - ptrdiff_t(capacity));
    r.begin = uint32_t(pool_.size() - capacity);
    r.capacity = uint32_t(capacity);
  }
  /// Sets a list's size within its room (reserve()); items beyond the old size
  /// are whatever the pool held there. Distinct lists may be resized, and
  /// written through at(), by several threads at once.
  /// @param list the list's index
  /// @param size the new size, at most the list's room
  void resize(size_t list, size_t size) {
    assert(size <= range_[list].capacity);
    range_[list].size = uint32_t(size);
  }
  /// Inserts an item into a list sorted by id, after the items of the same id.
  /// @param list the list's index
  /// @param item the item
  void insert_by_id(size_t list, const T& item) {
    push(list, item);
    const std::span<T> items = at(list);
    const auto place = std::upper_bound(items.begin(), items.end() - 1, id_of(item),
                                        [](int32_t id, const T& x) { return id < id_of(x); });
    std::rotate(place, items.end() - 1, items.end());
  }
  /// Removes the first item with this id, keeping the others' order.
  /// @param list the list's index
  /// @param id   the id of the item to remove; nothing happens if there is none
  void erase_id(size_t list, int32_t id) {
    const std::span<T> items = at(list);
    const auto at = std::find_if(items.begin(), items.end(), [&](const T& x) { return id_of(x) == id; });
    if (at == items.end()) return;
    std::copy(at + 1, items.end(), at);
    --range_[list].size;
  }
  /// Keeps the first items of a list (and its room).
  /// @param list the list's index
  /// @param size how many to keep
  void truncate(size_t list, size_t size) { range_[list].size = std::min(range_[list].size, uint32_t(size)); }
  /// Empties a list (keeping its room).
  /// @param list the list's index
  void clear(size_t list) { range_[list].size = 0; }
  /// Keeps some lists, in a new order, without copying their items: list i
  /// becomes the old list from[i], or a new empty one where from[i] is -1.
  /// The room of the lists not kept stays in the pool, unused.
  /// @param from the old index of each list, or -1
  void keep_lists(std::span<const int32_t> from) {
    std::vector<Range> kept(from.size());
    for (size_t i = 0; i < from.size(); ++i)
      if (from[i] >= 0) kept[i] = range_[size_t(from[i])];
    range_ = std::move(kept);
  }
  /// Replaces every item x of lists first..last-1 (all by default) by map(x),
  /// dropping those mapped to an id < 0. Lists share no items: callers may map
  /// disjoint ranges of lists in parallel.
  /// @param map   a function from T to T
  /// @param first the first list to map
  /// @param last  one past the last list to map (clamped to count())
  template <class Map> void map_items(Map&& map, size_t first = 0, size_t last = SIZE_MAX) {
    for (size_t list = first; list < std::min(last, range_.size()); ++list) {
      Range& r = range_[list];
      uint32_t kept = 0;
      for (uint32_t i = 0; i < r.size; ++i) {
        const T item = map(pool_[r.begin + i]);
        if (id_of(item) >= 0) pool_[r.begin + kept++] = item;
      }
      r.size = kept;
    }
  }
  /// List `list` becomes the last list, which goes (as swap-removal of an
  /// element goes): the room of the list replaced stays in the pool, unused.
  /// @param list the list's index
  void take_last(size_t list) {
    range_[list] = range_.back();
    range_.pop_back();
  }
  /// The number of lists.
  /// @return it
  size_t count() const { return range_.size(); }

private:
  struct Range {
    uint32_t begin = 0, size = 0, capacity = 0;
  };
  std::vector<Range> range_;
  std::vector<T> pool_;
};

} // namespace vm::detail
