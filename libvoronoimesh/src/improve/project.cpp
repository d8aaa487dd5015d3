#include "voronoimesh/improve/project.hpp"

#include "voronoimesh/improve/smooth.hpp"

#include "core/parallel.hpp"
#include "improve/field_checks.hpp"

#include <array>

namespace vm {

Vec3 projection_step(const PhaseField& field, const Vec3& x, std::span<const int32_t> phases,
                     const ProjectParams& params) {
  const size_t n = phases.size();
  if (n < 2) return Vec3::Zero();
  std::array<double, 8> phi;
  std::array<Vec3, 8> grad;
  for (size_t i = 0; i < n; ++i) {
    phi[i] = field.value(phases[i], x);
    grad[i] = field.gradient(phases[i], x);
  }
  const double min_gap2 = params.min_gradient_gap * params.min_gradient_gap;
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
  std::array<int32_t, 8> ids;
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
    const Vec3 p = node_projection_step(mesh, field, int32_t(v), mesh.positions()[v], params);
    if (!p.allFinite()) {
      not_finite[v] = 1;
      return;
    }
    delta[v] += p;
  });
  detail::refuse_not_finite(mesh, field, not_finite);
}

} // namespace vm
