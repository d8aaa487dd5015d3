// core/huge_pages.hpp: resizing on huge pages must be an ordinary resize to
// whoever reads the vector (the advice changes where the kernel puts the
// pages, and the first touch by every thread which thread clears them, never
// the contents): old elements kept, new ones filled, strings too.

#include "core/huge_pages.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace {

using vm::detail::assign_on_huge_pages;
using vm::detail::push_back_on_huge_pages;
using vm::detail::reserve_on_huge_pages;
using vm::detail::resize_on_huge_pages;

constexpr size_t kLarge = size_t(5) << 20; // elements: several whole huge pages to advise

TEST(HugePages, resizing_keeps_the_old_elements_and_fills_the_new) {
  std::vector<int32_t> v{4, 5, 6};
  resize_on_huge_pages(v, kLarge, -7);
  ASSERT_EQ(v.size(), kLarge);
  EXPECT_EQ(v[0], 4);
  EXPECT_EQ(v[2], 6);
  // Over kTouchInParallel: zeroed by every thread first, then filled.
  static_assert(kLarge * sizeof(int32_t) >= vm::detail::kTouchInParallel);
  EXPECT_TRUE(std::all_of(v.begin() + 3, v.end(), [](int32_t x) { return x == -7; }));
  resize_on_huge_pages(v, 2); // shrinking is a plain resize
  EXPECT_EQ(v, (std::vector<int32_t>{4, 5}));
}

TEST(HugePages, value_initialises_without_a_fill_and_assigns_over_old_contents) {
  std::string s = "header";
  resize_on_huge_pages(s, kLarge);
  EXPECT_EQ(s.substr(0, 6), "header");
  EXPECT_EQ(s[6], '\0');
  EXPECT_EQ(s.back(), '\0');
  std::vector<float> f(10, 3.f);
  assign_on_huge_pages(f, kLarge, 0.5f);
  ASSERT_EQ(f.size(), kLarge);
  EXPECT_EQ(f.front(), 0.5f);
  EXPECT_EQ(f.back(), 0.5f);
}

TEST(HugePages, pushing_back_keeps_every_element_in_order_as_it_grows) {
  std::vector<int64_t> v{-1};
  for (int64_t i = 0; i < int64_t(kLarge); ++i) push_back_on_huge_pages(v, i);
  ASSERT_EQ(v.size(), kLarge + 1);
  EXPECT_EQ(v[0], -1);
  for (size_t i = 1; i < v.size(); i += 4099) ASSERT_EQ(v[i], int64_t(i) - 1);
  EXPECT_EQ(v.back(), int64_t(kLarge) - 1);
}

TEST(HugePages, reserving_makes_room_and_changes_nothing_else) {
  std::vector<int32_t> v{1, 2};
  reserve_on_huge_pages(v, kLarge);
  EXPECT_GE(v.capacity(), kLarge);
  EXPECT_EQ(v, (std::vector<int32_t>{1, 2}));
  const int32_t* room = v.data();
  reserve_on_huge_pages(v, 3); // room enough already: the memory stays
  EXPECT_EQ(v.data(), room);
  EXPECT_EQ(v, (std::vector<int32_t>{1, 2}));
}

} // namespace
