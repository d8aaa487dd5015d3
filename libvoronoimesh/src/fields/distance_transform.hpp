#pragma once
/// @file fields/distance_transform.hpp
/// Exact Euclidean distance transform on a box of voxels (Felzenszwalb and
/// Huttenlocher, "Distance transforms of sampled functions", 2012: one pass of
/// lower envelopes of parabolas per axis).

#include "voronoimesh/core/types.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm::detail {

/// Replaces `f` (size[0] x size[1] x size[2] values, x fastest) by
/// min over voxels q of f(q) + |p - q|^2, distances in world units with voxel
/// sizes `spacing`. Feature voxels hold 0 and the others +infinity, so the
/// result is the squared distance to the nearest feature (infinity if none).
void squared_distance_transform(std::vector<float>& f, const std::array<int64_t, 3>& size, const Vec3& spacing);

} // namespace vm::detail
