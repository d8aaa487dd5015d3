#include "voronoimesh/sampled_field.hpp"

#include "voronoimesh/errors.hpp"

#include "detail/parallel.hpp"
#include "detail/top_k.hpp"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <span>
#include <sstream>

namespace vm {

namespace {

std::string point_text(const Vec3& x) {
  std::ostringstream s;
  s << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return s.str();
}

void check_grid(const GridSpec& grid) {
  for (int a = 0; a < 3; ++a) {
    if (grid.cells[a] < 1)
      throw InvalidInput(located("grid", "cells per axis must be at least 1, got " +
                                             std::to_string(grid.cells[a])));
    if (!(grid.domain.min[a] < grid.domain.max[a]))
      throw InvalidInput(located("grid", "domain min must be below max on every axis"));
  }
}

/// The error for the first non-finite value at node `n`: evaluating again is
/// cheaper than carrying the phase out of the parallel loop, and only happens once.
[[noreturn]] void throw_not_finite(const PhaseField& field, const GridSpec& grid, int64_t n) {
  const auto nodes = grid.nodes();
  const Vec3 x = grid.node_position(n % nodes[0], (n / nodes[0]) % nodes[1], n / (nodes[0] * nodes[1]));
  std::vector<double> v(size_t(field.num_phases()));
  field.values(x, v);
  int i = 0;
  while (i + 1 < int(v.size()) && std::isfinite(v[size_t(i)])) ++i;
  const std::string what = std::isnan(v[size_t(i)]) ? "NaN" : "infinite";
  throw InvalidInput(located("phase " + field.phase_name(i), "value is " + what + " at " + point_text(x)));
}

/// The node's floor value, from its kept values (largest first).
double node_floor(std::span<const double> vals, double h) {
  return detail::floor_below(vals.front(), vals.back(), h);
}

} // namespace

SampledField SampledField::sample(const PhaseField& field, const GridSpec& grid, int k) {
  if (k < 1 || k > 16)
    throw InvalidInput(located("sample", "k (phases kept per node) must be between 1 and 16, got " + std::to_string(k)));
  check_grid(grid);
  const int n_phases = field.num_phases();
  if (n_phases < 1) throw InvalidInput(located("sample", "the field has no phases"));

  SampledField s;
  s.grid_ = grid;
  s.num_phases_ = n_phases;
  s.k_ = std::min(k, n_phases);
  const size_t kk = size_t(s.k_);
  const int64_t count = grid.node_count();
  s.ids_.resize(size_t(count) * kk);
  s.values_.resize(size_t(count) * kk);
  s.floor_.resize(size_t(count));
  const double h = grid.h();
  const auto nodes = grid.nodes();

  // Lowest node index holding a NaN or infinity. Nodes above it are skipped and
  // nodes below it are all visited, so the error reported does not depend on
  // scheduling.
  std::atomic<int64_t> first_bad{std::numeric_limits<int64_t>::max()};

  // One task range = rows of nodes along x; every node is written by one task only.
  detail::parallel_for(tbb::blocked_range<int64_t>(0, nodes[1] * nodes[2]), [&](const auto& rows) {
    for (int64_t row = rows.begin(); row != rows.end(); ++row) {
      const int64_t j = row % nodes[1], kz = row / nodes[1];
      for (int64_t i = 0; i < nodes[0]; ++i) {
        const int64_t n = grid.node_index(i, j, kz);
        if (n > first_bad.load(std::memory_order_relaxed)) return;
        const std::span<int32_t> ids{&s.ids_[size_t(n) * kk], kk};
        const std::span<double> vals{&s.values_[size_t(n) * kk], kk};
        field.top_values(grid.node_position(i, j, kz), ids, vals);
        if (!std::all_of(vals.begin(), vals.end(), [](double d) { return std::isfinite(d); })) {
          int64_t seen = first_bad.load();
          while (n < seen && !first_bad.compare_exchange_weak(seen, n)) {}
          return;
        }
        s.floor_[size_t(n)] = node_floor(vals, h);
      }
    }
  });
  if (const int64_t bad = first_bad.load(); bad != std::numeric_limits<int64_t>::max())
    throw_not_finite(field, grid, bad);

  // The floor is below every stored value of its node, and slot 0 is the node's largest.
  s.min_value_ = *std::min_element(s.floor_.begin(), s.floor_.end());
  s.max_value_ = s.values_[0];
  for (int64_t n = 1; n < count; ++n) s.max_value_ = std::max(s.max_value_, s.values_[size_t(n) * kk]);
  return s;
}

double SampledField::value(int64_t n, int32_t phase) const {
  const auto stored = ids(n);
  for (size_t slot = 0; slot < stored.size(); ++slot)
    if (stored[slot] == phase) return values_[size_t(n) * size_t(k_) + slot];
  return floor_[size_t(n)];
}

} // namespace vm
