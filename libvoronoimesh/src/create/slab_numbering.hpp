#pragma once
/// @file create/slab_numbering.hpp
/// The ids of the limit points create's slabs found, in order of first
/// appearance over the slabs in order (key order within a slab), found for all
/// slabs in parallel.

#include "create/lattice.hpp"
#include "create/limit_key.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// global[i][k] is the id of key k of the i-th slab; the keys new in that slab
/// (not in an earlier one) have ids fresh[i]..fresh[i+1]-1, and fresh.back()
/// is how many distinct points there are.
struct SlabNumbering {
  std::vector<std::vector<int32_t>> global;
  std::vector<int32_t> fresh;
};

/// Numbers the keys of consecutive slabs first, first+1, ... (`slab_keys`,
/// each slab's keys distinct) as one pass over them in order would, the
/// slabs in parallel: each looks its keys up only in the earlier slabs that can
/// hold them, those whose tetrahedra use all of a key's lattice nodes. (The
/// serial pass took 0.4-0.7 s of every repair round of a 4M-triangle create.)
SlabNumbering number_slabs(const TetLattice& lattice, std::span<const std::vector<LimitKey>* const> slab_keys,
                           int first);

} // namespace vm::detail
