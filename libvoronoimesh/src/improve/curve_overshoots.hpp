#pragma once
/// @file improve/curve_overshoots.hpp
/// Triple curves that run past the quadruple point they end at, which the
/// remesh pass mends by merging the overshooting curve nodes into the point.
///
/// Four phases meet at a quadruple point, and each triple curve that ends there
/// stops where the fourth phase takes over: beyond it, that phase is larger
/// than the curve's three. Where the lattice put the point a fraction of a cell
/// off, the curves around it can run on past the true point, their nodes
/// inside the fourth phase, and the point itself lies where the curves end. Projection
/// cannot mend that: each curve node goes onto its own curve (which the phase
/// functions extend past the point), and the point can reach its place only by
/// passing through the curve nodes in its way, which the crossing guard
/// forbids. On seeds25_4 (25 random cells) such a point stayed 0.69 h from
/// where its four cells meet, with its worst triangle at q 0.198.

#include "improve/point_merges.hpp"

#include <span>
#include <vector>

namespace vm::detail {

/// The quadruple points (off the box) with a curve neighbour past them: a node
/// of a curve ending at the point where the point's fourth phase is larger than
/// the curve's three. Each becomes the merge of those neighbours into the
/// point, which goes where Newton's method on its four phases' equalities
/// leads from it (within two targets and inside the domain, else it is left as
/// it is: a point the phases put beyond the box is no point of the meshed
/// partition, whose curves end on the box instead). Meant for a
/// mesh whose nodes have been projected once: in a mesh just created, snapping
/// leaves many curve nodes a hair past their points, which projection brings
/// back by itself (merging those made the four-ball scenes' worst triangles
/// worse).
/// @param mesh   the node-level mesh
/// @param target the target edge length at each node
/// @param field  the phase functions
/// @return the merges, by point, ascending (they may touch: keep_apart() chooses among them)
std::vector<PointMerge> overshooting_curve_ends(const NodeRings& mesh, std::span<const double> target,
                                                const PhaseField& field);

} // namespace vm::detail
