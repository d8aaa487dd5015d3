/// @file improve/kept_points.cpp
/// Moves that carry a kept point out of its phase (improve/kept_points.hpp).

#include "improve/kept_points.hpp"

#include "core/parallel.hpp"

#include <algorithm>

namespace vm::detail {
namespace {

/// Which side of the plane of triangle (a, b, c) point p lies on, by the
/// triangle's normal (b - a) x (c - a): positive along it.
double side(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) { return (b - a).cross(c - a).dot(p - a); }

/// True when p, seen along the normal of triangle (a, b, c), lies within it.
bool within(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  const Vec3 n = (b - a).cross(c - a);
  return (b - a).cross(p - a).dot(n) >= 0 && (c - b).cross(p - b).dot(n) >= 0 && (a - c).cross(p - c).dot(n) >= 0;
}

} // namespace

std::vector<int32_t> triangles_losing_kept_points(const InterfaceMesh& mesh, std::span<const Vec3> before,
                                                  std::span<const uint8_t> involved, const PhaseField& field) {
  const auto& triangles = mesh.triangles();
  const auto& now = mesh.positions();
  std::vector<uint8_t> loses(triangles.size(), 0);
  detail::parallel_for_each_index(triangles.size(), [&](size_t t) {
    if (!involved[t]) return;
    const auto& tri = triangles[t];
    const Vec3 &a0 = before[size_t(tri[0])], &b0 = before[size_t(tri[1])], &c0 = before[size_t(tri[2])];
    const Vec3 &a1 = now[size_t(tri[0])], &b1 = now[size_t(tri[1])], &c1 = now[size_t(tri[2])];
    thread_local std::vector<Vec3> points;
    points.clear();
    field.kept_points(a0.cwiseMin(b0).cwiseMin(c0).cwiseMin(a1).cwiseMin(b1).cwiseMin(c1),
                      a0.cwiseMax(b0).cwiseMax(c0).cwiseMax(a1).cwiseMax(b1).cwiseMax(c1), points);
    const PhasePair pair = mesh.pair(OMesh::FaceHandle(int(t)));
    for (const Vec3& p : points) {
      // Geometry first: the phase is looked up only for a point the move took across.
      const double was = side(a0, b0, c0, p), is = side(a1, b1, c1, p);
      if (!((was > 0 && is < 0) || (was < 0 && is > 0)) || !(within(a0, b0, c0, p) || within(a1, b1, c1, p))) continue;
      const int32_t phase = field.kept_phase(p);
      // The normal points into the pair's second phase: a point of it that lay
      // above the triangle, or one of the first phase that lay below, went out.
      if ((phase == pair[1] && was > 0) || (phase == pair[0] && was < 0)) {
        loses[t] = 1;
        break;
      }
    }
  });
  std::vector<int32_t> out;
  for (size_t t = 0; t < loses.size(); ++t)
    if (loses[t]) out.push_back(int32_t(t));
  return out;
}

} // namespace vm::detail
