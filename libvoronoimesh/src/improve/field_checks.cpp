/// @file improve/field_checks.cpp
/// refuse_not_finite() and require_phases() (field_checks.hpp).

#include "improve/field_checks.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <cmath>

namespace vm::detail {

void refuse_not_finite(const InterfaceMesh& mesh, const PhaseField& field, const std::vector<uint8_t>& flagged) {
  const auto first = std::find(flagged.begin(), flagged.end(), 1);
  if (first == flagged.end()) return;
  const size_t n = size_t(first - flagged.begin());
  const Vec3& x = mesh.positions()[n];
  const std::string at = cat(" at (", x.x(), ", ", x.y(), ", ", x.z(), ")");
  for (int16_t p : mesh.phases()[n]) {
    if (p < 0) break;
    const double v = field.value(p, x);
    if (!std::isfinite(v)) throw InvalidInput(located(field.describe_phase(p), cat("its value", at, " is ", v)));
    const Vec3 g = field.gradient(p, x);
    if (!g.allFinite())
      throw InvalidInput(located(field.describe_phase(p),
                                 cat("its gradient", at, " is (", g.x(), ", ", g.y(), ", ", g.z(), "), not finite")));
  }
  // Evaluated again, every function was finite: it is not a function of the point alone.
  throw InvalidInput(cat("the phase functions at node ", n, at, " gave a value or gradient that is not finite once, "
                         "and finite values when asked again"));
}

namespace {

void require_phase(const PhaseField& field, int32_t top) {
  if (top >= field.num_phases())
    throw InvalidInput(cat("the mesh has phase ", top, ", but its phase functions only ", field.num_phases(),
                           " phases (0 to ", field.num_phases() - 1, ")",
                           top == field.num_phases() ? ": a closed mesh's phase outside the box needs "
                                                       "with_outside_phase() or phases_of_mesh()"
                                                     : ": give the input the mesh was made from"));
}

} // namespace

void require_phases(const PhaseField& field, std::span<const PhasePair> pairs) {
  int32_t top = -1;
  for (const PhasePair& p : pairs) top = std::max({top, p[0], p[1]});
  require_phase(field, top);
}

void require_phases(const PhaseField& field, const InterfaceMesh& mesh) {
  int32_t top = -1;
  for (const PhaseSet& set : mesh.phases())
    for (const int16_t p : set) top = std::max(top, int32_t(p));
  require_phase(field, top);
}

} // namespace vm::detail
