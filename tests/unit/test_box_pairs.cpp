// Candidate pairs of the intersection tests (check/box_pairs.hpp) against
// brute force, on boxes of very different sizes (several grid levels), with and
// without a mask of involved boxes; and the sort of grid entries by cell
// (check/cell_sort.hpp) against a stable comparison sort.

#include "check/box_pairs.hpp"
#include "check/cell_sort.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <span>
#include <random>
#include <string>

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

/// Boxes of about one size filling a cube, as a mesh's triangles fill their
/// grid, and a few larger ones (higher grid levels).
std::vector<Bounds> even_boxes(std::mt19937_64& rng, size_t n) {
  std::uniform_real_distribution<double> u(0, 0.5), size(0.01, 0.03);
  std::vector<Bounds> boxes;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 lo(u(rng), u(rng), u(rng));
    boxes.push_back({lo, lo + Vec3(size(rng), size(rng), size(rng))});
  }
  for (size_t i = 0; i < 10; ++i) {
    const Vec3 lo(u(rng), u(rng), u(rng));
    boxes.push_back({lo, lo + 10 * Vec3(size(rng), size(rng), size(rng))});
  }
  return boxes;
}

/// The pairs for_each_overlapping_box_pair() hands on, from whichever thread,
/// joined and sorted.
std::vector<BoxPair> sorted_pairs(std::span<const Bounds> boxes, std::span<const uint8_t> involved = {}) {
  std::mutex joining;
  std::vector<BoxPair> pairs;
  bool any_empty = false;
  detail::for_each_overlapping_box_pair(boxes, involved, [&](std::span<const BoxPair> some) {
    const std::lock_guard<std::mutex> lock(joining);
    any_empty |= some.empty();
    pairs.insert(pairs.end(), some.begin(), some.end());
  });
  EXPECT_FALSE(any_empty);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// Checks for_each_overlapping_box_pair() against brute force on `boxes`, with every
/// tenth box involved, none and all; at least `least_involved` pairs involved.
void expect_every_pair_once(std::mt19937_64& rng, const std::vector<Bounds>& boxes, size_t least_involved) {
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
  ASSERT_GT(some.size(), least_involved);
  EXPECT_EQ(sorted_pairs(boxes), all);
  EXPECT_EQ(sorted_pairs(boxes, involved), some);
  std::fill(involved.begin(), involved.end(), 1);
  EXPECT_EQ(sorted_pairs(boxes, involved), all);
}

TEST(BoxPairs, every_overlapping_pair_once_with_or_without_involved_boxes) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 4; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_every_pair_once(rng, random_boxes(rng, 600), 10);
  }
}

// Boxes that fill their grid have their cells counted, not sorted by
// comparison (sort_by_cell): the same pairs.
TEST(BoxPairs, every_overlapping_pair_once_where_boxes_fill_the_grid) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 3; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_every_pair_once(rng, even_boxes(rng, 3000), 100);
  }
}

// Entries as the grids make them, in triangle order, one to eight cells each,
// enough of them for the counting sort's many blocks and runs of cells (and
// cells no entry has): the same order as sorting by cell, stably.
TEST(CellSort, counted_into_cells_as_a_stable_sort_orders_them) {
  struct Entry {
    uint64_t key;
    int32_t tri;
  };
  std::mt19937_64 rng(3);
  for (const uint64_t cells : {uint64_t(1000), uint64_t(1) << 20}) {
    SCOPED_TRACE("cells " + std::to_string(cells));
    std::uniform_int_distribution<uint64_t> cell(0, cells - 1);
    std::uniform_int_distribution<int> per_triangle(1, 8);
    std::vector<Entry> entries;
    for (int32_t t = 0; entries.size() < 400000; ++t) {
      std::vector<uint64_t> own(size_t(per_triangle(rng)));
      for (uint64_t& c : own) c = cell(rng);
      std::sort(own.begin(), own.end());
      own.erase(std::unique(own.begin(), own.end()), own.end());
      for (uint64_t c : own) entries.push_back({3 * c + 7, t}); // keys: any increasing function of the cell
    }
    std::vector<Entry> expected = entries;
    std::stable_sort(expected.begin(), expected.end(), [](const Entry& a, const Entry& b) { return a.key < b.key; });
    detail::sort_by_cell_key(entries, cells, [](const Entry& e) { return (e.key - 7) / 3; });
    ASSERT_EQ(entries.size(), expected.size());
    for (size_t i = 0; i < entries.size(); ++i)
      ASSERT_TRUE(entries[i].key == expected[i].key && entries[i].tri == expected[i].tri) << "entry " << i;
  }
}

} // namespace
