/// @file check/box_pairs.cpp
/// All pairs of overlapping boxes (check/box_pairs.hpp) through a multi-level
/// uniform grid.

#include "check/box_pairs.hpp"

#include "check/cell_sort.hpp"
#include "core/huge_pages.hpp"
#include "core/indices_where.hpp"
#include "core/parallel.hpp"
#include "core/unset_vector.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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
  int32_t tri;
  uint8_t first;    ///< bit a: the cell is the triangle's first one along axis a
  uint8_t involved; ///< the box is one whose pairs are wanted
};

constexpr int kAxisBits = 19; // cells per axis below 2^19 (see Grid::Grid)

/// Pairs a thread gathers before it hands them on (for_each_overlapping_box_pair).
constexpr size_t kHandedOn = 4096;

class Grid {
public:
  explicit Grid(std::span<const Bounds> boxes) {
    // The boxes' reach (a minimum and maximum: the same in any order) and sizes, in parallel.
    const Vec3 infinite = Vec3::Constant(std::numeric_limits<double>::infinity());
    UnsetVector<double> extent(boxes.size());
    const Bounds reach = detail::parallel_reduce(
        tbb::blocked_range<size_t>(0, boxes.size()), Bounds{infinite, -infinite},
        [&](const tbb::blocked_range<size_t>& r, Bounds b) {
          for (size_t t = r.begin(); t != r.end(); ++t) {
            b = {b.lo.cwiseMin(boxes[t].lo), b.hi.cwiseMax(boxes[t].hi)};
            extent[t] = (boxes[t].hi - boxes[t].lo).maxCoeff();
          }
          return b;
        },
        [](const Bounds& a, const Bounds& b) { return Bounds{a.lo.cwiseMin(b.lo), a.hi.cwiseMax(b.hi)}; });
    const Vec3 lo = reach.lo, hi = reach.hi;
    origin_ = lo;
    extent_hi_ = hi;
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

  /// The cells of `level` along each axis that the boxes reach.
  std::array<int64_t, 3> cells(int level) const {
    std::array<int64_t, 3> n;
    for (int a = 0; a < 3; ++a) n[size_t(a)] = index(extent_hi_[a], a, level) + 1;
    return n;
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
  Vec3 origin_, extent_hi_;
  std::array<double, kAxisBits + 1> size_; ///< cell size by level, h 2^level
};


/// Sorts entries by cell key, and by triangle within a cell
/// (check/cell_sort.hpp): the cells up to `top_level` numbered densely.
void sort_by_cell(UnsetVector<Entry>& entries, const Grid& grid, int top_level) {
  std::vector<uint64_t> level_start(size_t(top_level) + 2, 0);
  std::vector<std::array<int64_t, 3>> cells(size_t(top_level) + 1);
  for (int l = 0; l <= top_level; ++l) {
    cells[size_t(l)] = grid.cells(l);
    const auto& c = cells[size_t(l)];
    level_start[size_t(l) + 1] = level_start[size_t(l)] + uint64_t(c[0]) * uint64_t(c[1]) * uint64_t(c[2]);
  }
  // Dense cell ids in key order: by level, then i, j, k.
  constexpr uint64_t mask = (uint64_t(1) << kAxisBits) - 1;
  sort_by_cell_key(entries, level_start.back(), [&](const Entry& e) {
    const auto l = size_t(e.key >> (3 * kAxisBits));
    const auto& c = cells[l];
    const uint64_t i = (e.key >> (2 * kAxisBits)) & mask, j = (e.key >> kAxisBits) & mask, k = e.key & mask;
    return level_start[l] + (i * uint64_t(c[1]) + j) * uint64_t(c[2]) + k;
  });
}

} // namespace

void for_each_overlapping_box_pair(std::span<const Bounds> boxes, std::span<const uint8_t> involved,
                                   const std::function<void(std::span<const BoxPair>)>& visit) {
  const size_t n = boxes.size();
  auto is_involved = [&](size_t t) { return uint8_t(involved.empty() || involved[t]); };
  if (n < 2) return;
  const Grid grid(boxes);
  std::vector<int8_t> level(n);
  std::vector<size_t> offset(n + 1, 0);
  detail::parallel_for(size_t(0), n, [&](size_t t) {
    level[t] = int8_t(grid.level(boxes[t]));
    size_t cells = 0;
    grid.for_cells(boxes[t], level[t], [&](uint64_t, uint8_t) { ++cells; });
    offset[t + 1] = cells;
  });
  for (size_t t = 0; t < n; ++t) offset[t + 1] += offset[t];
  // 16 bytes a cell a box reaches, fresh memory at every call (92 MB on 1,000
  // grains): on huge pages (core/huge_pages.hpp).
  UnsetVector<Entry> entries; // each written below, by the thread of its triangle
  resize_on_huge_pages(entries, offset[n]);
  detail::parallel_for(size_t(0), n, [&](size_t t) {
    size_t e = offset[t];
    grid.for_cells(boxes[t], level[t],
                   [&](uint64_t key, uint8_t first) { entries[e++] = {key, int32_t(t), first, is_involved(t)}; });
  });
  const int top_level = *std::max_element(level.begin(), level.end());
  sort_by_cell(entries, grid, top_level);
  std::vector<size_t> cell_start = indices_where<size_t>(
      entries.size(), [&](size_t e) { return e == 0 || entries[e].key != entries[e - 1].key; });
  cell_start.push_back(entries.size());
  std::vector<bool> level_used(size_t(top_level) + 1, false);
  for (int8_t l : level) level_used[size_t(l)] = true;

  // Each thread's pairs since it last handed them on: a buffer that stays in cache.
  tbb::enumerable_thread_specific<std::vector<BoxPair>> found([] {
    std::vector<BoxPair> buffer;
    buffer.reserve(kHandedOn);
    return buffer;
  });
  auto consider = [&](std::vector<BoxPair>& out, int32_t t, int32_t s, uint8_t first_t, uint8_t first_s,
                      const Bounds& box_t, const Bounds& box_s) {
    if ((first_t | first_s) != 7) return; // not the pair's own cell
    if (!box_t.overlaps(box_s)) return;
    out.push_back({std::min(t, s), std::max(t, s)});
    if (out.size() == kHandedOn) visit(out), out.clear();
  };
  // Pairs of one level, in their common cell. A cell's boxes are read once,
  // into a local copy: its pairs read them up to a cell's count of times each,
  // and from the whole array those reads were cache misses.
  tbb::enumerable_thread_specific<std::vector<Bounds>> cell_boxes;
  detail::parallel_for(tbb::blocked_range<size_t>(0, cell_start.size() - 1), [&](const tbb::blocked_range<size_t>& r) {
    auto& out = found.local();
    auto& local = cell_boxes.local();
    for (size_t c = r.begin(); c != r.end(); ++c) {
      const size_t begin = cell_start[c], end = cell_start[c + 1];
      local.clear();
      for (size_t i = begin; i < end; ++i) local.push_back(boxes[size_t(entries[i].tri)]);
      // Each involved entry meets every other, but an involved one before it
      // (that pair was taken from the other side).
      for (size_t i = begin; i < end; ++i) {
        if (!entries[i].involved) continue;
        for (size_t j = involved.empty() ? i + 1 : begin; j < end; ++j)
          if (j > i || (j < i && !entries[j].involved))
            consider(out, entries[i].tri, entries[j].tri, entries[i].first, entries[j].first, local[i - begin],
                     local[j - begin]);
      }
    }
  });
  // Pairs across levels: each box looks up the cells it covers in every higher level.
  if (top_level > 0)
    detail::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
      auto& out = found.local();
      for (size_t t = r.begin(); t != r.end(); ++t)
        for (int l = level[t] + 1; l <= top_level; ++l) {
          if (!level_used[size_t(l)]) continue;
          grid.for_cells(boxes[t], l, [&](uint64_t key, uint8_t first) {
            auto lo = std::lower_bound(entries.begin(), entries.end(), key,
                                       [](const Entry& e, uint64_t k) { return e.key < k; });
            for (; lo != entries.end() && lo->key == key; ++lo)
              if (is_involved(t) || lo->involved)
                consider(out, int32_t(t), lo->tri, first, lo->first, boxes[t], boxes[size_t(lo->tri)]);
          });
        }
    });
  for (const auto& rest : found)
    if (!rest.empty()) visit(rest);
}

} // namespace vm::detail
