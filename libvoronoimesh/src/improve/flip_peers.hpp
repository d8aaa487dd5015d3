#pragma once
/// @file improve/flip_peers.hpp
/// How the flip rounds of a distributed run agree across ranks
/// (mpi/improve_part.cpp). Each rank flips on its window of the mesh; at the
/// points below, where one process would look at the whole mesh, the ranks
/// agree, so that every rank makes the flips one process makes around its own
/// vertices. One process passes no peers.

#include "voronoimesh/improve/flip.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm::detail {

/// An edge that would gain from a flip: its nodes i < j, then the opposite k, l.
struct FlipCandidate {
  double gain;
  int32_t edge;
  std::array<int32_t, 4> nodes;
};

/// A flip of a call's log, named alike on every rank whose window holds it:
/// its edge's nodes before the flip, and how many flips of that edge came
/// before it in the call (a window that holds an edge makes all its flips, in
/// the order one process makes them).
struct FlipInstance {
  std::array<int32_t, 2> edge;
  int32_t earlier;
  auto operator<=>(const FlipInstance&) const = default;
};

class FlipPeers {
public:
  virtual ~FlipPeers() = default;
  /// True when any rank's `mine` is (the rounds go on while any rank has candidates).
  virtual bool any(bool mine) = 0;
  /// Sets take[c] for the candidates of `found` (best first) that flip this
  /// round: those one process takes over the whole mesh, each unless a better
  /// candidate sharing a node is taken. Candidates this rank cannot decide
  /// (far out in its window) stay 0 and are judged again, as lost ones are.
  virtual void choose(const std::vector<FlipCandidate>& found, std::vector<uint8_t>& take) = 0;
  /// True when this rank answers for the crossings of the triangle with these
  /// nodes (the windows of the others hold what this one may lack).
  virtual bool answers_for(const std::array<int32_t, 3>& triangle) = 0;
  /// Replaces `culprits` (flipped edges, as their nodes before the flip) with
  /// every rank's, those whose nodes are in this window; returns whether any
  /// rank had one (then every rank undoes those flips and the ones after them
  /// that share a node, improve/flip_log.hpp).
  virtual bool agree_on_culprits(std::vector<std::array<int32_t, 2>>& culprits) = 0;
  /// Replaces `flips` (flips this rank must undo with the culprits') with every
  /// rank's, those whose nodes are in this window; returns whether any rank had
  /// one. Unlike a culprit, which names every flip of its edge, each names one
  /// flip: one process undoes only the flips after an undone one
  /// (FlipLog::with_dependents()), not the earlier flips of their edges.
  virtual bool agree_on_flips(std::vector<FlipInstance>& flips) = 0;
};

} // namespace vm::detail
