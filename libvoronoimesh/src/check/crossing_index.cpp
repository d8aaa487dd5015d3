/// @file check/crossing_index.cpp
/// The kept lists of check/crossing_index.hpp, mended through a hash of cells
/// on a multi-level uniform grid.

#include "check/crossing_index.hpp"

#include "check/self_intersections.hpp"
#include "core/indices_where.hpp"
#include "core/key_set.hpp"
#include "core/morton.hpp"
#include "core/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>

namespace vm::detail {

namespace {

// Level 0 cells are kCellFactor median triangle extents wide, and triangles are
// filed under their box grown by kSkin cells of their level on every side: a
// median triangle's filing box then about fills a cell (the size that makes
// the search for its neighbours cheapest), and it is filed again only after a
// corner moved about a fifth of an edge.
constexpr double kCellFactor = 1.5;
constexpr double kSkin = 0.15;
constexpr int kAxisBits = 19;               // bits of a cell coordinate, biased
constexpr int64_t kBias = int64_t(1) << 17; // room below the grid's origin
static_assert(kAxisBits <= 21, "biased cell coordinates must fit a Morton key (core/morton.hpp)");
constexpr int64_t kLimit = int64_t(1) << kAxisBits;
constexpr int kLevels = 24;
// A triangle searching a finer level visits at most this many cells; beyond,
// it tests every triangle of that level instead.
constexpr int64_t kMaxCellsVisited = 64;
// The index pays where few triangles change between calls. Measured on the
// liver (303k triangles, 2 threads): filing a triangle again costs about 5 us,
// twice its share of a rebuild (735 ms), and a rebuild costs about three
// one-off checks of the whole mesh (find_self_intersections; with few
// triangles involved, a one-off check tests only those near them). So no index
// is built until two calls in a row find at most a sixth of the triangles
// changed since the call before (the first iterations move everything), and
// one is kept until a call finds more than half of them changed. (Dropping it
// at a sixth made the liver's late flip passes, which change 55k triangles,
// drop it and the next commit build it again, every iteration: 170 + 735 ms
// where filing them again costs 280.)
constexpr size_t kSettledShare = 6;
constexpr int kSettledCalls = 2;
constexpr size_t kDropShare = 2;

} // namespace

// ---------------------------------------------------------------------------
// The grid.

uint64_t CrossingIndex::key(int level, int64_t i, int64_t j, int64_t k) {
  return uint64_t(level) << (3 * kAxisBits) | uint64_t(i + kBias) << (2 * kAxisBits) |
         uint64_t(j + kBias) << kAxisBits | uint64_t(k + kBias);
}

std::array<int64_t, 3> CrossingIndex::key_cell(uint64_t k) {
  constexpr uint64_t mask = (uint64_t(1) << kAxisBits) - 1;
  return {int64_t((k >> (2 * kAxisBits)) & mask) - kBias, int64_t((k >> kAxisBits) & mask) - kBias,
          int64_t(k & mask) - kBias};
}

size_t CrossingIndex::key_level(uint64_t k) { return size_t(k >> (3 * kAxisBits)); }

std::array<int64_t, 3> CrossingIndex::cell_of(const Vec3& x, int level) const {
  const double inverse = inverse_cell_size_[size_t(level)];
  return {int64_t(std::floor((x.x() - origin_.x()) * inverse)), int64_t(std::floor((x.y() - origin_.y()) * inverse)),
          int64_t(std::floor((x.z() - origin_.z()) * inverse))};
}

int CrossingIndex::level_of(const Bounds& b) const {
  const double extent = (b.hi - b.lo).maxCoeff() * inverse_cell_size_[0];
  int l = 0;
  while (l + 1 < kLevels && extent > double(int64_t(1) << l)) ++l;
  return l;
}

bool CrossingIndex::fits_grid(const Bounds& b) const {
  // Level 0 coordinates bound those of every level.
  const auto lo = cell_of(b.lo, 0), hi = cell_of(b.hi, 0);
  for (int a = 0; a < 3; ++a)
    if (lo[size_t(a)] < -kBias || hi[size_t(a)] >= kLimit - kBias) return false;
  return true;
}

CrossingIndex::Filing CrossingIndex::filing_for(const Bounds& box, const Triangle& nodes, const Triangle& fans) const {
  const double skin = kSkin * std::ldexp(cell_size_, level_of(box));
  Filing f;
  f.box = FilingBox::around({box.lo.array() - skin, box.hi.array() + skin});
  f.nodes = nodes;
  f.fans = fans;
  const Bounds grown = f.box.bounds();
  f.level = int8_t(level_of(grown));
  // Beyond the grid (fits_grid() says so before the filing is used) the cells are not wanted.
  const auto first = cell_of(grown.lo, f.level);
  for (size_t a = 0; a < 3; ++a) f.first[a] = int32_t(std::clamp<int64_t>(first[a], INT32_MIN, INT32_MAX));
  return f;
}

CrossingIndex::FilingBox CrossingIndex::FilingBox::around(const Bounds& b) {
  FilingBox f;
  for (int a = 0; a < 3; ++a) {
    f.lo[size_t(a)] = float(b.lo[a]);
    if (double(f.lo[size_t(a)]) > b.lo[a]) f.lo[size_t(a)] = std::nextafter(f.lo[size_t(a)], -INFINITY);
    f.hi[size_t(a)] = float(b.hi[a]);
    if (double(f.hi[size_t(a)]) < b.hi[a]) f.hi[size_t(a)] = std::nextafter(f.hi[size_t(a)], INFINITY);
  }
  return f;
}

int64_t CrossingIndex::find(uint64_t k) const {
  const size_t s = slot_of(keys_, k);
  return keys_[s] == k ? int64_t(cell_of_key_[s]) : -1;
}

size_t CrossingIndex::find_or_add(uint64_t k) {
  if (2 * (cells_.count() + 1) > keys_.size()) grow_table(cells_.count());
  const size_t s = slot_of(keys_, k);
  if (keys_[s] == k) return cell_of_key_[s];
  keys_[s] = k;
  cell_of_key_[s] = uint32_t(cells_.count());
  return cells_.add_list();
}

void CrossingIndex::grow_table(size_t cells) {
  const std::vector<uint64_t> old_keys = std::move(keys_);
  const std::vector<uint32_t> old_cells = std::move(cell_of_key_);
  size_t capacity = 64;
  while (capacity < 4 * (cells + 1)) capacity *= 2;
  keys_.assign(capacity, kFreeSlot);
  cell_of_key_.assign(capacity, 0);
  for (size_t s = 0; s < old_keys.size(); ++s) {
    if (old_keys[s] == kFreeSlot) continue;
    const size_t slot = slot_of(keys_, old_keys[s]);
    keys_[slot] = old_keys[s];
    cell_of_key_[slot] = old_cells[s];
  }
}

CrossingIndex::CellEntry CrossingIndex::cell_entry(int32_t t, const Filing& f) {
  return {t, {int32_t(f.first[0]), int32_t(f.first[1]), int32_t(f.first[2])}};
}

template <class F> void CrossingIndex::for_filed_meeting(const Bounds& box, int32_t skip, F&& f) const {
  for (int l = 0; l < kLevels; ++l) {
    if (level_count_[size_t(l)] == 0) continue;
    const auto lo = cell_of(box.lo, l), hi = cell_of(box.hi, l);
    const int64_t visits = (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    if (visits > kMaxCellsVisited) { // a large box over a fine level: every triangle of it
      for (size_t s = 0; s < filed_.size(); ++s)
        if (filed_[s].level == l && int32_t(s) != skip && filed_[s].box.overlaps(box)) f(int32_t(s));
      continue;
    }
    for (int64_t i = lo[0]; i <= hi[0]; ++i)
      for (int64_t j = lo[1]; j <= hi[1]; ++j)
        for (int64_t k = lo[2]; k <= hi[2]; ++k) {
          const int64_t c = find(key(l, i, j, k));
          if (c < 0) continue;
          for (const CellEntry& s : cells_.at(size_t(c))) {
            // s is filed in every cell of its filing box and the search visits
            // every cell of `box`: s is taken in the cell of the overlap's lower corner.
            if (s.id == skip || std::max(lo[0], int64_t(s.first[0])) != i ||
                std::max(lo[1], int64_t(s.first[1])) != j || std::max(lo[2], int64_t(s.first[2])) != k ||
                !filed_[size_t(s.id)].box.overlaps(box))
              continue;
            f(s.id);
          }
        }
  }
}

bool CrossingIndex::share_a_fan(const Triangle& a, const Triangle& b) {
  return has_fan(b, a[0]) || has_fan(b, a[1]) || has_fan(b, a[2]);
}

void CrossingIndex::near(int32_t slot, std::vector<int32_t>& out) const {
  const Filing& f = filed_[size_t(slot)];
  const size_t before = out.size();
  for_filed_meeting(f.box.bounds(), slot, [&](int32_t s) {
    if (!share_a_fan(f.fans, filed_[size_t(s)].fans)) out.push_back(s);
  });
  std::sort(out.begin() + ptrdiff_t(before), out.end());
}

void CrossingIndex::free_slot(int32_t slot) {
  Filing& f = filed_[size_t(slot)];
  for_cells(f, [&](uint64_t k) { cells_.erase_id(size_t(find(k)), slot); });
  for (int32_t s : near_.at(size_t(slot))) near_.erase_id(size_t(s), slot);
  near_.clear(size_t(slot));
  if (f.level >= 0) --level_count_[size_t(f.level)];
  f = Filing::none();
  triangle_of_[size_t(slot)] = -1;
}

std::vector<int32_t> CrossingIndex::lists_unlike_search() const {
  std::vector<int32_t> unlike;
  std::vector<int32_t> searched;
  for (size_t slot = 0; slot < filed_.size(); ++slot) {
    if (filed_[slot].level < 0) continue;
    searched.clear();
    near(int32_t(slot), searched);
    const auto kept = near_.at(slot);
    if (!std::equal(kept.begin(), kept.end(), searched.begin(), searched.end())) unlike.push_back(int32_t(slot));
  }
  return unlike;
}

void CrossingIndex::filed_meeting(const Bounds& box, std::vector<int32_t>& out) const {
  for_filed_meeting(box, -1, [&](int32_t s) { out.push_back(s); });
}

// ---------------------------------------------------------------------------
// Keeping up with the mesh.

void CrossingIndex::set_grid() {
  // Origin and cell size from the boxes now, no more than 2^17 cells across.
  const size_t n = boxes_.size();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  std::vector<double> extent(n);
  for (size_t t = 0; t < n; ++t) {
    lo = lo.cwiseMin(boxes_[t].lo);
    hi = hi.cwiseMax(boxes_[t].hi);
    extent[t] = (boxes_[t].hi - boxes_[t].lo).maxCoeff();
  }
  const double span = n ? (hi - lo).maxCoeff() : 1.0;
  double h = 0;
  if (n) {
    auto mid = extent.begin() + ptrdiff_t(n / 2);
    std::nth_element(extent.begin(), mid, extent.end());
    h = kCellFactor * *mid;
  }
  if (!(h > 0)) h = span > 0 ? span : 1.0;
  cell_size_ = std::max(h, std::ldexp(span, -(kAxisBits - 2)));
  inverse_cell_size_.resize(kLevels);
  for (int l = 0; l < kLevels; ++l) inverse_cell_size_[size_t(l)] = 1 / std::ldexp(cell_size_, l);
  origin_ = n ? lo : Vec3::Zero();
}

std::vector<int32_t> CrossingIndex::in_space_order(std::span<const int32_t> triangles) const {
  std::vector<std::pair<uint64_t, int32_t>> keyed(triangles.size());
  detail::parallel_for_each_index(triangles.size(), [&](size_t i) {
    const Bounds& b = boxes_[size_t(triangles[i])];
    const auto c = cell_of(0.5 * (b.lo + b.hi), 0);
    keyed[i] = {morton_key(uint64_t(c[0] + kBias), uint64_t(c[1] + kBias), uint64_t(c[2] + kBias)), triangles[i]};
  });
  detail::parallel_sort(keyed.begin(), keyed.end(), std::less<>());
  std::vector<int32_t> ordered(keyed.size());
  detail::parallel_for_each_index(keyed.size(), [&](size_t i) { ordered[i] = keyed[i].second; });
  return ordered;
}

std::vector<BoxPair> CrossingIndex::one_off(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                            std::span<const uint8_t> involved) {
  filed_.clear();
  slot_of_.clear();
  triangle_of_.clear();
  cells_ = {};
  near_ = {};
  keys_.clear();
  cell_of_key_.clear();
  last_triangles_.assign(triangles.begin(), triangles.end());
  resize_to_overwrite(last_boxes_, boxes_.size());
  detail::parallel_for_each_index(boxes_.size(), [&](size_t t) { last_boxes_[t] = boxes_[t]; });
  return find_self_intersections(MeshArrays{points, triangles, {}}, std::numeric_limits<size_t>::max(), involved, false)
      .pairs;
}

const std::vector<int32_t>& CrossingIndex::find_stale(std::span<const Vec3> points,
                                                      std::span<const Triangle> triangles,
                                                      std::span<const Triangle> corner_fans, bool& anew,
                                                      std::span<const int32_t> only) {
  const size_t n = triangles.size();
  if (only.empty()) {
    resize_to_overwrite(boxes_, n);
    detail::parallel_for_each_index(n, [&](size_t t) { boxes_[t] = triangle_bounds(points, triangles[t]); });
  } else {
    detail::parallel_for_each_index(only.size(), [&](size_t i) {
      const auto t = size_t(only[i]);
      boxes_[t] = triangle_bounds(points, triangles[t]);
    });
  }
  stale_.clear();
  anew = filed_.empty() || slot_of_.size() != n || n == 0;
  if (anew) return stale_;
  auto is_stale = [&](size_t t) {
    const Triangle fans = corner_fans.empty() ? Triangle{-1, -1, -1} : corner_fans[t];
    const Filing& f = filed_[size_t(slot_of_[t])];
    return !same(f.nodes, triangles[t]) || !same(f.fans, fans) || !f.box.contains(boxes_[t]);
  };
  if (only.empty()) detail::indices_where(n, is_stale, stale_);
  else
    std::copy_if(only.begin(), only.end(), std::back_inserter(stale_), [&](int32_t t) { return is_stale(size_t(t)); });
  for (size_t i = 0; i < stale_.size() && !anew; ++i)
    anew = !fits_grid(filing_for(boxes_[size_t(stale_[i])], triangles[size_t(stale_[i])], {}).box.bounds());
  return stale_;
}

bool CrossingIndex::refresh(std::span<const Vec3> points, std::span<const Triangle> triangles,
                            std::span<const Triangle> corner_fans) {
  bool anew = false;
  const std::vector<int32_t>& stale = find_stale(points, triangles, corner_fans, anew);
  // Where crossings() would check anew, leave that to it.
  if (anew || kDropShare * stale.size() > triangles.size()) return false;
  if (!stale.empty()) refile(stale, triangles, corner_fans);
  return true;
}

std::vector<BoxPair> CrossingIndex::crossings(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                              std::span<const uint8_t> involved,
                                              std::span<const Triangle> corner_fans) {
  const size_t n = triangles.size();
  refiled_ = 0;
  rebuilt_ = false;
  // Up to date first: triangles with other nodes or fans, or out of their
  // filing box, are filed again.
  bool anew = false;
  const std::vector<int32_t>& stale = find_stale(points, triangles, corner_fans, anew);
  if (!anew && kDropShare * stale.size() > n) {
    settled_calls_ = 0;
    return one_off(points, triangles, involved);
  }
  if (anew) {
    size_t changed = n;
    if (last_triangles_.size() == n) {
      changed = 0;
      // As the index would see it: other nodes, or a box beyond a skin around
      // the last one (the skin of a triangle of about the median size).
      for (size_t t = 0; t < n; ++t) {
        const Bounds& last = last_boxes_[t];
        const double skin = kSkin * kCellFactor * (last.hi - last.lo).maxCoeff();
        changed += !same(last_triangles_[t], triangles[t]) ||
                   !contains(Bounds{(last.lo.array() - skin).matrix(), (last.hi.array() + skin).matrix()}, boxes_[t]);
      }
    }
    settled_calls_ = kSettledShare * changed > n ? 0 : settled_calls_ + 1;
    if (settled_calls_ < kSettledCalls) return one_off(points, triangles, involved);
    last_triangles_.clear();
    last_boxes_.clear();
    rebuild(triangles, corner_fans);
  } else {
    refile(stale, triangles, corner_fans), refiled_ = stale.size();
  }
  if (fans_stale_) fans_.build(triangles, corner_fans), fans_stale_ = false;
  return search(points, triangles, involved, corner_fans, {});
}

std::vector<BoxPair> CrossingIndex::crossings_after_changes(std::span<const Vec3> points,
                                                          std::span<const Triangle> triangles,
                                                          std::span<const uint8_t> involved,
                                                          std::span<const Triangle> corner_fans) {
  const size_t n = triangles.size();
  const std::vector<int32_t> changed = indices_where(n, [&](size_t t) { return involved[t] != 0; });
  // Without an index, or where most triangles changed, there is nothing to save.
  if (filed_.empty() || fans_stale_ || slot_of_.size() != n || boxes_.size() != n || 2 * changed.size() > n)
    return crossings(points, triangles, involved, corner_fans);
  if (changed.empty()) return {};
  refiled_ = 0;
  rebuilt_ = false;
  // Only the changed triangles' boxes are new; the others' are the last call's.
  bool anew = false;
  const std::vector<int32_t>& stale = find_stale(points, triangles, corner_fans, anew, changed);
  if (anew) return crossings(points, triangles, involved, corner_fans); // a box beyond the grid
  if (!stale.empty()) refile(stale, triangles, corner_fans), refiled_ = stale.size();
  return search(points, triangles, involved, corner_fans, changed);
}

std::vector<BoxPair> CrossingIndex::search(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                           std::span<const uint8_t> involved, std::span<const Triangle> corner_fans,
                                           std::span<const int32_t> only) const {
  const size_t n = triangles.size();
  // Projection axes of the tested triangles, found once each when first needed
  // (for a search of a few triangles, found at each test instead: a table of
  // every triangle's would cost more than the search).
  std::vector<std::atomic<int8_t>> axis(only.empty() ? n : 0);
  detail::parallel_for_each_index(axis.size(), [&](size_t t) { axis[t].store(-2, std::memory_order_relaxed); });
  auto axis_of = [&](int32_t t) {
    const Triangle& tri = triangles[size_t(t)];
    if (axis.empty()) return projection_axis(points[size_t(tri[0])], points[size_t(tri[1])], points[size_t(tri[2])]);
    int8_t a = axis[size_t(t)].load(std::memory_order_relaxed);
    if (a == -2) {
      a = projection_axis(points[size_t(tri[0])], points[size_t(tri[1])], points[size_t(tri[2])]);
      axis[size_t(t)].store(a, std::memory_order_relaxed);
    }
    return a;
  };
  const FanCertificates fans(points, triangles, fans_);
  auto fans_of = [&](int32_t t) { return corner_fans.empty() ? Triangle{-1, -1, -1} : corner_fans[size_t(t)]; };
  auto test = [&](int32_t t, int32_t s, std::vector<BoxPair>& out) {
    if (intersect_improperly(points, triangles[size_t(t)], triangles[size_t(s)], axis_of(t), axis_of(s)))
      out.push_back({std::min(t, s), std::max(t, s)});
  };
  // A listed pair, unless a renumbering has put it in one fan since (the fan
  // tests it then).
  auto test_listed = [&](int32_t t, int32_t s, std::vector<BoxPair>& out) {
    if (boxes_[size_t(t)].overlaps(boxes_[size_t(s)]) && !share_a_fan(fans_of(t), fans_of(s))) test(t, s, out);
  };
  // Each pair once: where most triangles are involved, a pair of two involved
  // ones from the lower slot (the upper part of its sorted list) and a pair
  // with an idle one from the idle one; where few are, every pair from its
  // involved ones (the lower slot if both are).
  auto is_involved = [&](int32_t t) { return involved.empty() || involved[size_t(t)]; };
  size_t involved_count = only.size();
  if (only.empty())
    for (size_t t = 0; t < n; ++t) involved_count += is_involved(int32_t(t));
  const bool from_idle = 2 * involved_count > n;
  // A pair in a fan, from an involved triangle: once, from the lower one if
  // both are involved, at the first fan they share; none if a fan they share
  // is certified embedded (they meet properly).
  auto test_fans = [&](int32_t t, std::vector<BoxPair>& out) {
    const Triangle t_fans = fans_of(t);
    for (int32_t fan : t_fans) {
      if (fan < 0 || fans.embedded(fan)) continue;
      for (int32_t corner : fans_.corners(size_t(fan))) {
        const int32_t s = corner / 3;
        if (s == t || (is_involved(s) && s < t)) continue;
        const Triangle s_fans = fans_of(s);
        int32_t first_shared = -1;
        bool certified = false;
        for (int32_t f : t_fans)
          if (has_fan(s_fans, f)) {
            if (first_shared < 0) first_shared = f;
            certified |= fans.embedded(f);
          }
        if (first_shared == fan && !certified && boxes_[size_t(t)].overlaps(boxes_[size_t(s)])) test(t, s, out);
      }
    }
  };
  tbb::enumerable_thread_specific<std::vector<BoxPair>> found_of_thread;
  const size_t searched = only.empty() ? n : only.size();
  detail::parallel_for(tbb::blocked_range<size_t>(0, searched, 64), [&](const tbb::blocked_range<size_t>& r) {
    auto& out = found_of_thread.local();
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const int32_t t = only.empty() ? int32_t(i) : only[i];
      const int32_t slot = slot_of_[size_t(t)];
      const std::span<const int32_t> list = near_.at(size_t(slot));
      auto triangle = [&](int32_t s) { return triangle_of_[size_t(s)]; };
      if (!is_involved(t)) {
        if (from_idle)
          for (int32_t s : list)
            if (is_involved(triangle(s))) test_listed(t, triangle(s), out);
        continue;
      }
      test_fans(t, out);
      if (from_idle) {
        for (auto s = std::upper_bound(list.begin(), list.end(), slot); s != list.end(); ++s)
          if (is_involved(triangle(*s))) test_listed(t, triangle(*s), out);
      } else {
        for (int32_t s : list)
          if (!is_involved(triangle(s)) || s > slot) test_listed(t, triangle(s), out);
      }
    }
  });
  std::vector<BoxPair> found;
  for (const auto& part : found_of_thread) found.insert(found.end(), part.begin(), part.end());
  std::sort(found.begin(), found.end());
  return found;
}

} // namespace vm::detail
