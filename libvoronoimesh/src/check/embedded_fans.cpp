/// @file check/embedded_fans.cpp
/// Fans certified embedded (check/embedded_fans.hpp).

#include "check/embedded_fans.hpp"

#include "core/parallel.hpp"

#include <algorithm>

namespace vm::detail {

namespace {

/// Orders `fan` into one chain, each sector's b the next one's a, starting
/// where an open chain starts; false if it forms no single chain. Sets
/// `closed` when the last b is the first a.
bool order_chain(std::span<Sector> fan, bool& closed) {
  const size_t m = fan.size();
  // The start: an a that is no b (an open chain), else any (a closed one).
  size_t start = 0, starts = 0;
  for (size_t i = 0; i < m; ++i)
    if (std::none_of(fan.begin(), fan.end(), [&](const Sector& s) { return s.b == fan[i].a; })) start = i, ++starts;
  if (starts > 1) return false;
  std::swap(fan[0], fan[start]);
  for (size_t i = 1; i < m; ++i) {
    const auto next = std::find_if(fan.begin() + ptrdiff_t(i), fan.end(),
                                   [&](const Sector& s) { return s.a == fan[i - 1].b; });
    if (next == fan.end()) return false;
    std::swap(fan[i], *next);
  }
  closed = fan[m - 1].b == fan[0].a;
  if (closed != (starts == 0)) return false;
  // Every node once as an a: a chain that winds through one node twice is no fan.
  for (size_t i = 0; i < m; ++i)
    for (size_t j = i + 1; j < m; ++j)
      if (fan[i].a == fan[j].a) return false;
  return true;
}

} // namespace

CornerFans::CornerFans(std::span<const Triangle> triangles, std::span<const Triangle> corner_fans) {
  int32_t count = 0;
  for (const Triangle& c : corner_fans) count = std::max({count, c[0] + 1, c[1] + 1, c[2] + 1});
  offset_.assign(size_t(count) + 1, 0);
  for (const Triangle& c : corner_fans)
    for (int32_t f : c) ++offset_[size_t(f) + 1];
  for (size_t f = 0; f < size_t(count); ++f) offset_[f + 1] += offset_[f];
  sectors_.resize(3 * corner_fans.size());
  node_.assign(size_t(count), -1);
  closed_.assign(size_t(count), 0);
  std::vector<uint32_t> next(offset_.begin(), offset_.end() - 1);
  for (size_t t = 0; t < corner_fans.size(); ++t)
    for (size_t k = 0; k < 3; ++k) {
      const auto fan = size_t(corner_fans[t][k]);
      node_[fan] = triangles[t][k];
      sectors_[next[fan]++] = {triangles[t][(k + 1) % 3], triangles[t][(k + 2) % 3]};
    }
  detail::parallel_for_each_index(size_t(count), [&](size_t f) {
    const std::span<Sector> fan(sectors_.data() + offset_[f], size_t(offset_[f + 1] - offset_[f]));
    bool closed = false;
    if (fan.empty() || !order_chain(fan, closed)) fan[0].a = -1; // marks it: no chain
    closed_[f] = closed;
  });
}

FanCertificates::FanCertificates(std::span<const Vec3> points, const CornerFans& fans)
    : points_(points), fans_(fans), state_(fans.count()) {
  detail::parallel_for_each_index(state_.size(), [&](size_t c) { state_[c].store(-1, std::memory_order_relaxed); });
}

/// Seen along the axis of the fan's largest normal component, every sector
/// turns the same way (exactly) and the chain goes once around its node
/// (closed) or less than once (open). Sectors around a node that overlap only
/// along common rays hold triangles that meet only there, so no two meet
/// improperly.
bool FanCertificates::embedded(int32_t fan) const {
  int8_t state = state_[size_t(fan)].load(std::memory_order_relaxed);
  if (state >= 0) return state == 1;
  // Two threads may both decide it; they decide alike.
  const std::span<const Sector> sectors = fans_.sectors(size_t(fan));
  state = 0;
  if (!sectors.empty() && sectors[0].a >= 0) {
    const Vec3& v = points_[size_t(fans_.node(size_t(fan)))];
    Vec3 normal = Vec3::Zero();
    for (const Sector& s : sectors) normal += (points_[size_t(s.a)] - v).cross(points_[size_t(s.b)] - v);
    int k = 0;
    normal.cwiseAbs().maxCoeff(&k);
    const int turn = orient2d(v, points_[size_t(sectors[0].a)], points_[size_t(sectors[0].b)], k);
    bool same = turn != 0;
    for (size_t i = 1; same && i < sectors.size(); ++i)
      same = orient2d(v, points_[size_t(sectors[i].a)], points_[size_t(sectors[i].b)], k) == turn;
    if (same) {
      // The times the chain, turning its way, reaches the ray from v through
      // its first a from the clockwise side: once around for a closed fan,
      // never for an open one. (A sector turns less than half a turn, so it
      // reaches the ray from the clockwise half-plane only by crossing it.)
      const Vec3& ray = points_[size_t(sectors[0].a)];
      auto side = [&](int32_t x) { return turn * orient2d(v, ray, points_[size_t(x)], k); };
      int passes = 0, before = 0; // side of the first a
      for (const Sector& s : sectors) {
        const int after = side(s.b);
        passes += before < 0 && after >= 0;
        before = after;
      }
      state = passes == (fans_.closed(size_t(fan)) ? 1 : 0);
    }
  }
  state_[size_t(fan)].store(state, std::memory_order_relaxed);
  return state == 1;
}

} // namespace vm::detail
