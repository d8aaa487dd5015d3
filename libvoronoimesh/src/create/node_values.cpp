#include "create/node_values.hpp"

#include "core/parallel.hpp"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace vm::detail {

namespace {

/// splitmix64's finaliser: well-spread bits from a node and phase.
uint64_t mix_bits(uint64_t x) {
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

} // namespace

std::array<double, 2> lattice_value_range(const SampledField& field, const TetLattice& lattice,
                                          std::array<int32_t, 2> layers) {
  using Range = std::array<double, 2>;
  const Range none{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  return detail::parallel_reduce(
      tbb::blocked_range<int64_t>(0, lattice.num_node_rows(), 16), none,
      [&](const tbb::blocked_range<int64_t>& rows, Range range) {
        for (int64_t r = rows.begin(); r < rows.end(); ++r) {
          const TetLattice::NodeRow row = lattice.node_row(r);
          if (row.z < layers[0] || row.z > layers[1]) continue;
          for (int32_t x = 0; x < row.count; ++x) {
            const SampledField::NodeSamples at = field.at(row.x0 + int64_t(row.step) * x, row.y, row.z);
            // The floor is below every stored value of its node, and slot 0 is the node's largest.
            range = {std::min(range[0], at.floor), std::max(range[1], at.values[0])};
          }
        }
        return range;
      },
      [](const Range& a, const Range& b) { return Range{std::min(a[0], b[0]), std::max(a[1], b[1])}; });
}

NodeValues::NodeValues(const SampledField& field, const TetLattice& lattice, double snap_eps, double untie_eps,
                       const std::vector<RepairLevel>* repair, const NodeScope* scope)
    : window_(scope ? scope->window : lattice.window(0, field.grid().cells[2])), k_(field.k()) {
  const GridSpec& grid = field.grid();
  const int64_t n_nodes = window_.size();
  ids_.reset(new int32_t[size_t(n_nodes) * size_t(k_)]);
  values_.reset(new int32_t[size_t(n_nodes) * size_t(k_)]);
  floor_.reset(new int32_t[size_t(n_nodes)]);
  label_.reset(new int32_t[size_t(n_nodes)]);
  snapped_.reset(new uint8_t[size_t(n_nodes)]);

  // One global affine map to integers, so equal values stay equal everywhere
  // and every node's numbers mean the same thing in every tetrahedron.
  const std::array<double, 2> whole =
      scope ? std::array{scope->min_value, scope->max_value} : lattice_value_range(field, lattice, {0, grid.cells[2]});
  lo_ = whole[0];
  const double range = whole[1] - lo_;
  scale_ = range > 0 ? std::ldexp(1.0, kValueBits) / range : 1.0;
  eps_ = std::llround(snap_eps * scale_);
  // Small against the grid yet far above round-off, so that the caps it opens
  // around a node are triangles validate() takes for non-degenerate.
  untie_ = std::clamp<int64_t>(std::llround(untie_eps * scale_), 1024, int64_t(1) << 19);

  snapped_nodes_ = detail::parallel_reduce(
      tbb::blocked_range<int64_t>(0, lattice.num_node_rows(), 16), uint64_t(0),
      [&](const tbb::blocked_range<int64_t>& rows, uint64_t snapped) {
        for (int64_t r = rows.begin(); r < rows.end(); ++r) {
          const TetLattice::NodeRow row = lattice.node_row(r);
          if (row.z < window_.z0 || row.z > window_.z1) continue;
          for (int32_t x = 0; x < row.count; ++x) {
            const int64_t id = row.first_id + x, n = window_.local(id);
            snapped += fill(field.at(row.x0 + int64_t(row.step) * x, row.y, row.z), id, n,
                            repair ? (*repair)[size_t(n)] : kSnap);
          }
        }
        return snapped;
      },
      std::plus<>());
}

void NodeValues::redo(const SampledField& field, const TetLattice& lattice, const std::vector<RepairLevel>& repair,
                      std::span<const int64_t> nodes) {
  // Snapped nodes gained minus those lost: each node is counted once before and once after.
  const int64_t gained = detail::parallel_reduce(
      tbb::blocked_range<size_t>(0, nodes.size(), 256), int64_t(0),
      [&](const tbb::blocked_range<size_t>& r, int64_t sum) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
          const int64_t id = nodes[i], n = window_.local(id);
          const GridPoint p = lattice.grid_point(id);
          sum -= snapped_[n];
          sum += fill(field.at(p[0], p[1], p[2]), id, n, repair[size_t(n)]);
        }
        return sum;
      },
      std::plus<>());
  snapped_nodes_ = uint64_t(int64_t(snapped_nodes_) + gained);
}

bool NodeValues::fill(const SampledField::NodeSamples& at, int64_t id, int64_t n, RepairLevel level) {
  auto quantize = [&](double v) { return int32_t((v - lo_) * scale_ + 0.5); }; // v >= lo_: rounds to nearest
  const auto ids = at.ids;
  const auto vals = at.values;
  std::copy(ids.begin(), ids.end(), ids_.get() + n * k_);
  int32_t* q = values_.get() + n * k_;
  for (int s = 0; s < k_; ++s) q[s] = quantize(vals[s]);
  floor_[n] = quantize(at.floor);
  // Pairwise snapping in phase-id order (Algorithm 2, line 1): a later
  // phase takes the earlier phase's value, so earlier snaps are not undone.
  int32_t by_id[16];
  for (int s = 0; s < k_; ++s) { // slots by increasing phase id (k_ <= 16)
    int e = s;
    for (; e > 0 && ids[by_id[e - 1]] > ids[s]; --e) by_id[e] = by_id[e - 1];
    by_id[e] = s;
  }
  if (level >= kFirstUntie) {
    // A phase with r lower ids tied with it drops by r untie, so the
    // symbolic order of tied phases survives, plus the pseudo-random
    // part below untie that every phase drops by. Stored phases stay
    // above the floor (unstored phases stay below it): one that would
    // reach it rises by its random part instead.
    int32_t tied_below[16] = {};
    for (int a = 0; a < k_; ++a)
      for (int b = a + 1; b < k_; ++b) tied_below[b] += q[by_id[a]] == q[by_id[b]];
    for (int b = 0; b < k_; ++b) {
      const uint64_t draw = mix_bits(uint64_t(id) * 0x9E3779B97F4A7C15ull ^ uint64_t(ids[by_id[b]]) ^
                                     uint64_t(level) << 56);
      const int64_t jitter = 1 + int64_t(draw % uint64_t(untie_));
      const int64_t lowered = int64_t(q[by_id[b]]) - untie_ * tied_below[b] - jitter;
      const int64_t raised = std::min(int64_t(q[by_id[b]]) + jitter, int64_t(1) << kValueBits);
      q[by_id[b]] = int32_t(lowered > floor_[n] ? lowered : raised);
    }
  }
  bool changed = false;
  if (eps_ > 0 && level == kSnap)
    for (int a = 0; a < k_; ++a)
      for (int b = a + 1; b < k_; ++b) {
        const int32_t vi = q[by_id[a]];
        int32_t& vj = q[by_id[b]];
        if (vi != vj && std::llabs(int64_t(vi) - vj) < eps_) {
          vj = vi;
          changed = true;
        }
      }
  snapped_[n] = changed;
  int best = 0;
  for (int s = 1; s < k_; ++s)
    if (beats(q[s], ids[s], q[best], ids[best])) best = s;
  label_[n] = ids[best];
  return changed;
}

} // namespace vm::detail
