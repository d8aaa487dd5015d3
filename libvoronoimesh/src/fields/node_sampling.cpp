#include "fields/node_sampling.hpp"

#include "voronoimesh/core/errors.hpp"

#include "fields/top_k.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace vm::detail {

namespace {

std::string point_text(const Vec3& x) {
  std::ostringstream s;
  s << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return s.str();
}

} // namespace

void check_phases_per_node(int k) {
  if (k < 1 || k > 16)
    throw InvalidInput(located("sample", "k (phases kept per node) must be between 1 and 16, got " + std::to_string(k)));
}

bool sample_node(const PhaseField& field, const GridSpec& grid, int64_t i, int64_t j, int64_t k,
                 std::span<int32_t> ids, std::span<double> vals, double& floor) {
  field.top_values(grid.node_position(i, j, k), ids, vals);
  if (!std::all_of(vals.begin(), vals.end(), [](double d) { return std::isfinite(d); })) return false;
  floor = floor_below(vals.front(), vals.back(), grid.h());
  return true;
}

void throw_not_finite(const PhaseField& field, const GridSpec& grid, int64_t n) {
  const auto nodes = grid.nodes();
  const Vec3 x = grid.node_position(n % nodes[0], (n / nodes[0]) % nodes[1], n / (nodes[0] * nodes[1]));
  std::vector<double> v(size_t(field.num_phases()));
  field.values(x, v);
  int i = 0;
  while (i + 1 < int(v.size()) && std::isfinite(v[size_t(i)])) ++i;
  const std::string what = std::isnan(v[size_t(i)]) ? "NaN" : "infinite";
  throw InvalidInput(located(field.describe_phase(i), "value is " + what + " at " + point_text(x)));
}

} // namespace vm::detail
