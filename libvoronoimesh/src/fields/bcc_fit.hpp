#pragma once
/// @file fields/bcc_fit.hpp
/// Which voxels of a label volume the bcc lattice on the voxel grid cannot
/// keep in their label's phase, so that create can take every grid node
/// (cube6) where a label would otherwise be lost.

#include "fields/label_field.hpp"

#include <cstdint>
#include <vector>

namespace vm::detail {

/// Per phase, its voxels that the bcc lattice of the voxel grid cannot hold.
/// That lattice's nodes are the voxel centres whose indices are all even or
/// all odd; every other centre is the midpoint of a lattice edge along the
/// axis whose index parity differs from the other two, where create
/// interpolates the values of the edge's ends linearly. A voxel whose two
/// neighbours along that axis share one label other than its own is therefore
/// outvoted whatever the phase functions (a structure one voxel thin there).
/// One between two other labels is outvoted unless its phase's values at the
/// edge's ends (`field`, on the voxel grid) sum to more than any other
/// phase's by `margin` (what snapping may take from it: a two-voxel label of
/// CGAL's liver lay between two others, and the bcc lattice lost it).
/// At the volume's edge, an edge whose far end is the node the grid adds past
/// the last voxel (an odd number of cells) is judged as any other, the field
/// holding the last voxel's values there; one that leaves the grid is not held.
std::vector<int64_t> voxels_bcc_cannot_hold(const PhaseVoxels& voxels, const PhaseField& field, double margin);

} // namespace vm::detail
