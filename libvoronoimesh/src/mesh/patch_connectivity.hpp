#pragma once
/// @file mesh/patch_connectivity.hpp
/// The halfedge connectivity of the patch-split mesh written straight into
/// OpenMesh's arrays. The corner classes already say which triangles meet at
/// each vertex copy and the edge table which edges are glued, so adding faces
/// one by one (add_face looks each halfedge up, relinks boundary loops and
/// walks fans) redoes work whose answer is known: it was 40% of a build.

#include "mesh/topology.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstdint>
#include <vector>

namespace vm::detail {

/// Adds the faces of `tris` to `mesh`, whose vertices (one per corner class,
/// vertex_of_corner[3t + k] that of corner k of triangle t) are added already:
/// face t is triangle t, its halfedge the one from corner 2 to corner 0 (as
/// add_face() stores it), the edges numbered as add_face() in triangle order
/// would number them; a glued edge (`glued[e]`, edge e of `et`) is one edge
/// of both triangles, every other halfedge has its own edge with a boundary
/// opposite, and a vertex on a boundary has its outgoing boundary halfedge.
/// @return false, leaving `mesh` untouched, when the classes are not fans that
///         this can link alone: two unglued halfedges joining the same two
///         vertices, or a vertex with more than one gap (add_face() decides those)
bool connect_patch_faces(OMesh& mesh, const Triangles& tris, const std::vector<int32_t>& vertex_of_corner,
                         const EdgeTable& et, const std::vector<uint8_t>& glued);

} // namespace vm::detail
