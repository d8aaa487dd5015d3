#pragma once
/// @file improve/clamp.hpp
/// Inversion-proof clamping of displacements (paper sect. 4.2.3, eq. 5, Algorithm 3).

#include "voronoimesh/mesh/interface_mesh.hpp"

#include <vector>

namespace vm {

/// Parameters of clamp_displacements() (the clamp pass); defaults are the paper's.
struct ClampParams {
  /// Fraction of the largest safe step a node may take (eq. 5): 1/2, so that no
  /// triangle can invert whatever its other nodes do.
  double factor = 0.5;
};

/// Algorithm 3: the largest s >= 0 such that v0 + s*delta stays in v0's region of
/// triangle (v0, v1, v2): the side of each of the three midlines (through the
/// edge midpoints) on which v0 lies. While every corner stays in its own region
/// the triangle cannot invert. +infinity when delta never leaves the region;
/// 0 for a degenerate triangle.
/// @param delta the displacement of v0
/// @param v0    the corner that moves
/// @param v1    the second corner
/// @param v2    the third corner
/// @return the largest safe fraction s of `delta`, in [0, +infinity]
double clamp_step(const Vec3& delta, const Vec3& v0, const Vec3& v1, const Vec3& v2);

/// The largest s >= 0 such that x + s*delta stays inside the domain box along
/// every axis whose faces x is not held on (`box_faces`, bits as
/// InterfaceMesh::box_faces()); +infinity when delta never leaves it. An axis
/// along which x is already outside sets no limit.
/// @param delta     the displacement of the node
/// @param x         the node's position
/// @param domain    the domain box
/// @param box_faces the box faces the node lies on (its moves keep it there)
/// @return the largest fraction s of `delta` that keeps the node inside, in [0, +infinity]
double box_step(const Vec3& delta, const Vec3& x, const Box& domain, uint8_t box_faces);

/// Scales each node's displacement by min(1, factor x min over its triangles of
/// clamp_step) (eq. 5), and by factor x box_step() besides, so that a node never
/// leaves the domain box nor reaches its faces: a surface meeting a box face at
/// a grazing angle would otherwise pull its nodes out through the face (not in
/// the paper, whose domains are periodic or closed). Each node's scale depends
/// on its own move alone, so the result is the same for any thread count.
/// @param mesh   the mesh, at the positions before the move, with triangles()
///               current (as every pass leaves it)
/// @param params the fraction of the largest safe step (ClampParams::factor)
/// @param delta  the displacement of every node, one entry per node; scaled in place
void clamp_displacements(const InterfaceMesh& mesh, const ClampParams& params, std::vector<Vec3>& delta);

} // namespace vm
