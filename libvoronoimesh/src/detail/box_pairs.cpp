/// @file detail/box_pairs.cpp
/// All pairs of overlapping boxes (detail/box_pairs.hpp) through a multi-level
/// uniform grid.

#include "detail/box_pairs.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vm::detail {

namespace {

// ---------------------------------------------------------------------------
// Candidate pairs: a multi-level uniform grid. Level L has cells of size
// h 2^L; each triangle lives in the lowest level whose cells are at least as
// large as its bounding box, in every cell its box touches there (2 per axis
// at most, but for rounding). A pair of overlapping boxes is taken in one cell only: the cell, at
// the higher of the two levels, that holds the lower corner of the boxes'
// intersection; along each axis that is the first cell of one of the two boxes.

/// One triangle in one cell.
struct Entry {
  uint64_t key;
  double lo_x; ///< the box's lower x, to sweep a cell along x
  int32_t tri;
  uint8_t first; ///< bit a: the cell is the triangle's first one along axis a
};

constexpr int kAxisBits = 19; // cells per axis below 2^19 (see Grid::Grid)

class Grid {
public:
  explicit Grid(std::span<const Bounds> boxes) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    std::vector<double> extent(boxes.size());
    for (size_t t = 0; t < boxes.size(); ++t) {
      lo = lo.cwiseMin(boxes[t].lo);
      hi = hi.cwiseMax(boxes[t].hi);
      extent[t] = (boxes[t].hi - boxes[t].lo).maxCoeff();
    }
    origin_ = lo;
    const double span = (hi - lo).maxCoeff();
    // Base cell: twice the median triangle size, so that most triangles
    // touch 1 to 2 cells per axis; no more than 2^18 cells per axis.
    auto mid = extent.begin() + ptrdiff_t(extent.size() / 2);
    std::nth_element(extent.begin(), mid, extent.end());
    double h = 2 * *mid;
    if (!(h > 0)) h = span > 0 ? span : 1.0;
    h = std::max(h, std::ldexp(span, -(kAxisBits - 1)));
    for (size_t l = 0; l < size_.size(); ++l) size_[l] = std::ldexp(h, int(l));
  }

  /// The level of a box: its size fits in one cell.
  int level(const Bounds& b) const {
    const double extent = (b.hi - b.lo).maxCoeff();
    int l = 0;
    while (extent > size(l)) ++l;
    return l;
  }

  double size(int level) const { return size_[size_t(level)]; }

  /// Index of the cell holding coordinate x along `axis` at `level`.
  int64_t index(double x, int axis, int level) const {
    return int64_t(std::floor((x - origin_[axis]) / size(level)));
  }

  /// Cell index ranges of box b at `level`, per axis.
  void range(const Bounds& b, int level, std::array<int64_t, 3>& first, std::array<int64_t, 3>& last) const {
    for (int a = 0; a < 3; ++a) {
      first[size_t(a)] = index(b.lo[a], a, level);
      last[size_t(a)] = index(b.hi[a], a, level);
    }
  }

  static uint64_t key(int level, int64_t i, int64_t j, int64_t k) {
    return (uint64_t(level) << (3 * kAxisBits)) | (uint64_t(i) << (2 * kAxisBits)) | (uint64_t(j) << kAxisBits) |
           uint64_t(k);
  }

  /// Calls f(key, first-flags) for every cell of box b at `level`.
  template <class F>
  void for_cells(const Bounds& b, int level, F f) const {
    std::array<int64_t, 3> first, last;
    range(b, level, first, last);
    for (int64_t i = first[0]; i <= last[0]; ++i)
      for (int64_t j = first[1]; j <= last[1]; ++j)
        for (int64_t k = first[2]; k <= last[2]; ++k)
          f(key(level, i, j, k), uint8_t((i == first[0]) | (j == first[1]) << 1 | (k == first[2]) << 2));
  }

private:
  Vec3 origin_;
  std::array<double, kAxisBits + 1> size_; ///< cell size by level, h 2^level
};


} // namespace

std::vector<BoxPair> overlapping_box_pairs(std::span<const Bounds> boxes) {
  const size_t n = boxes.size();
  if (n < 2) return {};
  const Grid grid(boxes);
  std::vector<int8_t> level(n);
  std::vector<size_t> offset(n + 1, 0);
  tbb::parallel_for(size_t(0), n, [&](size_t t) {
    level[t] = int8_t(grid.level(boxes[t]));
    size_t cells = 0;
    grid.for_cells(boxes[t], level[t], [&](uint64_t, uint8_t) { ++cells; });
    offset[t + 1] = cells;
  });
  for (size_t t = 0; t < n; ++t) offset[t + 1] += offset[t];
  std::vector<Entry> entries(offset[n]);
  tbb::parallel_for(size_t(0), n, [&](size_t t) {
    size_t e = offset[t];
    grid.for_cells(boxes[t], level[t], [&](uint64_t key, uint8_t first) { entries[e++] = {key, boxes[t].lo.x(), int32_t(t), first};
    });
  });
  tbb::parallel_sort(entries.begin(), entries.end(),
                     [](const Entry& x, const Entry& y) {
                       return x.key != y.key ? x.key < y.key : x.lo_x != y.lo_x ? x.lo_x < y.lo_x : x.tri < y.tri;
                     });
  std::vector<size_t> cell_start;
  for (size_t e = 0; e < entries.size(); ++e)
    if (e == 0 || entries[e].key != entries[e - 1].key) cell_start.push_back(e);
  cell_start.push_back(entries.size());
  const int top_level = *std::max_element(level.begin(), level.end());
  std::vector<bool> level_used(size_t(top_level) + 1, false);
  for (int8_t l : level) level_used[size_t(l)] = true;

  tbb::enumerable_thread_specific<std::vector<BoxPair>> found;
  auto consider = [&](std::vector<BoxPair>& out, int32_t t, int32_t s, uint8_t first_t, uint8_t first_s) {
    if ((first_t | first_s) != 7) return; // not the pair's own cell
    if (boxes[size_t(t)].overlaps(boxes[size_t(s)])) out.push_back({std::min(t, s), std::max(t, s)});
  };
  // Pairs of one level, in their common cell.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cell_start.size() - 1), [&](const tbb::blocked_range<size_t>& r) {
    auto& out = found.local();
    for (size_t c = r.begin(); c != r.end(); ++c)
      for (size_t i = cell_start[c]; i < cell_start[c + 1]; ++i) {
        // Sorted by lower x: once a box starts beyond this one's upper x, so do the rest.
        const double hi_x = boxes[size_t(entries[i].tri)].hi.x();
        for (size_t j = i + 1; j < cell_start[c + 1] && entries[j].lo_x <= hi_x; ++j)
          consider(out, entries[i].tri, entries[j].tri, entries[i].first, entries[j].first);
      }
  });
  // Pairs across levels: each box looks up the cells it covers in every higher level.
  if (top_level > 0)
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
      auto& out = found.local();
      for (size_t t = r.begin(); t != r.end(); ++t)
        for (int l = level[t] + 1; l <= top_level; ++l) {
          if (!level_used[size_t(l)]) continue;
          grid.for_cells(boxes[t], l, [&](uint64_t key, uint8_t first) {
            auto lo = std::lower_bound(entries.begin(), entries.end(), key,
                                       [](const Entry& e, uint64_t k) { return e.key < k; });
            for (; lo != entries.end() && lo->key == key; ++lo) consider(out, int32_t(t), lo->tri, first, lo->first);
          });
        }
    });
  size_t total = 0;
  for (const auto& part : found) total += part.size();
  std::vector<BoxPair> pairs;
  pairs.reserve(total);
  for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
  return pairs;
}

std::vector<int32_t> boxes_near(std::span<const Bounds> boxes, std::span<const uint8_t> flagged) {
  const size_t nt = boxes.size();
  auto box_of = [&](size_t t) -> const Bounds& { return boxes[t]; };
  std::vector<int32_t> all;
  size_t count = 0;
  double cell = 0;
  for (size_t t = 0; t < flagged.size(); ++t)
    if (flagged[t]) {
      const Bounds b = box_of(t);
      ++count, cell = std::max(cell, (b.hi - b.lo).maxCoeff());
    }
  if (flagged.empty() || 3 * count >= nt) {
    all.resize(nt);
    for (size_t t = 0; t < nt; ++t) all[t] = int32_t(t);
    return all;
  }
  if (!(cell > 0)) cell = 1;
  auto cell_of = [&](double x) { return int64_t(std::floor(x / cell)); };
  auto key = [](int64_t i, int64_t j, int64_t k) {
    return uint64_t(i) * 0x9E3779B97F4A7C15ull ^ uint64_t(j) * 0xC2B2AE3D27D4EB4Full ^ uint64_t(k) * 0x165667B19E3779F9ull;
  };
  // Calls f(key) for each cell of box b; false if b covers too many to list.
  auto cells = [&](const Bounds& b, auto&& f) {
    const int64_t i0 = cell_of(b.lo.x()), i1 = cell_of(b.hi.x()), j0 = cell_of(b.lo.y()), j1 = cell_of(b.hi.y()),
                  k0 = cell_of(b.lo.z()), k1 = cell_of(b.hi.z());
    if ((i1 - i0 + 1) * (j1 - j0 + 1) * (k1 - k0 + 1) > 64) return false;
    for (int64_t i = i0; i <= i1; ++i)
      for (int64_t j = j0; j <= j1; ++j)
        for (int64_t k = k0; k <= k1; ++k) f(key(i, j, k));
    return true;
  };
  // The covered cells in an open-addressing hash set: one probe or two per lookup.
  std::vector<uint64_t> covered;
  for (size_t t = 0; t < nt; ++t)
    if (flagged[t]) cells(box_of(t), [&](uint64_t k) { covered.push_back(k); });
  size_t slots = 16;
  while (slots < 2 * covered.size()) slots *= 2;
  constexpr uint64_t kEmpty = ~uint64_t(0); // keys are hashes: a collision with it only adds a false "near"
  std::vector<uint64_t> table(slots, kEmpty);
  for (uint64_t k : covered) {
    size_t i = size_t(k) & (slots - 1);
    while (table[i] != kEmpty && table[i] != k) i = (i + 1) & (slots - 1);
    table[i] = k;
  }
  auto is_covered = [&](uint64_t k) {
    for (size_t i = size_t(k) & (slots - 1);; i = (i + 1) & (slots - 1)) {
      if (table[i] == k) return true;
      if (table[i] == kEmpty) return false;
    }
  };
  std::vector<uint8_t> keep(nt, 0);
  tbb::parallel_for(size_t(0), nt, [&](size_t t) {
    bool near = false;
    const bool listed = cells(box_of(t), [&](uint64_t k) { near = near || is_covered(k); });
    keep[t] = flagged[t] || !listed || near;
  });
  for (size_t t = 0; t < nt; ++t)
    if (keep[t]) all.push_back(int32_t(t));
  return all;
}


} // namespace vm::detail
