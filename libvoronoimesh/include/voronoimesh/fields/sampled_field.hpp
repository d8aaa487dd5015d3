#pragma once
/// @file fields/sampled_field.hpp
/// A phase field sampled on a Cartesian grid keeping only the K largest phases
/// per grid node, so memory is O(nodes x K) whatever the number of phases.

#include "voronoimesh/core/types.hpp"
#include "voronoimesh/fields/phase_field.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vm {

/// Which nodes of its grid a SampledField holds.
enum class SampledNodes {
  all, ///< every node
  /// The nodes of the bcc lattice (create/create.hpp, Lattice::bcc) only: those
  /// whose three indices are all even or all odd, a quarter of the grid's, all
  /// that create reads with that lattice. The grid needs even cell counts.
  bcc,
};

/// Top-K samples of N phase functions on the nodes of a grid.
class SampledField {
public:
  /// Samples `field` at every node of `grid` in parallel, keeping the `k` largest
  /// phases per node (ties: lower phase id first).
  /// @param field the phase functions to sample
  /// @param grid  the grid whose nodes are sampled
  /// @param k     phases kept per node, in [1, 16] (more is never needed: few phases compete at any one
  ///              point)
  /// @return the samples of every node
  /// @throws InvalidInput if a value is NaN or infinite (naming the phase and the point), or if k is not
  ///         in [1, 16]
  static SampledField sample(const PhaseField& field, const GridSpec& grid, int k = 4);

  /// As sample(), but only the nodes `nodes` names: SampledNodes::bcc takes a
  /// quarter of the time and memory for a create with the bcc lattice.
  /// @param field the phase functions to sample
  /// @param grid  the grid whose nodes are sampled (even cell counts for SampledNodes::bcc)
  /// @param k     phases kept per node, in [1, 16]
  /// @param nodes which nodes to sample and hold
  /// @return the samples of those nodes
  /// @throws InvalidInput as sample(), and for an odd cell count with SampledNodes::bcc
  static SampledField sample(const PhaseField& field, const GridSpec& grid, int k, SampledNodes nodes);

  /// As sample(), but only the nodes of grid layers layers[0]..layers[1] (the
  /// nodes (i, j, z) with z in that range): one rank's block of a distributed
  /// run (mpi/distributed.hpp). Node indices stay those of the whole grid.
  /// @param field  the phase functions to sample
  /// @param grid   the whole grid
  /// @param k      phases kept per node, in [1, 16]
  /// @param layers the first and last grid layer (along z) to sample, inclusive, within [0, grid.cells[2]]
  /// @return the samples of the nodes of those layers
  /// @throws InvalidInput as sample(), and for layers outside [0, grid.cells[2]]
  static SampledField sample(const PhaseField& field, const GridSpec& grid, int k, std::array<int32_t, 2> layers);

  /// A block of samples made elsewhere (another rank's sample()): `ids` and
  /// `values` hold k entries per node, `floors` one, for the nodes of `layers`
  /// in node-index order.
  /// @param grid       the whole grid
  /// @param num_phases N, all phases of the field
  /// @param k          slots per node (k() of the block it copies), 1 or more
  /// @param layers     the first and last grid layer (along z) the samples hold, inclusive
  /// @param ids        the phase ids, k per node, sorted by decreasing value (as all_ids())
  /// @param values     their values, k per node (as all_values())
  /// @param floors     the floor value of each node (as all_floors(), floor_value())
  /// @return the block of samples
  /// @throws InvalidInput if the sizes do not match (or the layers lie outside the grid)
  static SampledField from_samples(const GridSpec& grid, int num_phases, int k, std::array<int32_t, 2> layers,
                                   std::vector<int32_t> ids, std::vector<double> values, std::vector<double> floors);

  const GridSpec& grid() const { return grid_; }  ///< the grid sampled
  int num_phases() const { return num_phases_; } ///< N, all phases of the field
  /// Slots per node (min(k, N)).
  int k() const { return k_; }
  /// The grid layers held: the whole grid unless sampled by layers.
  std::array<int32_t, 2> layers() const { return layers_; }
  /// Index of the first node held (nodes first_node() .. are held).
  int64_t first_node() const { return first_node_; }
  /// The stored arrays, nodes in order (k() entries per node for ids and values):
  /// the phase ids (ids()).
  std::span<const int32_t> all_ids() const { return ids_; }
  std::span<const double> all_values() const { return values_; } ///< the values matching all_ids() (values())
  std::span<const double> all_floors() const { return floor_; }  ///< the floor value of each node (floor_value())

  /// Phase ids stored at node n, sorted by decreasing value (k() entries).
  /// @param n a node index of the whole grid, among the nodes held
  std::span<const int32_t> ids(int64_t n) const { return {ids_.data() + slot(n) * k_, size_t(k_)}; }
  /// Values matching ids(n).
  /// @param n a node index of the whole grid, among the nodes held
  std::span<const double> values(int64_t n) const {
    return {values_.data() + slot(n) * k_, size_t(k_)};
  }
  /// What is held at one node: its ids(), values() and floor_value().
  struct NodeSamples {
    std::span<const int32_t> ids; ///< phase ids, by decreasing value (k() entries)
    std::span<const double> values; ///< the values matching ids
    double floor = 0;               ///< the value of every phase not stored there
  };
  /// What is held at grid node (i, j, k), found once and without dividing:
  /// for loops that walk the nodes by their grid coordinates (create's lattice).
  /// @param i node along x
  /// @param j node along y
  /// @param k node along z, among the layers held
  NodeSamples at(int64_t i, int64_t j, int64_t k) const {
    const int64_t s = slot(i, j, k);
    return {{ids_.data() + s * k_, size_t(k_)}, {values_.data() + s * k_, size_t(k_)}, floor_[size_t(s)]};
  }
  /// The value every phase not stored at node n takes there: below all stored
  /// values by a margin, and a function of the node alone, so the piecewise-linear
  /// field stays one consistent field (DESIGN.md, "Field").
  /// @param n a node index of the whole grid, among the nodes held
  double floor_value(int64_t n) const { return floor_[size_t(slot(n))]; }
  /// Value of phase `phase` at node n (stored value or floor_value).
  /// @param n     a node index of the whole grid, among the nodes held
  /// @param phase a phase id, in [0, num_phases())
  double value(int64_t n, int32_t phase) const;

  /// Smallest and largest value held (floor values included); for a block of
  /// layers, those of the block.
  double min_value() const { return min_value_; }
  double max_value() const { return max_value_; } ///< largest value held, as min_value()

  /// How many nodes of `grid` sample() with `nodes` holds.
  static int64_t count_nodes(const GridSpec& grid, SampledNodes nodes);
  /// Which nodes are held; with SampledNodes::bcc, the arrays hold the even
  /// nodes, then the odd ones, each in node order (create's lattice node ids).
  SampledNodes nodes() const { return nodes_; }

private:
  static SampledField sample_nodes(const PhaseField& field, const GridSpec& grid, int k, std::array<int32_t, 2> layers,
                                   SampledNodes which);
  void find_range();
  /// Where node n's entries are in the arrays.
  int64_t slot(int64_t n) const { return nodes_ == SampledNodes::all ? n - first_node_ : bcc_slot(n); }
  int64_t bcc_slot(int64_t n) const;
  /// Where node (i, j, k)'s entries are: with SampledNodes::bcc, the even
  /// nodes first (all of i, j, k even), then the odd ones, each in node order.
  int64_t slot(int64_t i, int64_t j, int64_t k) const {
    if (nodes_ == SampledNodes::all) return grid_.node_index(i, j, k) - first_node_;
    const auto n = grid_.nodes();
    if (i & 1) // odd: after all (cells/2 + 1)^3 even nodes
      return (n[0] / 2 + 1) * (n[1] / 2 + 1) * (n[2] / 2 + 1) + (i >> 1) + n[0] / 2 * ((j >> 1) + n[1] / 2 * (k >> 1));
    return (i >> 1) + (n[0] / 2 + 1) * ((j >> 1) + (n[1] / 2 + 1) * (k >> 1));
  }

  GridSpec grid_;
  int num_phases_ = 0;
  int k_ = 0;
  std::array<int32_t, 2> layers_{0, -1};
  int64_t first_node_ = 0;
  SampledNodes nodes_ = SampledNodes::all;
  std::vector<int32_t> ids_;
  std::vector<double> values_;
  std::vector<double> floor_;
  double min_value_ = 0, max_value_ = 0;
};

} // namespace vm
