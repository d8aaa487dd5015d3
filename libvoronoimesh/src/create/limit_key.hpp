#pragma once
/// @file limit_key.hpp
/// The exact identity of a mesh vertex: the lattice element its point lies in
/// (up to four lattice nodes, sorted) and the point's barycentric coordinates in
/// that element as reduced integers. Two vertices are the same exactly when their
/// points are the same, whichever tetrahedron computed them: the coordinates only
/// depend on values at the element's own nodes, and are computed exactly.

#include "core/exact.hpp"

#include <array>
#include <cstdint>
#include <functional>

namespace vm::detail {

struct LimitKey {
  std::array<int64_t, 4> nodes{-1, -1, -1, -1}; ///< sorted; unused slots -1
  std::array<i128, 4> weights{};                ///< positive, reduced by their gcd
  int count = 0;                                ///< nodes used (1..4)

  bool operator==(const LimitKey& o) const {
    return count == o.count && nodes == o.nodes && weights == o.weights;
  }
  bool operator<(const LimitKey& o) const {
    if (count != o.count) return count < o.count;
    if (nodes != o.nodes) return nodes < o.nodes;
    return weights < o.weights;
  }
};

struct LimitKeyHash {
  size_t operator()(const LimitKey& k) const {
    uint64_t h = 0x9e3779b97f4a7c15ull * uint64_t(k.count + 1);
    auto mix = [&](uint64_t v) {
      h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    };
    for (int c = 0; c < k.count; ++c) {
      mix(uint64_t(k.nodes[c]));
      mix(uint64_t(k.weights[c]));
      mix(uint64_t(k.weights[c] >> 64));
    }
    return size_t(h);
  }
};

} // namespace vm::detail
