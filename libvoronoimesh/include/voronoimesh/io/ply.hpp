#pragma once
/// @file io/ply.hpp
/// Node-level PLY: one vertex per node (x, y, z as double), faces as
/// `vertex_indices`, int face properties `phase0` and `phase1` holding the
/// phases' labels (NodeMesh::phase_labels), a `comment phase <label> <name>`
/// line for every phase, and a `comment phase_color <label> <r> <g> <b>` line
/// (each in [0, 1]) for every phase with a colour (NodeMesh::phase_colors).
/// OpenMesh's own PLY writer is not used: it stores
/// float32 and splits junction copies (openmesh-probe.md, Q4).

#include "voronoimesh/mesh/node_mesh.hpp"

#include <string>

namespace vm::io {

/// Writes `m` to `path`, binary little-endian unless `ascii`. The file is written
/// to a temporary name and renamed, so a failure leaves no partial file.
/// @param m     the mesh to write
/// @param path  the file to write
/// @param ascii ASCII PLY instead of binary little-endian
/// @throws IoError if the file cannot be written
void write_ply(const NodeMesh& m, const std::string& path, bool ascii = false);

/// Reads a PLY written by write_ply (ascii or binary, either endianness; vertex
/// coordinates float or double; face list index types any integer type). The
/// labels found (in the phase comments and the faces) become phase ids 0..N-1 in
/// increasing order; phase_labels keeps them unless they are 0..N-1 already, and
/// phase_names and phase_colors come from the comments (empty if no phase has
/// a name, or a colour), so
/// writing the mesh again gives the same file. A last phase named
/// kOutsidePhaseName whose triangles all lie in the domain box's faces is the
/// mesh's outside_phase (the file says no more of a closed mesh).
/// @param path the PLY file to read
/// @return the mesh it holds
/// @throws IoError naming the file and the problem if it cannot be read, is not a PLY, is truncated, lacks
///         the phase0/phase1 face properties or describes a phase twice
NodeMesh read_ply(const std::string& path);

} // namespace vm::io
