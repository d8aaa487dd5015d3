#pragma once
/// @file improve/flip.hpp
/// Edge flipping (paper sect. 4.3, Algorithm 5).

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/improve/guard.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <span>

namespace vm {

/// Parameters of flip_edges() (the flip pass); defaults are the paper's.
struct FlipParams {
  /// Pairs of triangles already this good are left alone (Algorithm 5, line 7).
  double skip_quality = 0.9;
  /// Rounds of flips per call; each round flips a set of edges sharing no node.
  int max_rounds = 8;
  /// Afterwards, collapse junction triangles below this quality that no flip can
  /// remove (improve/collapse.hpp; beyond the paper). 0 turns it off. 0.15 (0.05
  /// until collapses had to leave better triangles than the sliver and could
  /// merge close quadruple points): over 22 closed-form scenes (random seeds
  /// with 17-30 cells and random spheres at grid 48, the shipped ones) it raised
  /// the worst triangle on 13, lowered it on 2 (voronoi30 0.293 -> 0.246).
  double collapse_below = 0.15;
  /// Refuse flips and collapses that would make two surfaces cross (improve/guard.hpp).
  bool guard_crossings = true;
  /// With guard_crossings: the phase functions, to also refuse flips that make a
  /// junction triangle face against its phase pair (null: not checked).
  const PhaseField* field = nullptr;
  /// With guard_crossings: the guard whose index of the mesh to reuse (a
  /// pipeline's, improve/guard.hpp); null: a fresh one for this call.
  CrossingGuard* guard = nullptr;
  /// An ear (a triangle with all three corners on one junction curve or box
  /// edge, which moves can only flatten) below this quality flips even into a
  /// worse pair (beyond the paper). By default every ear: its corners cannot
  /// reach their curve otherwise. 0.05 gives much better worst triangles on some
  /// scenes (voronoi30 0.237 against 0.064 after 20 iterations) but leaves ear
  /// corners held off their curve (docs/algorithm.md, "Known gaps"). Last, so
  /// that positional initialisers written before it keep their meaning.
  double ear_below = 1;
  /// Nodes whose triangles stay as they are (in one process): no edge at them
  /// or across from them flips. The pipeline gives the nodes its quality floor
  /// let through this iteration when a floor pass may put them back
  /// (PassContext::floor_pass).
  std::span<const int32_t> keep_triangles_at = {};
};

/// What one flip_edges() call did.
struct FlipStats {
  size_t flips = 0;     ///< edges flipped
  int rounds = 0;       ///< rounds of flips made
  size_t collapses = 0; ///< junction slivers collapsed afterwards (collapse_junction_slivers())
};

/// Flips every edge shared by two triangles of the same surface when that raises
/// the smaller of their qualities and does not fold them (Algorithm 5). Junction
/// and domain-boundary edges never flip (they are boundaries of their patches),
/// and a flip never creates an edge that exists in another patch. In rounds: all
/// edges are judged in parallel, then the best (by quality gain, ties by edge)
/// that share no node are flipped; so the result is the same for any thread count.
/// With guard_crossings, flips whose new triangles cross another surface are
/// undone, with the later flips that share a node with them, until no flip
/// made a crossing: a mesh without crossings keeps none. Then degenerate junction triangles are collapsed
/// (collapse_junction_slivers), which renumbers the nodes.
/// @param mesh   the mesh, changed in place (collapses renumber its nodes)
/// @param params quality threshold, rounds, collapsing and the crossing guard
/// @return the flips, rounds and collapses made
FlipStats flip_edges(InterfaceMesh& mesh, const FlipParams& params = {});

} // namespace vm
