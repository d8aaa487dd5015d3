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
#include "create/node_source.hpp"
#include "voronoimesh/fields/sampled_field.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <compare>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// Quantized values span [0, 2^kValueBits]: see exact.hpp for why this bound.
constexpr int kValueBits = 29;

/// True when phase `a` with value `va` beats phase `b` with value `vb` in the
/// perturbed order.
inline bool beats(int64_t va, int32_t a, int64_t vb, int32_t b) { return va > vb || (va == vb && a < b); }

/// A lattice node where create raises `phase` up to a tie with the node's
/// leader, to close a tiny loop (create/tiny_loops.hpp).
struct LoopClosing {
  /// For `phase`: tie every phase within the wider snap instead.
  static constexpr int32_t kTieAll = -1;
  int64_t node;
  int32_t phase;
  auto operator<=>(const LoopClosing&) const = default;
};

/// The part of the field a NodeValues holds, for one rank of a distributed
/// create: the lattice nodes of a window of grid layers, and the range of
/// values over the whole field. Every rank must quantize with the same range,
/// or the same value would become different integers on different ranks.
struct NodeScope {
  NodeWindow window;
  double min_value = 0, max_value = 0;
  /// The phase functions sampled, for snapping slow pairs less (NodeValues); null: by value alone.
  const PhaseField* field = nullptr;
};

/// 1 for the lattice nodes (by id) whose key (their winner, or -1 where it is not sure)
/// is -1 or differs from a neighbour's (TetLattice::for_each_neighbour), and
/// with `box` for those on the grid's box. Nodes two grid steps or more inside
/// the box find their neighbours at fixed id offsets (ids are affine in the grid
/// point within each kind of node: from the node itself for its kind, from its
/// neighbour at (-1, -1, -1) for the other kind of bcc): 34 loads instead of the
/// general walk, which took a fifth of a label volume's create; and where keys
/// run along rows, a run of such nodes at a time. NodeValues holds these nodes' values.
std::vector<uint8_t> held_near_interfaces(const TetLattice& lattice, const std::vector<int32_t>& key, bool box);

/// The smallest floor value and the largest value of `field` over the lattice
/// nodes of grid layers `layers` (inclusive): the range NodeValues quantizes
/// over. Taken over the lattice's nodes only, it is the same whether the field
/// holds every grid node or only those (SampledNodes::bcc).
std::array<double, 2> lattice_value_range(const SampledField& field, const TetLattice& lattice,
                                          std::array<int32_t, 2> layers);

/// The quantized, snapped values of the lattice nodes, with each node's winner.
///
/// Snapping (Algorithm 2, line 1) makes two phases' values equal where they
/// differ by less than eps, which moves their interface onto the node from
/// about eps / |grad phi_p - grad phi_q| away: a tenth of a cell for the
/// paper's distance functions at eps = 0.2 h. Where the phase functions are
/// known, a pair whose difference grows slower than kSlowRate per unit length
/// snaps only within eps times its rate / kSlowRate, so that no snap moves an
/// interface more than eps / kSlowRate (a cell at the default eps). By value
/// alone, the bisector of two seeds 0.02 apart (seeds30_2, rate 0.085 there)
/// lay up to 3 cells off along two box faces, and after improvement still 2
/// cells off, folded at 10 edges. Faster pairs snap by value as the paper does:
/// snapping every pair by distance left near-degenerate vertices as clusters
/// of quadruple points a hundredth of a cell apart, which snapping merges.
///
/// Held for every node, or near interfaces only: there, every node keeps its
/// winning phase, but only the nodes a cut can read keep their values (the
/// nodes of tetrahedra whose corners have different winners). The winner of
/// every other node is sure: it beats every other phase there by more than
/// snapping and any repair level can change (hold_margin()), so the node's
/// tetrahedra stay uncut and its values are never read. A repair that changes
/// a node's winner holds its neighbours first. On CGAL's liver 273,269 of 6.36M
/// lattice nodes keep their values.
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
  /// kWideSnap snaps as kSnap, then raises the phases close_loops() gives the
  /// node to a tie with its leader where they are within widen_snap()'s
  /// distance of it (create/tiny_loops.hpp); given LoopClosing::kTieAll, it
  /// snaps within that distance instead. A node at it that offends goes on to
  /// kFirstUntie.
  using RepairLevel = uint8_t;
  static constexpr RepairLevel kSnap = 0, kUnsnap = 1, kFirstUntie = 2, kWideSnap = 254;

  /// Quantizes and snaps `field` at every node of `lattice`, indexed by lattice
  /// node id. `snap_eps` and `untie_eps` are in the field's value units. `repair`
  /// (if given, one RepairLevel per node of the window, in its numbering) says
  /// where create undoes what pinched a phase: snapping, or ties and
  /// coincidences of the data themselves. `scope` (if given) limits the nodes
  /// to a window, which `field` must cover, and sets the range quantized;
  /// otherwise every node, and the range of `field`.
  NodeValues(const SampledField& field, const TetLattice& lattice, double snap_eps, double untie_eps = 0,
             const std::vector<RepairLevel>* repair = nullptr, const NodeScope* scope = nullptr);

  /// As above for every node of the lattice at repair level kSnap, but holding
  /// values near interfaces only (the class comment), read from `source`, which
  /// is read once for every node and again for the nodes held. With
  /// `hold_box_nodes` the nodes on the grid's box are held too (closing reads them).
  /// @throws InvalidInput for a value that is NaN or infinite
  NodeValues(const NodeSource& source, const TetLattice& lattice, double snap_eps, double untie_eps,
             bool hold_box_nodes);

  /// Computes again the `nodes` (lattice ids in the window, no repeats) whose
  /// level in `repair` changed since: the values a new NodeValues with `repair`
  /// would hold, without redoing the unchanged rest (create's repair rounds
  /// change a few hundred nodes of millions). Nodes not held are left as they
  /// are (their winner is sure at every level) until held.
  void redo(const NodeSource& source, const TetLattice& lattice, const std::vector<RepairLevel>& repair,
            std::span<const int64_t> nodes);

  /// Holds the values of `nodes` (lattice ids in the window) at their level in
  /// `repair` (kSnap where it is empty), so that snapped() answers for them.
  void hold(const NodeSource& source, const TetLattice& lattice, const std::vector<RepairLevel>& repair,
            std::span<const int64_t> nodes);

  /// How far below its leader a phase rises at a node of kWideSnap (the
  /// field's value units; below the snapping distance given at construction,
  /// that one). Before redo() of them.
  void widen_snap(double eps) { wide_eps_ = std::max<int64_t>(eps_, std::llround(eps * scale_)); }

  /// Sets the phases that rise at nodes of kWideSnap (sorted, no repeats), before
  /// redo() of them; returns their nodes (sorted, no repeats).
  std::vector<int64_t> close_loops(std::vector<LoopClosing> closings);

  /// The nodes of the window.
  const NodeWindow& window() const { return window_; }
  /// True when lattice node n holds its values (every node unless near interfaces only).
  bool held(int64_t n) const { return slot(n) >= 0; }
  /// How many nodes hold their values.
  int64_t held_nodes() const { return slot_.empty() ? window_.size() : int64_t(floor_.size()); }

  /// Stored phase ids of lattice node n (the sampled field's order); n must be held.
  std::span<const int32_t> ids(int64_t n) const { return {ids_.data() + slot(n) * k_, size_t(k_)}; }
  /// Quantized, snapped values matching ids(n); n must be held.
  std::span<const int32_t> values(int64_t n) const { return {values_.data() + slot(n) * k_, size_t(k_)}; }
  /// Quantized value of phase p at node n (its stored value or the node's floor); n must be held.
  int32_t value(int64_t n, int32_t p) const {
    const int64_t s = slot(n);
    const int32_t* id = ids_.data() + s * k_;
    for (int i = 0; i < k_; ++i)
      if (id[i] == p) return values_[size_t(s * k_ + i)];
    return floor_[size_t(s)];
  }
  /// The winning phase at node n in the perturbed order.
  int32_t label(int64_t n) const { return label_[size_t(window_.local(n))]; }
  /// Held nodes whose values snapping changed.
  uint64_t snapped_nodes() const { return snapped_nodes_; }
  /// True when snapping changed the values of node n (false for a node not held).
  bool snapped(int64_t n) const {
    const int64_t s = held_slot(window_.local(n));
    return s >= 0 && snapped_[size_t(s)] != 0;
  }

private:
  /// Where the values of the node with window index `local` are, -1 if not held.
  int64_t held_slot(int64_t local) const { return slot_.empty() ? local : slot_[size_t(local)]; }
  int64_t slot(int64_t n) const { return held_slot(window_.local(n)); }
  /// Sets the map to integers from the range of values [lo, hi].
  void set_scale(double lo, double hi, double snap_eps, double untie_eps);
  /// The least lead of a node's winner over its second phase, in field units,
  /// that no snapping and no repair level can overturn (the class comment).
  double hold_margin() const;
  /// Gives the nodes `nodes` (window indices, not held, no repeats) their slots.
  void add_slots(std::span<const int64_t> nodes);
  /// Holds the values of the lattice nodes `nodes` (ids), those not yet held,
  /// and for every node whose winner that changes, its neighbours'; returns
  /// how many snapped among them.
  uint64_t hold_nodes(const NodeSource& source, const TetLattice& lattice, const std::vector<RepairLevel>& repair,
                      std::vector<int64_t> nodes);
  /// The winners of lattice nodes `nodes` before a change.
  std::vector<int32_t> labels_of(std::span<const int64_t> nodes) const;
  /// The neighbours of those of `nodes` whose winner is no longer `before`'s:
  /// they now border nodes a cut may read.
  std::vector<int64_t> around_new_winners(const TetLattice& lattice, std::span<const int64_t> nodes,
                                          const std::vector<int32_t>& before) const;
  /// Fills the node with lattice id `id`, window index `local`, from what is
  /// sampled there, `at`, at repair level `level`; returns whether snapping
  /// changed its values.
  bool fill(const SampledField::NodeSamples& at, int64_t id, int64_t local, RepairLevel level);

  NodeWindow window_;
  int k_;
  // The phase functions, to snap slow pairs less (null: by value alone), and where the nodes lie.
  const PhaseField* field_ = nullptr;
  const TetLattice* lattice_ = nullptr;
  // The affine map to integers (v - lo_) * scale_ and the snap and untie distances in its units.
  double lo_ = 0, scale_ = 1;
  int64_t eps_ = 0, untie_ = 0, wide_eps_ = 0;
  std::vector<LoopClosing> closings_; // close_loops()'s
  std::vector<int32_t> label_;   // by window index, every node
  std::vector<int32_t> slot_;    // by window index: where its values are, -1 if not held; empty: all held in order
  std::vector<int32_t> ids_;     // k_ per held node
  std::vector<int32_t> values_;  // k_ per held node
  std::vector<int32_t> floor_;   // per held node
  std::vector<uint8_t> snapped_; // per held node
  uint64_t snapped_nodes_ = 0;
};

} // namespace vm::detail
