/// @file check/surface_corners.cpp
/// Surface corners at junction points (check/surface_corners.hpp).

#include "check/surface_corners.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <tuple>

namespace vm::detail {

bool is_junction_point(const NodePhases& np, const std::vector<uint8_t>& box, size_t n) {
  return np.count(n) + size_t(std::popcount(unsigned(box[n]))) >= 4;
}

std::vector<SurfaceCorner> corners_at(const NodeMesh& m, const NodeTriangles& nt, const NodePhases& np,
                                      const std::vector<uint8_t>& box, int32_t n) {
  std::vector<SurfaceCorner> corners;
  if (!is_junction_point(np, box, size_t(n))) return corners;
  // The node's triangles by phase pair; within a pair, a fan is a run of
  // triangles each sharing an edge at n with the next. Valences are small:
  // fans are joined by repeated sweeps rather than a table.
  struct Wedge {
    int32_t triangle;
    PhasePair pair;
    int32_t fan;
    std::array<int32_t, 2> ends; // the other two corners
    double angle;
  };
  std::vector<Wedge> wedges;
  const Vec3& at = m.points[size_t(n)];
  for (int32_t t : nt.of(size_t(n))) {
    const auto& tri = m.triangles[size_t(t)];
    const size_t k = tri[0] == n ? 0 : tri[1] == n ? 1 : 2;
    const int32_t b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
    const Vec3 u = m.points[size_t(b)] - at, v = m.points[size_t(c)] - at;
    const double angle = std::atan2(u.cross(v).norm(), u.dot(v)) * (180.0 / std::numbers::pi);
    wedges.push_back({t, m.pairs[size_t(t)], int32_t(wedges.size()), {b, c}, angle});
  }
  auto share_an_edge = [](const Wedge& x, const Wedge& y) {
    return x.pair == y.pair && (x.ends[0] == y.ends[0] || x.ends[0] == y.ends[1] || x.ends[1] == y.ends[0] ||
                                x.ends[1] == y.ends[1]);
  };
  for (bool joined = true; joined;) {
    joined = false;
    for (Wedge& x : wedges)
      for (const Wedge& y : wedges)
        if (y.fan < x.fan && share_an_edge(x, y)) x.fan = y.fan, joined = true;
  }
  std::sort(wedges.begin(), wedges.end(), [](const Wedge& x, const Wedge& y) { return x.fan < y.fan; });
  for (size_t i = 0; i < wedges.size();) {
    SurfaceCorner corner{0, n, wedges[i].pair, {}};
    const int32_t fan = wedges[i].fan;
    for (; i < wedges.size() && wedges[i].fan == fan; ++i) {
      corner.angle_deg += wedges[i].angle;
      corner.triangles.push_back(wedges[i].triangle);
    }
    corners.push_back(corner);
  }
  return corners;
}

CornerSummary summarize_corners(const NodeMesh& m, const NodeTriangles& nt, const NodePhases& np,
                                const std::vector<uint8_t>& box, double sharp_deg) {
  CornerSummary summary;
  for (size_t n = 0; n < m.points.size(); ++n)
    for (const SurfaceCorner& c : corners_at(m, nt, np, box, int32_t(n))) {
      summary.sharp += c.angle_deg < sharp_deg;
      if (std::tie(c.angle_deg, c.node) < std::tie(summary.smallest.angle_deg, summary.smallest.node))
        summary.smallest = c;
    }
  return summary;
}

} // namespace vm::detail
