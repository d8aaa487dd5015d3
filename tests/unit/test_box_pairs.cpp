// Candidate pairs of the intersection tests (check/box_pairs.hpp) against
// brute force, on boxes of very different sizes (several grid levels), with and
// without a mask of involved boxes.

#include "check/box_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace {

using namespace vm;
using detail::BoxPair;
using detail::Bounds;

std::vector<Bounds> random_boxes(std::mt19937_64& rng, size_t n) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Bounds> boxes;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 lo(u(rng), u(rng), u(rng));
    const double size = std::pow(10.0, -3 * u(rng)); // 1e-3 to 1: many levels
    boxes.push_back({lo, lo + size * Vec3(u(rng), u(rng), u(rng))});
  }
  boxes.push_back(boxes[3]);                                // identical boxes
  boxes.push_back({boxes[5].hi, boxes[5].hi + Vec3::Constant(0.01)}); // touching at a corner
  return boxes;
}

std::vector<BoxPair> sorted(std::vector<BoxPair> pairs) {
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

TEST(BoxPairs, every_overlapping_pair_once_with_or_without_involved_boxes) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 4; ++trial) {
    const std::vector<Bounds> boxes = random_boxes(rng, 600);
    std::vector<uint8_t> involved(boxes.size());
    for (auto& f : involved) f = rng() % 10 == 0;
    std::vector<BoxPair> all, some;
    for (size_t i = 0; i < boxes.size(); ++i)
      for (size_t j = i + 1; j < boxes.size(); ++j)
        if (boxes[i].overlaps(boxes[j])) {
          all.push_back({int32_t(i), int32_t(j)});
          if (involved[i] || involved[j]) some.push_back({int32_t(i), int32_t(j)});
        }
    ASSERT_GT(all.size(), some.size());
    ASSERT_GT(some.size(), 10u);
    EXPECT_EQ(sorted(detail::overlapping_box_pairs(boxes)), all) << "trial " << trial;
    EXPECT_EQ(sorted(detail::overlapping_box_pairs(boxes, involved)), some) << "trial " << trial;
    std::fill(involved.begin(), involved.end(), 1);
    EXPECT_EQ(sorted(detail::overlapping_box_pairs(boxes, involved)), all) << "trial " << trial;
  }
}

} // namespace
