#pragma once
/// @file improve/edge_lengths.hpp
/// The sum behind rms_edge_length(), over some of the nodes: a distributed run
/// adds each rank's sum over the edges it owns.

#include "core/fixed_point_sum.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstdint>
#include <span>

namespace vm::detail {

struct SquaredEdgeLengths {
  FixedPointSum sum; ///< in units of the squared domain diagonal
  uint64_t edges = 0;
};

/// Squared lengths of the node-level edges (v, w) with v < w and v `counted`
/// (every node when `counted` is empty), without a closed mesh's box-face edges.
SquaredEdgeLengths squared_edge_lengths(const InterfaceMesh& mesh, std::span<const uint8_t> counted);

} // namespace vm::detail
