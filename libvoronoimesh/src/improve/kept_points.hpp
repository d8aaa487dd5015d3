#pragma once
/// @file improve/kept_points.hpp
/// Moves that carry a kept point (PhaseField::kept_points(): a voxel-faithful
/// label volume's centres of voxels in thin structures) out of its own phase,
/// for the crossing guard to undo: create puts every such point in its phase,
/// and smoothing would otherwise pull a one-voxel tube's ends back past them.

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// The triangles of `moved` whose move, from `before` to the mesh's
/// positions now, left a kept point of one of its two phases on the other
/// side: the point lay on its phase's side and within the triangle (seen along
/// its normal) before or after, and now lies on the far side; or brought one
/// nearer to it than 0.2% of its longest edge (a point on a surface is
/// in either phase by round-off), where it was not as near before. In the order of
/// `moved`; the call costs time in those triangles, not in the mesh (the guard's
/// later rounds list only those at the nodes they put back).
/// @param mesh     the mesh, its nodes moved
/// @param before   every node's position before the move
/// @param moved    the triangles that moved, ascending
/// @param field    the phase functions, which give the kept points
/// @return the triangle ids
std::vector<int32_t> triangles_losing_kept_points(const InterfaceMesh& mesh, std::span<const Vec3> before,
                                                  std::span<const int32_t> moved, const PhaseField& field);

/// Whether flipping the edge (i, j) of triangles (i, j, k) and (i, l, j) of a
/// surface into (i, l, k) and (l, j, k) would take a kept point out of its
/// phase: a flip sweeps its surface across the tetrahedron of its quad, so a
/// kept point inside it changes sides, and one of the phase it leaves would be
/// lost; so would one of the pair's phases that a new triangle comes nearer to
/// than 0.2% of its longest edge, where neither old one was as near. Asked
/// before each flip (flip_gain()): judged after the flips, a flip whose two
/// faces later flips had changed again went unjudged.
/// @param positions the nodes' positions
/// @param quad      {i, j, k, l}: the edge's nodes, then the corner of (i, j, k) and of (i, l, j)
/// @param pair      the surface's phase pair; the normal of (i, j, k), (j - i) x (k - i), points into pair[1]
/// @param field     the phase functions, which give the kept points
/// @return true if the flip would lose a kept point
bool flip_loses_kept_point(std::span<const Vec3> positions, const std::array<int32_t, 4>& quad,
                           const PhasePair& pair, const PhaseField& field);

/// The merge targets whose merge took a kept point out of its phase: node
/// merges (improve/node_merge.hpp) replace the triangles at a target and the
/// nodes merged into it by the triangles at the target, over the same ring, so
/// the old and the new triangles of a phase's boundary there close up; a kept
/// point lies between them, and was swept, where their winding numbers (sums
/// of solid angles, normals out of the phase) differ by one. Only a point that
/// was in its phase and no longer is counts, or one that a new triangle of its
/// phase comes nearer to than 0.2% of the triangle's longest edge, where
/// no old one was as near (remesh collapses took the centres
/// of a one-voxel sheet of flat voxels out of it: 14% of them).
/// @param before the mesh the trial was merged from
/// @param trial  the merged mesh (the same node ids; merged nodes left unused)
/// @param into   per node of `before`, the target it merges into, or -1
/// @param check  per node, whether this process answers for it as a target
/// @param field  the phase functions, which give the kept points
/// @return the targets, ascending
std::vector<int32_t> merges_losing_kept_points(const NodeMesh& before, const NodeMesh& trial,
                                               std::span<const int32_t> into, std::span<const uint8_t> check,
                                               const PhaseField& field);

} // namespace vm::detail
