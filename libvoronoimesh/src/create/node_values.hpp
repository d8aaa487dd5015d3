#pragma once
/// @file node_values.hpp
/// The values create works on: the sampled field quantized to integers and
/// snapped (Algorithm 2, line 1), with the winning phase of every node.
///
/// Ties are broken by a symbolic perturbation phi'_i = phi_i - eps_i, where the
/// eps_i are infinitesimals of different orders, 0 < eps_0 << eps_1 << ...: the
/// lower phase id wins an exact tie, and no combination of phases can stay tied
/// (tet_cutter.cpp, sign_at). The perturbation is the same at every point, so the
/// perturbed field is still one consistent piecewise-linear field; exact ties
/// (snapping makes many, symmetric scenes have them by construction) never need a
/// tolerance.

#include "create/lattice.hpp"
#include "voronoimesh/fields/sampled_field.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace vm::detail {

/// Quantized values span [0, 2^kValueBits]: see exact.hpp for why this bound.
constexpr int kValueBits = 29;

/// True when phase `a` with value `va` beats phase `b` with value `vb` in the
/// perturbed order.
inline bool beats(int64_t va, int32_t a, int64_t vb, int32_t b) { return va > vb || (va == vb && a < b); }

/// The part of the field a NodeValues holds, for one rank of a distributed
/// create: the lattice nodes of a window of grid layers, and the range of
/// values over the whole field. Every rank must quantize with the same range,
/// or the same value would become different integers on different ranks.
struct NodeScope {
  NodeWindow window;
  double min_value = 0, max_value = 0;
};

/// The smallest floor value and the largest value of `field` over the lattice
/// nodes of grid layers `layers` (inclusive): the range NodeValues quantizes
/// over. Taken over the lattice's nodes only, it is the same whether the field
/// holds every grid node or only those (SampledNodes::bcc).
std::array<double, 2> lattice_value_range(const SampledField& field, const TetLattice& lattice,
                                          std::array<int32_t, 2> layers);

class NodeValues {
public:
  /// How much of create's repair a node gets (create/create.cpp), by level: 0 snaps its
  /// values (Algorithm 2, line 1); 1 keeps the sampled values; 2 and above also
  /// lower every stored value by a pseudo-random amount of up to untie_eps (at
  /// least 16 and at most 2^19 quanta), a function of node, phase and level. That
  /// leaves no exact tie at the node, nor crossings of three phases at one point of
  /// the lattice edges, faces and tets around it: the coincidences the symbolic
  /// perturbation separates only infinitesimally, whose limit points merge into
  /// a pinched phase. Each level draws anew, so a draw that ties again is redrawn.
  using RepairLevel = uint8_t;
  static constexpr RepairLevel kSnap = 0, kUnsnap = 1, kFirstUntie = 2;

  /// Quantizes and snaps `field` at the nodes of `lattice`, indexed by lattice
  /// node id. `snap_eps` and `untie_eps` are in the field's value units. `repair`
  /// (if given, one RepairLevel per node of the window, in its numbering) says
  /// where create undoes what pinched a phase: snapping, or ties and
  /// coincidences of the data themselves. `scope` (if given) limits the nodes
  /// to a window, which `field` must cover, and sets the range quantized;
  /// otherwise every node, and the range of `field`.
  NodeValues(const SampledField& field, const TetLattice& lattice, double snap_eps, double untie_eps = 0,
             const std::vector<RepairLevel>* repair = nullptr, const NodeScope* scope = nullptr);

  /// Computes again the `nodes` (lattice ids in the window, no repeats) whose
  /// level in `repair` changed since: the values a new NodeValues with `repair`
  /// would hold, without redoing the unchanged rest (create's repair rounds
  /// change a few hundred nodes of millions).
  void redo(const SampledField& field, const TetLattice& lattice, const std::vector<RepairLevel>& repair,
            std::span<const int64_t> nodes);

  /// The nodes held.
  const NodeWindow& window() const { return window_; }

  /// Stored phase ids of lattice node n (the sampled field's order).
  std::span<const int32_t> ids(int64_t n) const { return {ids_.get() + window_.local(n) * k_, size_t(k_)}; }
  /// Quantized, snapped values matching ids(n).
  std::span<const int32_t> values(int64_t n) const { return {values_.get() + window_.local(n) * k_, size_t(k_)}; }
  /// Quantized value of phase p at node n (its stored value or the node's floor).
  int32_t value(int64_t n, int32_t p) const {
    n = window_.local(n);
    const int32_t* id = ids_.get() + n * k_;
    for (int s = 0; s < k_; ++s)
      if (id[s] == p) return values_[n * k_ + s];
    return floor_[n];
  }
  /// The winning phase at node n in the perturbed order.
  int32_t label(int64_t n) const { return label_[window_.local(n)]; }
  /// Nodes whose values snapping changed.
  uint64_t snapped_nodes() const { return snapped_nodes_; }
  /// True when snapping changed the values of node n.
  bool snapped(int64_t n) const { return snapped_[window_.local(n)] != 0; }

private:
  /// Fills node `id` (local index n) from what is sampled there, `at`, at
  /// repair level `level`; returns whether snapping changed its values.
  bool fill(const SampledField::NodeSamples& at, int64_t id, int64_t n, RepairLevel level);

  NodeWindow window_;
  int k_;
  // The affine map to integers (v - lo_) * scale_ and the snap and untie distances in its units.
  double lo_ = 0, scale_ = 1;
  int64_t eps_ = 0, untie_ = 0;
  // Every entry is written once by the parallel fill, so none is zeroed first.
  std::unique_ptr<int32_t[]> ids_;
  std::unique_ptr<int32_t[]> values_;
  std::unique_ptr<int32_t[]> floor_;
  std::unique_ptr<int32_t[]> label_;
  std::unique_ptr<uint8_t[]> snapped_;
  uint64_t snapped_nodes_ = 0;
};

} // namespace vm::detail
