#include "voronoimesh/fields/sampled_field.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/atomic_lowest.hpp"
#include "core/parallel.hpp"
#include "fields/node_sampling.hpp"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <span>

namespace vm {

namespace {

void check_grid(const GridSpec& grid) {
  for (int a = 0; a < 3; ++a) {
    if (grid.cells[a] < 1)
      throw InvalidInput(located("grid", "cells per axis must be at least 1, got " +
                                             std::to_string(grid.cells[a])));
    if (!(grid.domain.min[a] < grid.domain.max[a]))
      throw InvalidInput(located("grid", "domain min must be below max on every axis"));
  }
}

} // namespace

SampledField SampledField::sample(const PhaseField& field, const GridSpec& grid, int k) {
  return sample(field, grid, k, {0, grid.cells[2]});
}

SampledField SampledField::sample(const PhaseField& field, const GridSpec& grid, int k,
                                  std::array<int32_t, 2> layers) {
  return sample_nodes(field, grid, k, layers, SampledNodes::all);
}

SampledField SampledField::sample(const PhaseField& field, const GridSpec& grid, int k, SampledNodes nodes) {
  return sample_nodes(field, grid, k, {0, grid.cells[2]}, nodes);
}

SampledField SampledField::sample_nodes(const PhaseField& field, const GridSpec& grid, int k,
                                        std::array<int32_t, 2> layers, SampledNodes which) {
  detail::check_phases_per_node(k);
  check_grid(grid);
  if (layers[0] < 0 || layers[1] > grid.cells[2] || layers[0] > layers[1])
    throw InvalidInput(located("sample", "layers " + std::to_string(layers[0]) + ".." + std::to_string(layers[1]) +
                                             " are not within the grid's 0.." + std::to_string(grid.cells[2])));
  if (which == SampledNodes::bcc)
    for (int a = 0; a < 3; ++a)
      if (grid.cells[a] % 2 != 0)
        throw InvalidInput(located("sample", "the bcc lattice's nodes need an even number of grid cells per axis, got " +
                                                 std::to_string(grid.cells[a])));
  const int n_phases = field.num_phases();
  if (n_phases < 1) throw InvalidInput(located("sample", "the field has no phases"));

  SampledField s;
  s.grid_ = grid;
  s.num_phases_ = n_phases;
  s.k_ = std::min(k, n_phases);
  s.nodes_ = which;
  const size_t kk = size_t(s.k_);
  const auto nodes = grid.nodes();
  s.layers_ = layers;
  s.first_node_ = grid.node_index(0, 0, layers[0]);
  const bool bcc = which == SampledNodes::bcc;
  const int64_t count = bcc ? count_nodes(grid, which) : (layers[1] - layers[0] + 1) * nodes[0] * nodes[1];
  s.ids_.resize(size_t(count) * kk);
  s.values_.resize(size_t(count) * kk);
  s.floor_.resize(size_t(count));
  // Lowest node index holding a NaN or infinity. Nodes above it are skipped and
  // nodes below it are all visited, so the error reported does not depend on
  // scheduling.
  std::atomic<int64_t> first_bad{std::numeric_limits<int64_t>::max()};

  // One task range = rows of nodes along x; every node is written by one task
  // only. With bcc, rows whose y and z differ in parity hold no node, and a row
  // holds every second node, starting at its parity.
  const int64_t first_row = layers[0] * nodes[1], end_row = (layers[1] + 1) * nodes[1];
  detail::parallel_for(tbb::blocked_range<int64_t>(first_row, end_row), [&](const auto& rows) {
    for (int64_t row = rows.begin(); row != rows.end(); ++row) {
      const int64_t j = row % nodes[1], kz = row / nodes[1];
      if (bcc && (j & 1) != (kz & 1)) continue;
      const int64_t step = bcc ? 2 : 1;
      for (int64_t i = bcc ? (j & 1) : 0; i < nodes[0]; i += step) {
        const int64_t n = grid.node_index(i, j, kz);
        if (n - s.first_node_ > first_bad.load(std::memory_order_relaxed)) return;
        const int64_t at = s.slot(i, j, kz);
        const std::span<int32_t> ids{&s.ids_[size_t(at) * kk], kk};
        const std::span<double> vals{&s.values_[size_t(at) * kk], kk};
        if (!detail::sample_node(field, grid, i, j, kz, ids, vals, s.floor_[size_t(at)])) {
          detail::lower_atomically(first_bad, n - s.first_node_);
          return;
        }
      }
    }
  });
  if (const int64_t bad = first_bad.load(); bad != std::numeric_limits<int64_t>::max())
    detail::throw_not_finite(field, grid, bad + s.first_node_);
  s.find_range();
  return s;
}

int64_t SampledField::count_nodes(const GridSpec& grid, SampledNodes nodes) {
  const auto n = grid.nodes();
  if (nodes == SampledNodes::all) return n[0] * n[1] * n[2];
  // (cells/2 + 1)^3 even nodes, (cells/2)^3 odd ones (cells = nodes - 1, even).
  return (n[0] / 2 + 1) * (n[1] / 2 + 1) * (n[2] / 2 + 1) + (n[0] / 2) * (n[1] / 2) * (n[2] / 2);
}

int64_t SampledField::bcc_slot(int64_t n) const {
  const auto nodes = grid_.nodes();
  return slot(n % nodes[0], n / nodes[0] % nodes[1], n / (nodes[0] * nodes[1]));
}

SampledField SampledField::from_samples(const GridSpec& grid, int num_phases, int k, std::array<int32_t, 2> layers,
                                        std::vector<int32_t> ids, std::vector<double> values,
                                        std::vector<double> floors) {
  check_grid(grid);
  const auto nodes = grid.nodes();
  const int64_t count = (layers[1] - layers[0] + 1) * nodes[0] * nodes[1];
  if (k < 1 || layers[0] < 0 || layers[1] > grid.cells[2] || layers[0] > layers[1] ||
      ids.size() != size_t(count) * size_t(k) || values.size() != ids.size() || floors.size() != size_t(count))
    throw InvalidInput(located("samples", "the arrays do not match layers " + std::to_string(layers[0]) + ".." +
                                              std::to_string(layers[1]) + " with " + std::to_string(k) +
                                              " phases per node"));
  SampledField s;
  s.grid_ = grid;
  s.num_phases_ = num_phases;
  s.k_ = k;
  s.layers_ = layers;
  s.first_node_ = grid.node_index(0, 0, layers[0]);
  s.ids_ = std::move(ids);
  s.values_ = std::move(values);
  s.floor_ = std::move(floors);
  s.find_range();
  return s;
}

void SampledField::find_range() {
  // The floor is below every stored value of its node, and slot 0 is the node's largest.
  min_value_ = *std::min_element(floor_.begin(), floor_.end());
  max_value_ = values_[0];
  for (size_t n = 1; n < floor_.size(); ++n) max_value_ = std::max(max_value_, values_[n * size_t(k_)]);
}

double SampledField::value(int64_t n, int32_t phase) const {
  const auto stored = ids(n);
  for (size_t slot = 0; slot < stored.size(); ++slot)
    if (stored[slot] == phase) return values(n)[slot];
  return floor_value(n);
}

} // namespace vm
