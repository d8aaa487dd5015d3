#pragma once
/// @file detail/junction_tables.hpp
/// find_junctions() on incidence tables the caller already has (compute_stats
/// builds them for its own counts).

#include "detail/topology.hpp"
#include "voronoimesh/junctions.hpp"

namespace vm::detail {

/// The junction structure from the edge table and node phases of a mesh
/// whose triangles have the phase pairs `pairs`.
Junctions junctions_from(const std::vector<PhasePair>& pairs, const EdgeTable& et, const NodePhases& np);

} // namespace vm::detail
