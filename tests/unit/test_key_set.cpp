// core/key_set.hpp: the hash set through which the one-off crossing check finds
// the triangles near flagged ones. It must answer exactly as a std::set would,
// for keys whose low bits agree (packed cell coordinates), for repeats, and for
// the key it uses to mark a free slot.

#include "core/key_set.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <set>
#include <vector>

namespace {

using vm::detail::KeySet;

TEST(KeySet, holds_exactly_the_keys_it_was_given) {
  std::mt19937_64 random(7);
  std::vector<uint64_t> keys;
  for (int i = 0; i < 3000; ++i) keys.push_back(random() << 20); // low bits all zero: they must not decide the slot
  for (int i = 0; i < 500; ++i) keys.push_back(keys[size_t(i)]); // repeats
  keys.push_back(0);
  const KeySet set(keys);
  const std::set<uint64_t> expected(keys.begin(), keys.end());
  for (uint64_t k : expected) EXPECT_TRUE(set.contains(k)) << k;
  size_t absent = 0;
  for (int i = 0; i < 20000; ++i) {
    const uint64_t k = random() << (i % 2 ? 20 : 0);
    if (expected.count(k)) continue;
    EXPECT_FALSE(set.contains(k)) << k;
    ++absent;
  }
  EXPECT_GT(absent, 19000u);
  EXPECT_FALSE(set.contains(~uint64_t(0)));
}

TEST(KeySet, the_key_that_marks_free_slots_is_a_key_too) {
  const std::vector<uint64_t> keys{~uint64_t(0), 5};
  const KeySet set(keys);
  EXPECT_TRUE(set.contains(~uint64_t(0)));
  EXPECT_TRUE(set.contains(5));
  EXPECT_FALSE(set.contains(6));
  EXPECT_FALSE(KeySet(std::vector<uint64_t>{}).contains(0));
}

} // namespace
