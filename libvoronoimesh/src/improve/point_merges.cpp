/// @file improve/point_merges.cpp
/// What the remesh pass's merges into one point share (improve/point_merges.hpp).

#include "improve/point_merges.hpp"

#include <Eigen/LU>

#include <algorithm>

namespace vm::detail {
namespace {

/// Newton steps toward a meeting point of four phases, and how close (in
/// reaches) the last must come.
constexpr int kNewtonSteps = 30;
constexpr double kConverged = 1e-6;
/// Two points closer than this share of a target edge length are at one place
/// (off_other_points()).
constexpr double kOnePlace = 0.1;

} // namespace

std::vector<int32_t> nodes_around(const NodeRings& mesh, const PointMerge& merge) {
  std::vector<int32_t> around = merge.merged;
  around.push_back(merge.keep);
  for (size_t i = 0, nodes = around.size(); i < nodes; ++i) {
    const auto ring = mesh.neighbours(around[i]);
    around.insert(around.end(), ring.begin(), ring.end());
  }
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  return around;
}

std::vector<PointMerge> keep_apart(const NodeRings& mesh, std::vector<PointMerge> merges) {
  std::vector<uint8_t> taken(mesh.num_nodes(), 0);
  std::vector<PointMerge> kept;
  for (PointMerge& m : merges) {
    const std::vector<int32_t> around = nodes_around(mesh, m);
    if (std::any_of(around.begin(), around.end(), [&](int32_t n) { return taken[size_t(n)]; })) continue;
    for (int32_t n : around) taken[size_t(n)] = 1;
    kept.push_back(std::move(m));
  }
  std::sort(kept.begin(), kept.end(), [](const PointMerge& x, const PointMerge& y) { return x.keep < y.keep; });
  return kept;
}

std::vector<PointMerge> off_other_points(const NodeRings& mesh, std::vector<PointMerge> merges,
                                         std::span<const double> target) {
  if (merges.empty()) return merges;
  std::vector<int32_t> points; // nodes of four phases or more
  for (size_t n = 0; n < mesh.num_nodes(); ++n)
    if (phase_count(mesh.phases()[n]) >= 4) points.push_back(int32_t(n));
  auto shares_four = [&](int32_t a, int32_t b) { // four of a's phases are b's
    int shared = 0;
    for (int16_t p : mesh.phases()[size_t(a)]) shared += p >= 0 && mesh.has_phase(b, p);
    return shared >= 4;
  };
  auto onto_another = [&](const PointMerge& m) {
    const double reach = kOnePlace * target[size_t(m.keep)];
    return std::any_of(points.begin(), points.end(), [&](int32_t n) {
      return n != m.keep && std::find(m.merged.begin(), m.merged.end(), n) == m.merged.end() &&
             (mesh.positions()[size_t(n)] - m.to).squaredNorm() < reach * reach &&
             shares_four(m.keep, n);
    });
  };
  merges.erase(std::remove_if(merges.begin(), merges.end(), onto_another), merges.end());
  return merges;
}

std::optional<Vec3> meeting_point(const PhaseField& field, const PhaseSet& phases, Vec3 x, double reach) {
  for (int step = 0; step < kNewtonSteps; ++step) {
    Eigen::Matrix3d rows;
    Vec3 gap;
    const double phi0 = field.value(phases[0], x);
    const Vec3 grad0 = field.gradient(phases[0], x);
    for (int i = 1; i < 4; ++i) {
      rows.row(i - 1) = (field.gradient(phases[size_t(i)], x) - grad0).transpose();
      gap[i - 1] = phi0 - field.value(phases[size_t(i)], x);
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(rows);
    if (!lu.isInvertible()) return std::nullopt;
    Vec3 move = lu.solve(gap);
    if (!move.allFinite()) return std::nullopt;
    const double length = move.norm();
    if (length > reach) move *= reach / length;
    x += move;
    if (length < kConverged * reach) return x;
  }
  return std::nullopt;
}

} // namespace vm::detail
