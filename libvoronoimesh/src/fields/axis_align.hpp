#pragma once
/// @file fields/axis_align.hpp
/// Turning a volume's direction matrix into plain axes: voronoimesh meshes an
/// axis-aligned domain, so only directions that permute or flip the axes can be
/// honoured exactly.

#include "voronoimesh/io/volume.hpp"

#include <string>

namespace vm::detail {

/// Reorders and flips the voxels of `v` so that its direction becomes the
/// identity while every voxel keeps its world position. Throws InvalidInput
/// naming `source` for an oblique direction (not a permutation with signs)
/// unless `ignore_direction`, which takes the direction as the identity.
void axis_align(io::Volume& v, const std::string& source, bool ignore_direction);

} // namespace vm::detail
