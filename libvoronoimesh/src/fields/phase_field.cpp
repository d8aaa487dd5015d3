#include "voronoimesh/fields/phase_field.hpp"

#include "fields/top_k.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

namespace vm {

std::string PhaseField::describe_phase(int i) const { return "phase " + phase_name(i); }

void PhaseField::top_values(const Vec3& x, std::span<int32_t> ids, std::span<double> vals) const {
  // Scratch space per thread: this runs once per grid node. A call nested in
  // another (a field whose values() asks another field's top values, as the
  // phase outside a closed mesh's box does) has its own: sharing it, the inner
  // call shrank the outer's arrays to its own phases, and the outside phase was
  // never among the top.
  thread_local int depth = 0;
  thread_local std::vector<double> outer_v;
  thread_local std::vector<int32_t> outer_order;
  std::vector<double> nested_v;
  std::vector<int32_t> nested_order;
  std::vector<double>& v = depth == 0 ? outer_v : nested_v;
  std::vector<int32_t>& order = depth == 0 ? outer_order : nested_order;
  ++depth;
  struct Leave {
    ~Leave() { --depth; }
  } leave;
  v.resize(size_t(num_phases()));
  order.resize(v.size());
  values(x, v);
  if (const auto bad = std::find_if(v.begin(), v.end(), [](double d) { return !std::isfinite(d); }); bad != v.end()) {
    ids[0] = int32_t(bad - v.begin());
    vals[0] = *bad;
    return;
  }
  std::iota(order.begin(), order.end(), 0);
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(ids.size()), order.end(),
                    [&](int32_t a, int32_t b) { return detail::ranks_before(v[size_t(a)], a, v[size_t(b)], b); });
  for (size_t slot = 0; slot < ids.size(); ++slot) {
    ids[slot] = order[slot];
    vals[slot] = v[size_t(order[slot])];
  }
}

bool PhaseField::same_top_values([[maybe_unused]] const Vec3& lo, [[maybe_unused]] const Vec3& hi) const {
  return false;
}

void PhaseField::kept_points([[maybe_unused]] const Vec3& lo, [[maybe_unused]] const Vec3& hi,
                             [[maybe_unused]] std::vector<Vec3>& out) const {}

int32_t PhaseField::kept_phase(const Vec3& p) const {
  std::array<int32_t, 1> id;
  std::array<double, 1> value;
  top_values(p, id, value);
  return id[0];
}

} // namespace vm
