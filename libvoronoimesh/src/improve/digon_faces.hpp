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

/// The chains among `faces` (of small_digon_faces()): faces that share a
/// corner, each chain of two or more as one merge into its lowest corner.
/// The lattice can resolve a vertex two of whose curves leave it at a small
/// angle (its four phases nearly tie along them) as a chain: a small digon of
/// one pair of the phases next to a longer one of the other pair, three
/// corners of the same phases in a row, the phase functions leading every
/// corner to the one vertex near the chain's far end. Merged face by face,
/// the small digon's node would have to travel the chain's length (seeds17_4:
/// 3.3 h), which fails on every call, while the longer digon, touching it,
/// waits: the chain stays, with its scene's worst triangles.
/// @param faces     digon faces, as small_digon_faces() gives them
/// @param num_nodes the mesh's number of nodes
std::vector<PointMerge> digon_chains(std::span<const PointMerge> faces, size_t num_nodes);

} // namespace vm::detail
