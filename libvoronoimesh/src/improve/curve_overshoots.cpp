/// @file improve/curve_overshoots.cpp
/// Finding curve ends past their quadruple point (improve/curve_overshoots.hpp).

#include "improve/curve_overshoots.hpp"

#include <algorithm>

namespace vm::detail {
namespace {

/// How far (in targets) Newton's method may take a point that merges curve nodes.
constexpr double kFarthestMove = 2.0;

/// True when the fourth phase of quadruple point `corner`, the one curve node
/// `n` lacks, is larger at n than the least of n's three.
bool past_the_point(const NodeRings& mesh, const PhaseField& field, int32_t corner, int32_t n) {
  const PhaseSet &point = mesh.phases()[size_t(corner)], &curve = mesh.phases()[size_t(n)];
  const Vec3& x = mesh.positions()[size_t(n)];
  const auto curve_end = curve.begin() + 3;
  const auto fourth = std::find_if(point.begin(), point.begin() + 4,
                                   [&](int32_t p) { return std::find(curve.begin(), curve_end, p) == curve_end; });
  double least = field.value(curve[0], x);
  for (int k = 1; k < 3; ++k) least = std::min(least, field.value(curve[size_t(k)], x));
  return field.value(*fourth, x) > least;
}

} // namespace

std::vector<PointMerge> overshooting_curve_ends(const NodeRings& mesh, std::span<const double> target,
                                                const PhaseField& field) {
  const auto& pos = mesh.positions();
  std::vector<PointMerge> found;
  for (int32_t q = 0; q < int32_t(mesh.num_nodes()); ++q) {
    if (!is_corner(mesh, q)) continue;
    PointMerge merge{q, {}, Vec3::Zero()};
    for (int32_t n : mesh.neighbours(q))
      if (is_curve_node(mesh, n) && mesh.constraints_within(n, q) && mesh.along_curve(q, n) &&
          past_the_point(mesh, field, q, n))
        merge.merged.push_back(n);
    if (merge.merged.empty()) continue;
    const double size = target[size_t(q)];
    const auto point = meeting_point(field, mesh.phases()[size_t(q)], pos[size_t(q)], size);
    const Box& box = mesh.mesh().domain;
    if (!point || (*point - pos[size_t(q)]).norm() > kFarthestMove * size ||
        !((point->array() > box.min.array()).all() && (point->array() < box.max.array()).all()))
      continue;
    merge.to = *point;
    std::sort(merge.merged.begin(), merge.merged.end());
    found.push_back(std::move(merge));
  }
  return found;
}

} // namespace vm::detail
