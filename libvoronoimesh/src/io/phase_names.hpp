#pragma once
/// @file io/phase_names.hpp
/// How the writers name phases, phase pairs and junctions, the same in every
/// format: a phase is its label (NodeMesh::label_of()), followed by "-" and
/// its name when it has one ("1-sphere1"); the characters of a name other than
/// letters, digits, '.', '+' and '-' become '-', so a token is safe in a file
/// name or an OBJ group name. Several phases are joined by '_'
/// ("0-outside_1-sphere1"). Phase colours (NodeMesh::phase_colors) are read
/// here too, for the formats that hold them.

#include "voronoimesh/mesh/node_mesh.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace vm::io::detail {

/// The number of phases of `m`: enough for every pair, name and label.
size_t phase_count(const NodeMesh& m);

/// The name of phase `p`, "" when it has none.
std::string phase_name(const NodeMesh& m, int32_t p);

/// The display colour of phase `p`, if it has one.
std::optional<Rgb> phase_color(const NodeMesh& m, int32_t p);

/// True when some phase of `m` has a display colour: the formats that can hold
/// colours then write them.
bool has_phase_colors(const NodeMesh& m);

/// "label" or "label-name" (see the file comment).
std::string phase_token(const NodeMesh& m, int32_t p);

/// The tokens of `phases` joined by '_'.
std::string phases_token(const NodeMesh& m, std::span<const int32_t> phases);

/// The distinct phase pairs of the triangles, ascending. Writers number the
/// surfaces by this order, from 1 (MSH physical surfaces, MEDIT references).
std::vector<PhasePair> distinct_pairs(const NodeMesh& m);

/// For each triangle, the index of its pair in `pairs` (from distinct_pairs(m)).
std::vector<int32_t> pair_indices(const NodeMesh& m, const std::vector<PhasePair>& pairs);

} // namespace vm::io::detail
