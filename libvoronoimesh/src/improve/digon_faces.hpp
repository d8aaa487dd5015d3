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

#include "mesh/node_rings.hpp"

#include "voronoimesh/fields/phase_field.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// A digon face to merge into one point: `keep` (the lower of its two
/// corners) and every other node of the face (the other corner, the nodes
/// inside its two curves and inside the face), and where the merged node goes.
struct DigonFace {
  int32_t keep;
  std::vector<int32_t> merged;
  Vec3 to;
};

/// The nodes of `face` (its corner `keep` and the merged ones) and their
/// neighbours, ascending, each once: where a check of its merge can fail.
std::vector<int32_t> nodes_around(const NodeRings& mesh, const DigonFace& face);

/// The digon faces of `mesh` that the phase functions say are artefacts: from
/// each of its two corners, Newton's method on the four phases' equalities
/// converges to one point (the merged node's place), within a tenth of the
/// target of each other. A lens of a smooth partition (three overlapping balls
/// in a fourth phase) has two such points apart and is kept. Both curves are
/// at most `longest` x the target edge length (at either corner) long and all
/// nodes lie off the box; no two faces share a node or a neighbour (the
/// shorter first), so that each merge is judged on the mesh around it as it is.
/// @param mesh    the node-level mesh
/// @param target  the target edge length at each node
/// @param field   the phase functions
/// @param longest the longest curve of a face merged, in targets
/// @return the faces, by their corner `keep`, ascending
std::vector<DigonFace> small_digon_faces(const NodeRings& mesh, std::span<const double> target,
                                         const PhaseField& field, double longest);

} // namespace vm::detail
