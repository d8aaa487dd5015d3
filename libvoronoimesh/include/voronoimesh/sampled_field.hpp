#pragma once
/// @file sampled_field.hpp
/// A phase field sampled on a Cartesian grid keeping only the K largest phases
/// per grid node, so memory is O(nodes x K) whatever the number of phases.

#include "voronoimesh/field.hpp"
#include "voronoimesh/types.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vm {

/// Top-K samples of N phase functions on the nodes of a grid.
class SampledField {
public:
  /// Samples `field` at every node of `grid` in parallel, keeping the `k` largest
  /// phases per node (ties: lower phase id first). Throws InvalidInput if a value
  /// is NaN or infinite (naming the phase and the point), or if k is not in
  /// [1, 16] (more is never needed: few phases compete at any one point).
  static SampledField sample(const PhaseField& field, const GridSpec& grid, int k = 4);

  const GridSpec& grid() const { return grid_; }  ///< the grid sampled
  int num_phases() const { return num_phases_; } ///< N, all phases of the field
  /// Slots per node (min(k, N)).
  int k() const { return k_; }

  /// Phase ids stored at node n, sorted by decreasing value (k() entries).
  std::span<const int32_t> ids(int64_t n) const { return {ids_.data() + n * k_, size_t(k_)}; }
  /// Values matching ids(n).
  std::span<const double> values(int64_t n) const { return {values_.data() + n * k_, size_t(k_)}; }
  /// The value every phase not stored at node n takes there: below all stored
  /// values by a margin, and a function of the node alone, so the piecewise-linear
  /// field stays one consistent field (DESIGN.md, "Field").
  double floor_value(int64_t n) const { return floor_[n]; }
  /// Value of phase `phase` at node n (stored value or floor_value).
  double value(int64_t n, int32_t phase) const;

  /// Smallest and largest value held (floor values included).
  double min_value() const { return min_value_; }
  double max_value() const { return max_value_; }

private:
  GridSpec grid_;
  int num_phases_ = 0;
  int k_ = 0;
  std::vector<int32_t> ids_;
  std::vector<double> values_;
  std::vector<double> floor_;
  double min_value_ = 0, max_value_ = 0;
};

} // namespace vm
