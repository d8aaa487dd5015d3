#pragma once
/// @file create/coincident_triangles.hpp
/// The one repair create makes to its triangles themselves: pairs of triangles
/// on the same three points, where a phase won only on a lattice face.

#include "create/create_slabs.hpp"

namespace vm::detail {

/// Two triangles on the same three points are a phase squeezed to zero thickness
/// between them (it won only on a face, by an exact tie). Seen from the first
/// triangle's vertex order, each has a back and a front phase; the squeezed phase
/// is the one they share, and what remains is the interface between the outer two
/// (nothing, if those are the same phase). Couples that do not stack that way, and
/// stacks of three or more, are left for the validator to report. Where a pair
/// cancels, corners that no triangle uses any more are dropped (any vertex no
/// triangle uses is): a vertex lies in at most two neighbouring slabs, and every
/// rank that numbers it cuts both, so all drop the same vertices and number the
/// rest as one process does.
void resolve_coincident_triangles(SlabsMesh& e, CreateStats& stats);

} // namespace vm::detail
