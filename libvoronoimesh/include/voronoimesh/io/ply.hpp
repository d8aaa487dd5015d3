#pragma once
/// @file io/ply.hpp
/// Node-level PLY: one vertex per node (x, y, z as double), faces as
/// `vertex_indices`, int face properties `phase0` and `phase1`. OpenMesh's own
/// PLY writer is not used: it stores float32 and splits junction copies
/// (openmesh-probe.md, Q4).

#include "voronoimesh/node_mesh.hpp"

#include <string>

namespace vm::io {

/// Writes `m` to `path`, binary little-endian unless `ascii`. The file is written
/// to a temporary name and renamed, so a failure leaves no partial file. Throws IoError.
void write_ply(const NodeMesh& m, const std::string& path, bool ascii = false);

/// Reads a PLY written by write_ply (ascii or binary, either endianness; vertex
/// coordinates float or double; face list index types any integer type). Throws
/// IoError naming the file and the problem if it is not a PLY, is truncated, or
/// lacks the phase0/phase1 face properties.
NodeMesh read_ply(const std::string& path);

} // namespace vm::io
