#pragma once
/// @file create/tiny_loops.hpp
/// Closed triple curves far smaller than a cell, which create closes.
///
/// Where a third phase nearly ties the two that meet on a lattice edge at the
/// point they cross it, but stays below them there, the three meet on a loop
/// around the edge, as small as the third phase's shortfall: the two touch
/// through a tiny window in the third. On random label volumes such loops are
/// 0.0004-0.006 of a cell across, and their triangles' quality 0.003-0.012
/// after any number of iterations (no collapse can shrink a loop of three nodes
/// further, and none may remove it). They are the linear interpolation's
/// doing: a layer of the third phase one voxel thin, which its smoothed
/// indicator leads across, runs between two lattice nodes that hold the other
/// two, and the interpolation along their edge dips below them there.
/// Raising the third phase at the loop's lattice nodes, up to a tie with the
/// node's leader, lets it lead where the two cross: the window closes, and the
/// loop goes with it. The other phases are left as they are: tying them all,
/// as a wider snap does, takes the third phase's lead at nodes inside its
/// layer too, and opens a hole a cell wide (a 32^3 ellipsoid volume: a loop of
/// 0.02 voxels became one of 7, its nodes 4.6 voxels from where the phase
/// functions meet).

#include "create/create_slabs.hpp"
#include "mesh/topology.hpp"

#include <cstdint>
#include <vector>

namespace vm::detail {

/// The vertices of every closed triple curve (find_junctions()'s TripleCurve::closed())
/// whose vertices lie within `extent` of each other along every axis; ascending.
std::vector<int32_t> tiny_loop_vertices(const std::vector<Vec3>& points, const Triangles& triangles,
                                        const std::vector<PhasePair>& pairs, double extent);

/// Where create closes the tiny loops (tiny_loop_vertices()'s) of `mesh`: at
/// the lattice nodes of each loop's vertices, the loop's phase that is not on
/// its window (the surface of the loop's triangles that lie within the loop's
/// size of its box, and only of one phase pair). A loop of more than three
/// phases, or without one such window (a tiny lens of a phase on the surface of
/// two others, where two of its surfaces lie within, or none), gets
/// LoopClosing::kTieAll: every phase there ties within the wider snap, as
/// before 2026-12-07. Sorted, no repeats.
std::vector<LoopClosing> tiny_loop_closings(const SlabsMesh& mesh, double extent);

} // namespace vm::detail
