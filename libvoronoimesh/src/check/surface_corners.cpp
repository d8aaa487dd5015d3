/// @file check/surface_corners.cpp
/// Surface corners at junction points (check/surface_corners.hpp).

#include "check/surface_corners.hpp"

#include "core/union_find.hpp"
#include "mesh/angle.hpp"

#include <algorithm>
#include <bit>
#include <tuple>

namespace vm::detail {

namespace {

/// Whether node `n` is a junction point, whose place the phases fix: its phases
/// and the box faces it lies on number four or more.
bool is_junction_point(const NodePhases& np, const std::vector<uint8_t>& box, size_t n) {
  return np.count(n) + size_t(std::popcount(unsigned(box[n]))) >= 4;
}

} // namespace

std::vector<SurfaceCorner> corners_at(const NodeMesh& m, const NodeTriangles& nt, const NodePhases& np,
                                      const std::vector<uint8_t>& box, int32_t n) {
  std::vector<SurfaceCorner> corners;
  if (!is_junction_point(np, box, size_t(n))) return corners;
  // The node's triangles, each a wedge between its two other corners; two
  // wedges of one phase pair that share an other corner share an edge at n,
  // so one fan holds them. Joined through sorted (pair, corner) keys: a node of
  // any valence costs k log k.
  struct Wedge {
    int32_t triangle;
    PhasePair pair;
    double angle;
  };
  std::vector<Wedge> wedges;
  std::vector<std::tuple<PhasePair, int32_t, int32_t>> ends; // (pair, other corner, wedge)
  const Vec3& at = m.points[size_t(n)];
  for (int32_t t : nt.of(size_t(n))) {
    const auto& tri = m.triangles[size_t(t)];
    const size_t k = tri[0] == n ? 0 : tri[1] == n ? 1 : 2;
    const int32_t b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
    const double angle = angle_deg(m.points[size_t(b)] - at, m.points[size_t(c)] - at);
    const auto w = int32_t(wedges.size());
    wedges.push_back({t, m.pairs[size_t(t)], angle});
    ends.emplace_back(m.pairs[size_t(t)], b, w);
    ends.emplace_back(m.pairs[size_t(t)], c, w);
  }
  std::sort(ends.begin(), ends.end());
  UnionFind fans(wedges.size());
  for (size_t i = 1; i < ends.size(); ++i)
    if (std::get<0>(ends[i]) == std::get<0>(ends[i - 1]) && std::get<1>(ends[i]) == std::get<1>(ends[i - 1]))
      fans.unite(std::get<2>(ends[i]), std::get<2>(ends[i - 1]));
  // Each fan in the order of its first wedge (its representative: the smallest member).
  std::vector<int32_t> corner_of(wedges.size(), -1);
  for (size_t w = 0; w < wedges.size(); ++w) {
    int32_t& corner = corner_of[size_t(fans.find(int32_t(w)))];
    if (corner < 0) {
      corner = int32_t(corners.size());
      corners.push_back({0, n, wedges[w].pair, {}});
    }
    corners[size_t(corner)].angle_deg += wedges[w].angle;
    corners[size_t(corner)].triangles.push_back(wedges[w].triangle);
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
