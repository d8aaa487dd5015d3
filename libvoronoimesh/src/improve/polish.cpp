/// @file improve/polish.cpp
/// The polish pass's moves (improve/polish.hpp).

#include "voronoimesh/improve/polish.hpp"

#include "voronoimesh/improve/clamp.hpp"
#include "voronoimesh/improve/project.hpp"
#include "voronoimesh/improve/smooth.hpp"
#include "voronoimesh/mesh/triangle_quality.hpp"

#include "core/indices_where.hpp"
#include "core/parallel.hpp"
#include "improve/tangential.hpp"
#include "mesh/node_rings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>

namespace vm {
namespace {

/// Trial moves per node: directions in the tangent plane (a curve node tries
/// the two along its curve) times steps, fractions of the mean edge at it.
constexpr int kDirections = 8;
constexpr std::array<double, 4> kSteps{0.4, 0.2, 0.1, 0.05};
/// Newton steps (eq. 4) that take a trial back to the node's surface or curve:
/// the pass may be the last to move nodes in a run.
constexpr int kNewtonSteps = 3;
/// A trial must beat the node's smallest quality by this much.
constexpr double kGain = 1e-3;
/// No triangle of a moved node may turn by this much (cos 60 degrees).
constexpr double kMinTurnCosine = 0.5;

struct Fan {
  std::vector<std::array<int32_t, 2>> far; ///< (a, b) of each triangle (n, a, b) at the node, in orientation order
  std::vector<Vec3> normal;                ///< each triangle's normal where the node is
};

Fan fan_of(const InterfaceMesh& mesh, int32_t n) {
  Fan fan;
  const auto& p = mesh.positions();
  const Vec3& x = p[size_t(n)];
  mesh.for_each_triangle_at(n, [&](int32_t a, int32_t b) {
    fan.far.push_back({a, b});
    fan.normal.push_back((p[size_t(a)] - x).cross(p[size_t(b)] - x));
  });
  return fan;
}

/// The smallest quality of the fan with the node at y, or -1 where a triangle
/// would turn by kMinTurnCosine or more (or lose its area).
double fan_quality(std::span<const Vec3> p, const Fan& fan, const Vec3& y) {
  double worst = 1;
  for (size_t i = 0; i < fan.far.size(); ++i) {
    const Vec3 &a = p[size_t(fan.far[i][0])], &b = p[size_t(fan.far[i][1])];
    const Vec3 normal = (a - y).cross(b - y);
    if (!(normal.dot(fan.normal[i]) > kMinTurnCosine * normal.norm() * fan.normal[i].norm())) return -1;
    worst = std::min(worst, triangle_quality(y, a, b));
  }
  return worst;
}

/// True when the move of node n from x to y goes at most half its distance
/// towards each box face it is not on (the clamp pass's rule, box_step() with
/// its factor 1/2), so that no node leaves the box.
bool stays_in_box(const InterfaceMesh& mesh, int32_t n, const Vec3& x, const Vec3& y) {
  return box_step(y - x, x, mesh.domain(), mesh.box_faces()[size_t(n)]) >= 2;
}

/// The directions a node of `order` 2 or 3 tries at x, tangential to its constraints.
std::vector<Vec3> trial_directions(const InterfaceMesh& mesh, const PhaseField& field, int32_t n, const Vec3& x,
                                   const Fan& fan) {
  std::vector<Vec3> directions;
  if (detail::constraint_order(mesh, n) == 3) {
    // An axis kept on the curve is the curve's tangent: of the three, the one
    // least across the curve.
    Vec3 tangent = Vec3::Zero();
    for (int a = 0; a < 3; ++a) {
      Vec3 d = Vec3::Unit(a);
      if (!detail::keep_tangential(mesh, field, n, x, d)) return directions;
      if (d.norm() > tangent.norm()) tangent = d;
    }
    constrain_to_box(tangent, mesh.box_faces()[size_t(n)]); // exactly: Gram-Schmidt leaves round-off
    if (!(tangent.norm() > 1e-6)) return directions;
    tangent.normalize();
    return {tangent, -tangent};
  }
  // A surface node (order 2, a box face's too): an orthonormal pair spanning its
  // tangent plane, from two directions across the fan's normal kept on the surface.
  Vec3 normal = Vec3::Zero();
  for (const Vec3& v : fan.normal) normal += v;
  if (!(normal.norm() > 0)) return directions;
  normal.normalize();
  Vec3 u = normal.unitOrthogonal(), v = normal.cross(u);
  if (!detail::keep_tangential(mesh, field, n, x, u) || !detail::keep_tangential(mesh, field, n, x, v))
    return directions;
  if (!(u.norm() > 1e-6)) return directions;
  u.normalize();
  v -= v.dot(u) * u;
  if (!(v.norm() > 1e-6)) return directions;
  v.normalize();
  for (int k = 0; k < kDirections; ++k) {
    const double angle = 2 * std::numbers::pi * k / kDirections;
    directions.push_back(std::cos(angle) * u + std::sin(angle) * v);
  }
  return directions;
}

} // namespace

size_t add_polish_moves(const InterfaceMesh& mesh, const PhaseField& field, const PolishParams& params,
                        std::vector<Vec3>& delta) {
  const auto& triangles = mesh.triangles();
  const auto& quality = mesh.qualities();
  const auto& p = mesh.positions();
  const std::vector<int32_t> bad =
      detail::indices_where(triangles.size(), [&](size_t t) { return quality[t] < params.below; });
  // The candidates: movable corners of bad triangles (constraint order 2 or 3:
  // box faces count, a closed mesh's outside phase does not), worst triangle
  // first (ties by node).
  std::vector<std::pair<double, int32_t>> candidates;
  for (int32_t t : bad)
    for (int32_t n : triangles[size_t(t)]) {
      const int order = detail::constraint_order(mesh, n);
      if (order == 2 || order == 3) candidates.emplace_back(quality[size_t(t)], n);
    }
  std::sort(candidates.begin(), candidates.end());
  // No two taken nodes share a triangle: each is judged with its neighbours
  // where they are, which they stay if the crossing guard puts one back.
  std::vector<uint8_t> blocked(mesh.num_nodes(), 0);
  std::vector<int32_t> taken;
  for (const auto& [q, n] : candidates) {
    if (blocked[size_t(n)]) continue;
    taken.push_back(n);
    blocked[size_t(n)] = 1;
    for (int32_t m : mesh.neighbours(n)) blocked[size_t(m)] = 1;
  }
  std::vector<Vec3> move(taken.size(), Vec3::Zero());
  detail::parallel_for_each_index(taken.size(), [&](size_t i) {
    const int32_t n = taken[i];
    const Vec3& x = p[size_t(n)];
    const Fan fan = fan_of(mesh, n);
    const double mean_edge = mean_edge_length_at(mesh, n);
    // Trials in the tangent plane; only the best is taken back onto the
    // interface (a second-order change), and must still beat where the node is.
    const double now = fan_quality(p, fan, x);
    double best = now + kGain;
    Vec3 best_y = x;
    for (const Vec3& d : trial_directions(mesh, field, n, x, fan))
      for (double step : kSteps) {
        const Vec3 y = x + step * mean_edge * d;
        if (!stays_in_box(mesh, n, x, y)) continue;
        if (const double q = fan_quality(p, fan, y); q > best) best = q, best_y = y;
      }
    if (best_y == x) return;
    for (int newton = 0; newton < kNewtonSteps; ++newton) best_y += node_projection_step(mesh, field, n, best_y);
    if (best_y.allFinite() && stays_in_box(mesh, n, x, best_y) && fan_quality(p, fan, best_y) > now + kGain)
      move[i] = best_y - x;
  });
  size_t moved = 0;
  for (size_t i = 0; i < taken.size(); ++i)
    if (!move[i].isZero(0)) delta[size_t(taken[i])] += move[i], ++moved;
  return moved;
}

} // namespace vm
