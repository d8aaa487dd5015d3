#pragma once
/// @file mpi/balance.hpp
/// Sharing the slabs out among the ranks by the work they hold. Cutting an
/// interface tetrahedron costs far more than skipping one whose nodes all have
/// the same winner, and the interface can sit in a few slabs only (the
/// weakness of equal blocks the paper names, sect. 4.4), so ranks get similar
/// amounts of weighted work rather than similar numbers of slabs.

#include "create/lattice.hpp"
#include "mpi/layers.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::mpi::detail {

/// Work of one slab: its tetrahedra, and those of them create cuts.
struct SlabWork {
  uint64_t tets = 0;
  uint64_t interface_tets = 0;
};

/// Cost of cutting an interface tetrahedron, in tetrahedra skipped: fitting
/// create's time to a x tetrahedra + b x cut tetrahedra on the four spheres and
/// voronoi30 at 128^3 (one thread) gave about 80 ns and 5.4 us. Rough, and it
/// only shifts slab boundaries.
constexpr uint64_t kCutCost = 64;

/// The slabs whose first grid layer lies in `block`.
std::array<int, 2> slabs_starting_in(const vm::detail::TetLattice& lattice, Layers block);

/// The work of slabs slabs[0]..slabs[1], from the winning phase at every grid
/// node of layers `layers` (node (i, j, z) at labels[node_index - first node of
/// layers[0]]), which must hold those slabs' nodes: a block of lattice blocks
/// whose nodes do not all have the same winner is cut (create/create.cpp, cut_slab).
std::vector<SlabWork> slab_work(const vm::detail::TetLattice& lattice, const GridSpec& grid,
                                std::span<const int32_t> labels, Layers layers, std::array<int, 2> slabs);

/// Contiguous, non-empty slab ranges, one per rank in order, of similar weight
/// (tets + kCutCost x interface tets). Needs ranks <= work.size().
std::vector<std::array<int, 2>> balance_slabs(std::span<const SlabWork> work, int ranks);

} // namespace vm::mpi::detail
