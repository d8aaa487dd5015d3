#include "voronoimesh/improve/project.hpp"

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include "core/parallel.hpp"
#include "core/text.hpp"
#include "improve/field_checks.hpp"

#include <Eigen/SVD>

#include <array>

namespace vm {

namespace {

/// Singular values below this share of the largest are taken as zero: the step
/// has no part along directions no pair's equation constrains (along a curve).
constexpr double kRankThreshold = 1e-3;

/// The least-norm step d with (grad_i - grad_j) . d = -(phi_i - phi_j) for
/// every pair, in the least-squares sense (ProjectParams::least_squares_from);
/// pairs whose gradients differ by no more than sqrt(min_gap2) are left out.
Vec3 least_squares_step(std::span<const double> phi, std::span<const Vec3> grad, double min_gap2) {
  const size_t n = phi.size();
  Eigen::Matrix<double, Eigen::Dynamic, 3> J(n * (n - 1) / 2, 3);
  Eigen::VectorXd r(n * (n - 1) / 2);
  Eigen::Index rows = 0;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const Vec3 dg = grad[i] - grad[j];
      if (dg.squaredNorm() <= min_gap2) continue;
      J.row(rows) = dg.transpose();
      r(rows++) = -(phi[i] - phi[j]);
    }
  if (rows == 0) return Vec3::Zero();
  Eigen::JacobiSVD<Eigen::Matrix<double, Eigen::Dynamic, 3>> svd(J.topRows(rows),
                                                                 Eigen::ComputeThinU | Eigen::ComputeThinV);
  svd.setThreshold(kRankThreshold);
  return svd.solve(r.head(rows));
}

/// The values and gradients of `phases` at x.
struct PhasesAt {
  std::array<double, kMaxPhasesAtNode> phi;
  std::array<Vec3, kMaxPhasesAtNode> grad;
  PhasesAt(const PhaseField& field, const Vec3& x, std::span<const int32_t> phases, const char* caller) {
    if (phases.size() > kMaxPhasesAtNode)
      throw InvalidInput(detail::cat(caller, ": ", phases.size(), " phases given, at most ", kMaxPhasesAtNode,
                                     " meet at a node"));
    for (size_t i = 0; i < phases.size(); ++i) {
      phi[i] = field.value(phases[i], x);
      grad[i] = field.gradient(phases[i], x);
    }
  }
};

} // namespace

Vec3 least_squares_step_on_faces(const PhaseField& field, const Vec3& x, std::span<const int32_t> phases,
                                 uint8_t box_faces) {
  const size_t n = phases.size();
  if (n < 2) return Vec3::Zero();
  PhasesAt at(field, x, phases, "least_squares_step_on_faces");
  // A held axis is left out of every gradient, so of every equation: the
  // least-norm step has no part along it.
  for (size_t i = 0; i < n; ++i) constrain_to_box(at.grad[i], box_faces);
  return least_squares_step({at.phi.data(), n}, {at.grad.data(), n}, 0);
}

Vec3 projection_step(const PhaseField& field, const Vec3& x, std::span<const int32_t> phases,
                     const ProjectParams& params) {
  const size_t n = phases.size();
  if (n < 2) return Vec3::Zero();
  const PhasesAt at(field, x, phases, "projection_step");
  const auto& [phi, grad] = at;
  const double min_gap2 = params.min_gradient_gap * params.min_gradient_gap;
  if (params.least_squares_from > 0 && n >= size_t(params.least_squares_from))
    return least_squares_step({phi.data(), n}, {grad.data(), n}, min_gap2);
  Vec3 p = Vec3::Zero();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const Vec3 dg = grad[i] - grad[j];
      const double d2 = dg.squaredNorm();
      if (d2 > min_gap2) p -= (phi[i] - phi[j]) / d2 * dg;
    }
  return p / double(n - 1);
}

Vec3 node_projection_step(const InterfaceMesh& mesh, const PhaseField& field, int32_t n, const Vec3& x,
                          const ProjectParams& params) {
  const PhaseSet& s = mesh.phases()[size_t(n)];
  std::array<int32_t, kMaxPhasesAtNode> ids;
  const int count = phase_count(s);
  for (int i = 0; i < count; ++i) ids[size_t(i)] = s[size_t(i)];
  Vec3 p = projection_step(field, x, {ids.data(), size_t(count)}, params);
  if (p.allFinite()) constrain_to_box(p, mesh.box_faces()[size_t(n)]); // else reported by the caller
  return p;
}

void add_projection(const InterfaceMesh& mesh, const PhaseField& field, const ProjectParams& params,
                    std::vector<Vec3>& delta) {
  std::vector<uint8_t> not_finite(mesh.num_nodes(), 0);
  detail::parallel_for_each_index(mesh.num_nodes(), [&](size_t v) {
    Vec3 p = node_projection_step(mesh, field, int32_t(v), mesh.positions()[v], params);
    if (!p.allFinite()) {
      not_finite[v] = 1;
      return;
    }
    if (params.max_step > 0) {
      const double longest = params.max_step * mean_edge_length_at(mesh, int32_t(v));
      if (p.squaredNorm() > longest * longest) p *= longest / p.norm();
    }
    delta[v] += p;
  });
  detail::refuse_not_finite(mesh, field, not_finite);
}

} // namespace vm
