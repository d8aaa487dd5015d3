/// @file improve/kept_points.cpp
/// Moves that carry a kept point out of its phase (improve/kept_points.hpp).

#include "improve/kept_points.hpp"

#include "core/indices_where.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <span>

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

/// A kept point must stay this share of a triangle's longest edge away from
/// it (as well as on its phase's side): remesh collapses at the rim of a
/// one-voxel sheet of flat voxels left triangles through the centres there (to
/// within 1e-3 of a voxel, their winding numbers 0.78 and 0.995), which a
/// check of the sides alone lets through, and which any point location then
/// reads as out of the phase, or in it, by round-off. Measured with 0.001,
/// 0.002, 0.003 and 0.01 (voxel-faithful, 2026-12-05): all keep that sheet;
/// the liver's worst triangle 0.165 -> 0.167, 0.167, 0.167, 0.129, its voxel
/// centres 99.981% in their label -> 99.982% for all; 60 grains' centres
/// 99.975% -> 99.975, 99.974, 99.971, 99.961%. 0.002 keeps points twice as far
/// as the point location of the tests' checks looks beside them.
constexpr double kKeptMargin = 0.002;

/// The squared distance from p to triangle (a, b, c) (closest point by the
/// region of the triangle's plane p projects into).
double squared_distance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm(); // nearest a
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm(); // nearest b
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm(); // nearest c
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (ap - ab * (d1 / (d1 - d3))).squaredNorm(); // on ab
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (ap - ac * (d2 / (d2 - d6))).squaredNorm(); // on ac
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) // on bc
    return (bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))).squaredNorm();
  const double sum = va + vb + vc;
  if (!(sum > 0)) return std::min({ap.squaredNorm(), bp.squaredNorm(), cp.squaredNorm()}); // degenerate
  return (ap - ab * (vb / sum) - ac * (vc / sum)).squaredNorm(); // inside
}

/// Whether p lies nearer triangle (a, b, c) than kKeptMargin of its longest edge.
bool near_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return squared_distance(a, b, c, p) < kKeptMargin * kKeptMargin * longest;
}

/// The box [lo, hi] grown by kKeptMargin of its diagonal: every point
/// near_triangle() of a triangle inside the box lies in it.
std::array<Vec3, 2> with_margin(const Vec3& lo, const Vec3& hi) {
  const double grow = kKeptMargin * (hi - lo).norm();
  return {(lo.array() - grow).matrix(), (hi.array() + grow).matrix()};
}

/// The field's kept points in the box [lo, hi], in this thread's buffer (valid
/// until the thread asks again): the checks ask once per triangle or target.
const std::vector<Vec3>& kept_points_in(const PhaseField& field, const Vec3& lo, const Vec3& hi) {
  thread_local std::vector<Vec3> points;
  points.clear();
  field.kept_points(lo, hi, points);
  return points;
}

/// True when p lies strictly inside tetrahedron (a, b, c, d): on each face's
/// side of its opposite corner.
bool inside_tetrahedron(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& p) {
  const std::array<std::array<const Vec3*, 4>, 4> faces{{{&a, &b, &c, &d}, {&a, &b, &d, &c}, {&a, &c, &d, &b},
                                                         {&b, &c, &d, &a}}};
  return std::all_of(faces.begin(), faces.end(), [&](const auto& f) {
    const double corner = side(*f[0], *f[1], *f[2], *f[3]), point = side(*f[0], *f[1], *f[2], p);
    return (corner > 0 && point > 0) || (corner < 0 && point < 0);
  });
}

/// The solid angle of triangle (a, b, c) seen from p, signed: positive where p
/// lies behind it (against its normal), as from inside a closed surface whose
/// normals point out (Van Oosterom and Strackee's formula).
double solid_angle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  const Vec3 u = a - p, v = b - p, w = c - p;
  const double lu = u.norm(), lv = v.norm(), lw = w.norm();
  return 2 * std::atan2(u.dot(v.cross(w)), lu * lv * lw + u.dot(v) * lw + u.dot(w) * lv + v.dot(w) * lu);
}

} // namespace

std::vector<int32_t> merges_losing_kept_points(const NodeMesh& before, const NodeMesh& trial,
                                               std::span<const int32_t> into, std::span<const uint8_t> check,
                                               const PhaseField& field) {
  // Each target's triangles before (at it or at a node merged into it) and after (at it).
  std::vector<int32_t> target_of(before.num_nodes(), -1);
  for (size_t b = 0; b < into.size(); ++b)
    if (into[b] >= 0 && check[size_t(into[b])]) target_of[b] = target_of[size_t(into[b])] = into[b];
  // Each target's triangles of a mesh, in order: those of target a are
  // triangles[first[a]] to triangles[first[a + 1] - 1]. Counted and placed in
  // one pass each: sorting (target, triangle) pairs took 0.1 s of every check
  // of the remesh pass's batches on the voxel-faithful liver (1M triangles).
  struct AtTargets {
    std::vector<int32_t> first, triangles;
    std::span<const int32_t> of(int32_t a) const {
      return std::span(triangles).subspan(size_t(first[size_t(a)]), size_t(first[size_t(a) + 1] - first[size_t(a)]));
    }
  };
  // A triangle belongs to every target at one of its corners: a collapse's b
  // may neighbour another's a, so one triangle can lie at two targets, and
  // each target's old and new triangles close up only with all of theirs.
  auto gather = [&](const NodeMesh& m) {
    std::vector<std::array<int32_t, 3>> targets(m.num_triangles());
    parallel_for_each_index(targets.size(), [&](size_t t) {
      auto& at_t = targets[t];
      for (size_t k = 0; k < 3; ++k) { // the targets at its corners, each once, -1 elsewhere
        const int32_t a = target_of[size_t(m.triangles[t][k])];
        at_t[k] = std::find(at_t.begin(), at_t.begin() + ptrdiff_t(k), a) == at_t.begin() + ptrdiff_t(k) ? a : -1;
      }
    });
    AtTargets at{std::vector<int32_t>(target_of.size() + 1, 0), {}};
    for (const auto& at_t : targets)
      for (int32_t a : at_t)
        if (a >= 0) ++at.first[size_t(a) + 1];
    std::partial_sum(at.first.begin(), at.first.end(), at.first.begin());
    at.triangles.resize(size_t(at.first.back()));
    std::vector<int32_t> next(at.first.begin(), at.first.end() - 1);
    for (size_t t = 0; t < targets.size(); ++t)
      for (int32_t a : targets[t])
        if (a >= 0) at.triangles[size_t(next[size_t(a)]++)] = int32_t(t);
    return at;
  };
  const AtTargets old_at = gather(before), new_at = gather(trial);
  const std::vector<int32_t> targets =
      indices_where(target_of.size(), [&](size_t a) { return old_at.first[a + 1] > old_at.first[a]; });
  std::vector<uint8_t> loses(targets.size(), 0);
  detail::parallel_for_each_index(targets.size(), [&](size_t i) {
    const auto old_triangles = old_at.of(targets[i]), new_triangles = new_at.of(targets[i]);
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int32_t t : old_triangles)
      for (int32_t v : before.triangles[size_t(t)]) lo = lo.cwiseMin(before.points[size_t(v)]), hi = hi.cwiseMax(before.points[size_t(v)]);
    for (int32_t t : new_triangles)
      for (int32_t v : trial.triangles[size_t(t)]) lo = lo.cwiseMin(trial.points[size_t(v)]), hi = hi.cwiseMax(trial.points[size_t(v)]);
    const auto [near_lo, near_hi] = with_margin(lo, hi);
    const std::vector<Vec3>& points = kept_points_in(field, near_lo, near_hi);
    // Whether p lies near a triangle of `phase` among `triangles` of m.
    auto near = [](const NodeMesh& m, std::span<const int32_t> triangles, int32_t phase, const Vec3& p) {
      return std::any_of(triangles.begin(), triangles.end(), [&](int32_t t) {
        const PhasePair& pair = m.pairs[size_t(t)];
        const auto& tri = m.triangles[size_t(t)];
        return (pair[0] == phase || pair[1] == phase) &&
               near_triangle(m.points[size_t(tri[0])], m.points[size_t(tri[1])], m.points[size_t(tri[2])], p);
      });
    };
    // Winding number of the phase's boundary there, normals out of the phase.
    auto winding = [](const NodeMesh& m, std::span<const int32_t> triangles, int32_t phase, const Vec3& p) {
      double sum = 0;
      for (int32_t t : triangles) {
        const PhasePair& pair = m.pairs[size_t(t)];
        if (pair[0] != phase && pair[1] != phase) continue;
        const auto& tri = m.triangles[size_t(t)];
        // The normal points into pair[1]: out of pair[0].
        const double angle = solid_angle(m.points[size_t(tri[0])], m.points[size_t(tri[1])], m.points[size_t(tri[2])], p);
        sum += pair[0] == phase ? angle : -angle;
      }
      return sum / (4 * std::numbers::pi);
    };
    for (const Vec3& p : points) {
      const int32_t phase = field.kept_phase(p);
      if (winding(before, old_triangles, phase, p) - winding(trial, new_triangles, phase, p) > 0.5 ||
          (near(trial, new_triangles, phase, p) && !near(before, old_triangles, phase, p))) {
        loses[i] = 1;
        break;
      }
    }
  });
  std::vector<int32_t> out;
  for (size_t i = 0; i < targets.size(); ++i)
    if (loses[i]) out.push_back(targets[i]);
  return out;
}

bool flip_loses_kept_point(std::span<const Vec3> positions, const std::array<int32_t, 4>& quad,
                           const PhasePair& pair, const PhaseField& field) {
  const Vec3 &i = positions[size_t(quad[0])], &j = positions[size_t(quad[1])], &k = positions[size_t(quad[2])],
             &l = positions[size_t(quad[3])];
  // The face (i, j, k)'s normal points into the pair's second phase. A point
  // inside the tetrahedron lies on l's side of it, and the new triangles close
  // the tetrahedron on the other side: the flip takes the point into the other phase.
  const double l_side = side(i, j, k, l);
  const int32_t was_in = l_side > 0 ? pair[1] : pair[0];
  const auto [lo, hi] = with_margin(i.cwiseMin(j).cwiseMin(k).cwiseMin(l), i.cwiseMax(j).cwiseMax(k).cwiseMax(l));
  const std::vector<Vec3>& points = kept_points_in(field, lo, hi);
  return std::any_of(points.begin(), points.end(), [&](const Vec3& p) {
    if (l_side != 0 && inside_tetrahedron(i, j, k, l, p) && field.kept_phase(p) == was_in) return true;
    const bool comes_near = (near_triangle(i, l, k, p) || near_triangle(l, j, k, p)) && !near_triangle(i, j, k, p) &&
                            !near_triangle(i, l, j, p);
    if (!comes_near) return false;
    const int32_t phase = field.kept_phase(p);
    return phase == pair[0] || phase == pair[1];
  });
}

std::vector<int32_t> triangles_losing_kept_points(const InterfaceMesh& mesh, std::span<const Vec3> before,
                                                  std::span<const int32_t> moved, const PhaseField& field) {
  const auto& triangles = mesh.triangles();
  const auto& now = mesh.positions();
  std::vector<uint8_t> loses(moved.size(), 0);
  detail::parallel_for_each_index(moved.size(), [&](size_t i) {
    const auto t = size_t(moved[i]);
    const auto& tri = triangles[t];
    const Vec3 &a0 = before[size_t(tri[0])], &b0 = before[size_t(tri[1])], &c0 = before[size_t(tri[2])];
    const Vec3 &a1 = now[size_t(tri[0])], &b1 = now[size_t(tri[1])], &c1 = now[size_t(tri[2])];
    const auto [lo, hi] = with_margin(a0.cwiseMin(b0).cwiseMin(c0).cwiseMin(a1).cwiseMin(b1).cwiseMin(c1),
                                      a0.cwiseMax(b0).cwiseMax(c0).cwiseMax(a1).cwiseMax(b1).cwiseMax(c1));
    const std::vector<Vec3>& points = kept_points_in(field, lo, hi);
    const PhasePair pair = mesh.pair(OMesh::FaceHandle(int(t)));
    for (const Vec3& p : points) {
      // Geometry first: the phase is looked up only for a point the move took
      // across, or brought near the triangle.
      if (near_triangle(a1, b1, c1, p) && !near_triangle(a0, b0, c0, p)) {
        if (const int32_t phase = field.kept_phase(p); phase == pair[0] || phase == pair[1]) {
          loses[i] = 1;
          break;
        }
      }
      const double was = side(a0, b0, c0, p), is = side(a1, b1, c1, p);
      if (!((was > 0 && is < 0) || (was < 0 && is > 0)) || !(within(a0, b0, c0, p) || within(a1, b1, c1, p))) continue;
      const int32_t phase = field.kept_phase(p);
      // The normal points into the pair's second phase: a point of it that lay
      // above the triangle, or one of the first phase that lay below, went out.
      if ((phase == pair[1] && was > 0) || (phase == pair[0] && was < 0)) {
        loses[i] = 1;
        break;
      }
    }
  });
  std::vector<int32_t> out;
  for (size_t i = 0; i < loses.size(); ++i)
    if (loses[i]) out.push_back(moved[i]);
  return out;
}

} // namespace vm::detail
