#pragma once
/// @file mesh/junction_tables.hpp
/// find_junctions() on incidence tables the caller already has (compute_stats
/// builds them for its own counts).

#include "mesh/topology.hpp"
#include "voronoimesh/mesh/junctions.hpp"

namespace vm::detail {

/// The junction structure from the edge table and node phases of a mesh
/// whose triangles have the phase pairs `pairs`.
Junctions junctions_from(const std::vector<PhasePair>& pairs, const EdgeTable& et, const NodePhases& np);

} // namespace vm::detail
