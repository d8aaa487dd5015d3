// core/pooled_lists.hpp: keep_lists(), which carries the crossing index's
// neighbour lists over a renumbering without copying them, map_items() by
// ranges of lists, which the index maps in parallel, and take_last(), with
// which the edits in place remove a node.

#include "voronoimesh/core/pooled_lists.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using vm::detail::PooledLists;

std::vector<int32_t> items(const PooledLists<int32_t>& lists, size_t list) {
  const auto span = lists.at(list);
  return {span.begin(), span.end()};
}

/// Lists of the given sizes holding 0, 1, 2, ... in order.
PooledLists<int32_t> numbered(const std::vector<uint32_t>& sizes) {
  PooledLists<int32_t> lists;
  lists.assign(sizes);
  int32_t next = 0;
  for (size_t l = 0; l < sizes.size(); ++l)
    for (int32_t& x : lists.at(l)) x = next++;
  return lists;
}

TEST(PooledLists, assign_shows_the_fresh_pool_before_filling_it) {
  PooledLists<int32_t> lists;
  const std::vector<uint32_t> sizes{3, 0, 5};
  const int32_t* seen = nullptr;
  size_t room = 0;
  lists.assign(sizes, [&](const int32_t* data, size_t count) { seen = data, room = count; });
  ASSERT_NE(seen, nullptr);
  EXPECT_GE(room, size_t(3 + 0 + 5));
  ASSERT_EQ(lists.count(), 3u);
  EXPECT_EQ(lists.at(0).data(), seen); // the lists live in the memory shown
  EXPECT_EQ(lists.at(2).size(), 5u);
  EXPECT_EQ(lists.at(2)[4], 0);
}

TEST(PooledLists, keep_lists_reorders_drops_and_adds_lists_that_still_grow) {
  PooledLists<int32_t> lists = numbered({2, 3, 1}); // 0 1 | 2 3 4 | 5
  const std::vector<int32_t> from{0, -1, 2}; // list 1 dropped, a new empty one in its place
  lists.keep_lists(from);
  ASSERT_EQ(lists.count(), 3u);
  EXPECT_EQ(items(lists, 0), (std::vector<int32_t>{0, 1}));
  EXPECT_TRUE(items(lists, 1).empty());
  EXPECT_EQ(items(lists, 2), (std::vector<int32_t>{5}));
  for (int32_t x : {7, 8, 9, 10, 11}) lists.push(1, x); // the new list grows at the end of the pool
  lists.insert_by_id(2, 4);
  EXPECT_EQ(items(lists, 0), (std::vector<int32_t>{0, 1})) << "growing another list must not touch this one";
  EXPECT_EQ(items(lists, 1), (std::vector<int32_t>{7, 8, 9, 10, 11}));
  EXPECT_EQ(items(lists, 2), (std::vector<int32_t>{4, 5}));
  lists.map_items([](int32_t x) { return x % 2 ? x : -1; }); // drop the even ones
  EXPECT_EQ(items(lists, 0), (std::vector<int32_t>{1}));
  EXPECT_EQ(items(lists, 1), (std::vector<int32_t>{7, 9, 11}));
  EXPECT_EQ(items(lists, 2), (std::vector<int32_t>{5}));
}

TEST(PooledLists, map_items_of_a_range_of_lists_leaves_the_others) {
  PooledLists<int32_t> lists = numbered({2, 2, 2, 2}); // 0 1 | 2 3 | 4 5 | 6 7
  lists.map_items([](int32_t x) { return x % 2 ? 10 * x : -1; }, 1, 3);
  EXPECT_EQ(items(lists, 0), (std::vector<int32_t>{0, 1}));
  EXPECT_EQ(items(lists, 1), (std::vector<int32_t>{30}));
  EXPECT_EQ(items(lists, 2), (std::vector<int32_t>{50}));
  EXPECT_EQ(items(lists, 3), (std::vector<int32_t>{6, 7}));
  lists.map_items([](int32_t x) { return x + 1; }, 3, 99); // past the end: clamped
  EXPECT_EQ(items(lists, 3), (std::vector<int32_t>{7, 8}));
}

TEST(PooledLists, take_last_moves_the_last_list_into_a_slot) {
  // As the edits in place remove a node: its list goes, the last takes its index.
  PooledLists<int32_t> lists = numbered({2, 1, 3}); // 0 1 | 2 | 3 4 5
  lists.take_last(0);
  ASSERT_EQ(lists.count(), 2u);
  EXPECT_EQ(items(lists, 0), (std::vector<int32_t>{3, 4, 5}));
  EXPECT_EQ(items(lists, 1), (std::vector<int32_t>{2}));
  lists.push(0, 6); // still grows
  EXPECT_EQ(items(lists, 0), (std::vector<int32_t>{3, 4, 5, 6}));
  lists.take_last(1); // the last list itself
  ASSERT_EQ(lists.count(), 1u);
  EXPECT_EQ(items(lists, 0), (std::vector<int32_t>{3, 4, 5, 6}));
}

} // namespace
