#include "core/morton.hpp"

#include <gtest/gtest.h>

#include <random>

namespace vm::detail {
namespace {

/// The key bit by bit, as the definition reads: bit b of i, j, k at 3b+2, 3b+1, 3b.
uint64_t morton_by_bits(uint64_t i, uint64_t j, uint64_t k) {
  uint64_t key = 0;
  for (int b = 0; b < 21; ++b)
    key |= ((i >> b) & 1) << (3 * b + 2) | ((j >> b) & 1) << (3 * b + 1) | ((k >> b) & 1) << (3 * b);
  return key;
}

TEST(Morton, InterleavesTheBitsOfEachCoordinate) {
  EXPECT_EQ(morton_key(1, 0, 0), 4u);
  EXPECT_EQ(morton_key(0, 1, 0), 2u);
  EXPECT_EQ(morton_key(0, 0, 1), 1u);
  const uint64_t top = (uint64_t(1) << 21) - 1;
  EXPECT_EQ(morton_key(top, top, top), (uint64_t(1) << 63) - 1);
  std::mt19937_64 random(7);
  for (int n = 0; n < 1000; ++n) {
    const uint64_t i = random() & top, j = random() & top, k = random() & top;
    ASSERT_EQ(morton_key(i, j, k), morton_by_bits(i, j, k)) << i << " " << j << " " << k;
  }
}

TEST(Morton, KeepsTheCellsOfAnOctantTogether) {
  // Every cell of the 2x2x2 block at (2, 4, 6) comes before every cell of the next block.
  uint64_t highest = 0;
  for (uint64_t di = 0; di < 2; ++di)
    for (uint64_t dj = 0; dj < 2; ++dj)
      for (uint64_t dk = 0; dk < 2; ++dk) highest = std::max(highest, morton_key(2 + di, 4 + dj, 6 + dk));
  EXPECT_EQ(highest - morton_key(2, 4, 6), 7u);
}

} // namespace
} // namespace vm::detail
