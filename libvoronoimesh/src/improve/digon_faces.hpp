#pragma once
/// @file improve/digon_faces.hpp
/// Small faces bounded by two curves only, which the remesh pass removes.
///
/// Where a vertex of the phases is nearly degenerate (a fifth phase almost
/// ties, or two vertices lie closer than a cell), the lattice can resolve it
/// as two quadruple points of the same four phases, joined by two triple
/// curves that enclose a small face of the two phases the curves share: a
/// "digon". No Voronoi diagram has one (its faces are convex polygons, and four
/// seeds have one vertex), and a smooth partition has one only as a lens
/// as large as the features that make it. Small, it holds slivers that no
/// collapse can remove (no edge of it may collapse without folding one curve
/// onto the other) and keeps both corners away from the one point the phases
/// meet at. Merging the whole face into one point leaves a proper quadruple
/// point: the two corners' other four curves, one of each triple.

#include "improve/point_merges.hpp"

#include <span>
#include <vector>

namespace vm::detail {

/// The digon faces of `mesh` that the phase functions say are artefacts: from
/// each of its two corners, Newton's method on the four phases' equalities
/// converges to one point (the merged node's place), within a tenth of the
/// target of each other. A lens of a smooth partition (three overlapping balls
/// in a fourth phase) has two such points apart and is kept. Both curves are
/// at most `longest` x the target edge length (at either corner) long and all
/// nodes lie off the box.
/// @param mesh    the node-level mesh
/// @param target  the target edge length at each node
/// @param field   the phase functions
/// @param longest the longest curve of a face merged, in targets
/// @return each face as the merge of its nodes into its lower corner `keep`, the faces with the shorter
///         curves first (faces may touch: keep_apart() chooses among them)
std::vector<PointMerge> small_digon_faces(const NodeRings& mesh, std::span<const double> target,
                                          const PhaseField& field, double longest);

} // namespace vm::detail
