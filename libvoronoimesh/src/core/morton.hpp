#pragma once
/// @file core/morton.hpp
/// Morton (Z-order) keys of grid cells: cells close in space get close keys,
/// so work sorted by them visits memory laid out by space in order.

#include <cstdint>

namespace vm::detail {

/// The low 21 bits of x spread to every third bit.
constexpr uint64_t spread_to_every_third_bit(uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffff;
  x = (x | x << 16) & 0x1f0000ff0000ff;
  x = (x | x << 8) & 0x100f00f00f00f00f;
  x = (x | x << 4) & 0x10c30c30c30c30c3;
  x = (x | x << 2) & 0x1249249249249249;
  return x;
}

/// The Morton key of cell (i, j, k), each in [0, 2^21).
constexpr uint64_t morton_key(uint64_t i, uint64_t j, uint64_t k) {
  return spread_to_every_third_bit(i) << 2 | spread_to_every_third_bit(j) << 1 | spread_to_every_third_bit(k);
}

} // namespace vm::detail
