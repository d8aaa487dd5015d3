#pragma once
/// @file check/validate_part.hpp
/// validate() on part of a mesh (one rank's share of a distributed create).

#include "voronoimesh/check/validate.hpp"

#include <cstddef>

namespace vm::detail {

/// The problems validate() finds at nodes 0..checked-1 of `m`: the checks of
/// those nodes, of the edges and duplicate triangles with one of them as their
/// smallest node, and of the triangles using one of them. When every triangle
/// around those nodes is in `m`, they are exactly the problems validate() would
/// find at them in any larger mesh holding `m`, whatever the other nodes lack.
ValidationReport validate_first_nodes(const NodeMesh& m, size_t checked);

} // namespace vm::detail
