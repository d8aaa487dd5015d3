#pragma once
/// @file improve/phase_islands.hpp
/// Small pieces of a phase that the phase functions do not have, which the
/// remesh pass merges away.
///
/// Where a few phases nearly tie near a vertex of the partition, the lattice's
/// linear interpolation can let a phase lead in a pocket far smaller than a
/// cell, cut off from the rest of it: a closed piece of the phase's boundary
/// of a few triangles (seeds17_4 of bench/junction_scenes.sh: a tetrahedron of
/// cell 11 against the box, 0.6 h across, where cells 2 and 15 lead and 11 is
/// 0.6 h behind). No Voronoi cell has two pieces, no projection can mend it
/// (its four curves hold a quadruple point 1.8 h from where its phases meet)
/// and its triangles stay slivers. Merging all its nodes into one removes it
/// and leaves the curves the phase functions have.

#include "improve/point_merges.hpp"

#include <span>
#include <vector>

namespace vm::detail {

/// The pieces of a phase's boundary that are artefacts: connected through
/// their edges (a triple curve joins the two triangles of the phase at it),
/// reached from a junction or box node, of at most 64 triangles and
/// at most `widest` x the target (the smallest of their nodes') across, of a
/// phase that has other triangles (a label is never lost), and where the
/// phase functions make another phase lead at the mean of their nodes and a
/// tenth of a target inside the centre of every triangle. A piece the phase
/// fills, however small (a drop 0.8 h in radius), keeps its phase leading
/// inside and is kept.
/// @param mesh   the node-level mesh
/// @param target the target edge length at each node
/// @param field  the phase functions
/// @param widest the largest piece merged, in targets
/// @return each piece as the merge of its nodes into one that lies on every box face any of them lies on
///         (pieces that touch box faces no node of them shares are left), which goes to their mean
///         (on those faces); by `keep`
std::vector<PointMerge> phase_islands(const NodeRings& mesh, std::span<const double> target, const PhaseField& field,
                                      double widest);

} // namespace vm::detail
