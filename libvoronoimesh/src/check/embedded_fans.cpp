/// @file check/embedded_fans.cpp
/// Fans certified embedded (check/embedded_fans.hpp).

#include "check/embedded_fans.hpp"

#include "core/parallel.hpp"
#include "mesh/topology.hpp"

#include <algorithm>
#include <array>
#include <functional>

namespace vm::detail {

namespace {

/// Fans this large are left uncertified (their pairs are tested one by one).
constexpr size_t kMaxSectors = 32;

/// The nodes after the fan's node in corner 3 t + k: the sector of the fan
/// that triangle t spans.
struct Sector {
  int32_t a, b;
};

Sector sector(std::span<const Triangle> triangles, int32_t corner) {
  const Triangle& tri = triangles[size_t(corner / 3)];
  const int k = corner % 3;
  return {tri[size_t((k + 1) % 3)], tri[size_t((k + 2) % 3)]};
}

/// Puts m sectors (sector_at(i); swap(i, j) exchanges two) in chain order,
/// each one's b the next one's a, and says what they make.
template <class SectorAt, class Swap> ChainShape order_chain(size_t m, const SectorAt& sector_at, const Swap& swap) {
  auto a = [&](size_t i) { return sector_at(i).a; };
  auto b = [&](size_t i) { return sector_at(i).b; };
  if (m == 0) return ChainShape::none;
  // The start: an a that is no b (an open chain), else any (a closed one).
  size_t start = 0, starts = 0;
  for (size_t i = 0; i < m; ++i) {
    bool is_b = false;
    for (size_t j = 0; j < m && !is_b; ++j) is_b = b(j) == a(i);
    if (!is_b) start = i, ++starts;
  }
  if (starts > 1) return ChainShape::none;
  swap(0, start);
  for (size_t i = 1; i < m; ++i) {
    size_t next = i;
    while (next < m && a(next) != b(i - 1)) ++next;
    if (next == m) return ChainShape::none;
    swap(i, next);
  }
  // Every node once as an a: a chain that winds through a node twice is no fan.
  for (size_t i = 0; i < m; ++i)
    for (size_t j = i + 1; j < m; ++j)
      if (a(i) == a(j)) return ChainShape::none;
  const bool closed = b(m - 1) == a(0);
  if (closed != (starts == 0)) return ChainShape::none;
  return closed ? ChainShape::closed : ChainShape::open;
}

/// Seen along the axis of the fan's largest normal component, every sector
/// turns the same way (exactly) and the chain goes once around its node v
/// (closed) or less than once (open). Sectors around a node that overlap only
/// along common rays hold triangles that meet only there, so no two meet
/// improperly. `sectors` are in chain order.
bool sectors_embedded(std::span<const Vec3> points, const Vec3& v, std::span<const Sector> sectors, bool closed) {
  Vec3 normal = Vec3::Zero();
  for (const Sector& s : sectors) normal += (points[size_t(s.a)] - v).cross(points[size_t(s.b)] - v);
  int k = 0;
  normal.cwiseAbs().maxCoeff(&k);
  const int turn = orient2d(v, points[size_t(sectors[0].a)], points[size_t(sectors[0].b)], k);
  if (turn == 0) return false;
  for (size_t i = 1; i < sectors.size(); ++i)
    if (orient2d(v, points[size_t(sectors[i].a)], points[size_t(sectors[i].b)], k) != turn) return false;
  // The times the chain, turning its way, reaches the ray from v through
  // its first a from the clockwise side: once around for a closed fan,
  // never for an open one. (A sector turns less than half a turn, so it
  // reaches the ray from the clockwise half-plane only by crossing it.)
  const Vec3& ray = points[size_t(sectors[0].a)];
  auto side = [&](int32_t x) { return turn * orient2d(v, ray, points[size_t(x)], k); };
  int passes = 0, before = 0; // side of the first a
  for (const Sector& s : sectors) {
    const int after = side(s.b);
    passes += before < 0 && after >= 0;
    before = after;
  }
  return passes == (closed ? 1 : 0);
}

} // namespace

void CornerFans::order(size_t fan, std::span<const Triangle> triangles) {
  const std::span<int32_t> corners = corners_.at(fan);
  shape_[fan] = order_chain(
      corners.size(), [&](size_t i) { return sector(triangles, corners[i]); },
      [&](size_t i, size_t j) { std::swap(corners[i], corners[j]); });
}

void CornerFans::build(std::span<const Triangle> triangles, std::span<const Triangle> corner_fans) {
  int32_t count = 0;
  for (const Triangle& c : corner_fans) count = std::max({count, c[0] + 1, c[1] + 1, c[2] + 1});
  std::vector<uint32_t> sizes(size_t(count), 0);
  for (const Triangle& c : corner_fans)
    for (int32_t f : c) ++sizes[size_t(f)];
  corners_.assign(sizes);
  node_.assign(size_t(count), -1);
  shape_.assign(size_t(count), ChainShape::none);
  std::fill(sizes.begin(), sizes.end(), 0);
  for (size_t t = 0; t < corner_fans.size(); ++t)
    for (size_t k = 0; k < 3; ++k) {
      const auto fan = size_t(corner_fans[t][k]);
      node_[fan] = triangles[t][k];
      corners_.at(fan)[sizes[fan]++] = int32_t(3 * t + k);
    }
  detail::parallel_for_each_index(size_t(count), [&](size_t f) { order(f, triangles); });
}

void CornerFans::update(std::span<const int32_t> changed, std::span<const Triangle> old_fans,
                        std::span<const Triangle> triangles, std::span<const Triangle> corner_fans) {
  std::vector<int32_t> touched;
  for (size_t i = 0; i < changed.size(); ++i)
    for (size_t k = 0; k < 3; ++k)
      if (const int32_t fan = old_fans[i][k]; fan >= 0 && size_t(fan) < count()) {
        corners_.erase_id(size_t(fan), 3 * changed[i] + int32_t(k));
        touched.push_back(fan);
      }
  for (int32_t t : changed)
    for (size_t k = 0; k < 3; ++k) {
      const int32_t fan = corner_fans[size_t(t)][k];
      while (count() <= size_t(fan)) corners_.add_list(), node_.push_back(-1), shape_.push_back(ChainShape::none);
      corners_.push(size_t(fan), 3 * t + int32_t(k));
      node_[size_t(fan)] = triangles[size_t(t)][k];
      touched.push_back(fan);
    }
  detail::parallel_sort(touched.begin(), touched.end(), std::less<int32_t>());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  // Each fan's corners and shape are its own: ordered in parallel.
  detail::parallel_for_each_index(touched.size(), [&](size_t i) { order(size_t(touched[i]), triangles); });
}

FanCertificates::FanCertificates(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                 const CornerFans& fans)
    : points_(points), triangles_(triangles), fans_(fans), state_(fans.count()) {
  detail::parallel_for_each_index(state_.size(), [&](size_t c) { state_[c].store(-1, std::memory_order_relaxed); });
}

bool FanCertificates::embedded(int32_t fan) const {
  int8_t state = state_[size_t(fan)].load(std::memory_order_relaxed);
  if (state >= 0) return state == 1;
  // Two threads may both decide it; they decide alike.
  const std::span<const int32_t> corners = fans_.corners(size_t(fan));
  state = 0;
  if (fans_.chained(size_t(fan)) && corners.size() <= kMaxSectors) {
    std::array<Sector, kMaxSectors> sectors;
    for (size_t i = 0; i < corners.size(); ++i) sectors[i] = sector(triangles_, corners[i]);
    state = sectors_embedded(points_, points_[size_t(fans_.node(size_t(fan)))], {sectors.data(), corners.size()},
                             fans_.closed(size_t(fan)));
  }
  state_[size_t(fan)].store(state, std::memory_order_relaxed);
  return state == 1;
}

std::vector<uint8_t> embedded_stars(std::span<const Vec3> points, std::span<const Triangle> triangles) {
  const NodeTriangles at = node_triangles(points.size(), triangles);
  std::vector<uint8_t> embedded(points.size(), 0);
  detail::parallel_for_each_index(points.size(), [&](size_t v) {
    const std::span<const int32_t> star = at.of(v);
    if (star.empty() || star.size() > kMaxSectors) return;
    std::array<Sector, kMaxSectors> sectors;
    for (size_t i = 0; i < star.size(); ++i) {
      const Triangle& tri = triangles[size_t(star[i])];
      const int k = tri[0] == int32_t(v) ? 0 : tri[1] == int32_t(v) ? 1 : 2;
      sectors[i] = sector(triangles, 3 * star[i] + k);
    }
    const ChainShape shape = order_chain(
        star.size(), [&](size_t i) { return sectors[i]; },
        [&](size_t i, size_t j) { std::swap(sectors[i], sectors[j]); });
    embedded[v] = shape != ChainShape::none &&
                  sectors_embedded(points, points[v], {sectors.data(), star.size()}, shape == ChainShape::closed);
  });
  return embedded;
}

} // namespace vm::detail
