#pragma once
/// @file create/tiny_loops.hpp
/// Closed triple curves far smaller than a cell, which create snaps away.
///
/// Where a third phase nearly ties the two that meet on a lattice edge at the
/// point they cross it, but stays below them there, the three meet on a loop
/// around the edge, as small as the third phase's shortfall: on random label
/// volumes loops of three nodes 0.0004-0.006 of a cell across, and their
/// triangles' quality 0.003-0.012 after any number of iterations (no collapse
/// can shrink a loop of three nodes further, and none may remove it). Snapping
/// at the edge's nodes ties the third phase with the others there, so that it
/// leads where they cross (or falls back from the edge): the loop goes.

#include "create/create_slabs.hpp"
#include "mesh/topology.hpp"

#include <cstdint>
#include <vector>

namespace vm::detail {

/// The vertices of every closed triple curve (find_junctions()'s TripleCurve::closed())
/// whose vertices lie within `extent` of each other along every axis; ascending.
std::vector<int32_t> tiny_loop_vertices(const std::vector<Vec3>& points, const Triangles& triangles,
                                        const std::vector<PhasePair>& pairs, double extent);

/// The lattice nodes of the tiny_loop_vertices() of `mesh`; sorted, no repeats.
std::vector<int64_t> tiny_loop_nodes(const SlabsMesh& mesh, double extent);

} // namespace vm::detail
