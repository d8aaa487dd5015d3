#pragma once
/// @file check/locate.hpp
/// Which phase of a closed mesh each point of a regular grid lies in: how a
/// label volume's voxel centres are compared with the mesh made from it.

#include "voronoimesh/core/types.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm {

/// A regular grid of points: point (i, j, k) lies at origin + spacing .* (i, j, k),
/// and has index i + size[0] * (j + size[1] * k).
struct PointGrid {
  Vec3 origin = Vec3::Zero();          ///< point (0, 0, 0)
  Vec3 spacing = Vec3::Ones();         ///< distance between neighbouring points along each axis, > 0
  std::array<int64_t, 3> size{0, 0, 0}; ///< points per axis
};

/// The phase of `closed` at every point of `grid`, found by walking rays along
/// +x from outside the box through the mesh's crossings (a triangle of pair
/// (a, b) whose normal points along +x is crossed from a into b). The rays pass
/// 7.3e-4 and 5.2e-4 spacings beside the points in y and z, so that they miss
/// nodes on lattice points. -1 for points not strictly inside the domain box
/// and along rays that hit an edge or a corner exactly or meet a crossing that
/// does not start in the phase the ray is in (a mesh that is not closed).
/// @param closed a closed mesh (NodeMesh::outside_phase >= 0)
/// @param grid   the points to locate
/// @return one phase id (or -1) per grid point
std::vector<int32_t> locate_grid_points(const NodeMesh& closed, const PointGrid& grid);

} // namespace vm
