#pragma once
/// @file mesh/patch_connectivity.hpp
/// The patch-split mesh's vertices and halfedge connectivity, written straight
/// into OpenMesh's arrays. Which triangles meet at each vertex copy (the corner
/// classes) and which edges are glued follow from the edge table, so adding
/// faces one by one (add_face looks each halfedge up, relinks boundary loops
/// and walks fans) redoes work whose answer is known: it was 40% of a build.
/// Each step is a parallel pass over nodes, edges or halfedges.

#include "mesh/topology.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstdint>
#include <vector>

namespace vm::detail {

/// The glued partner of each triangle halfedge (h = 3t + k, mesh/topology.hpp):
/// the other halfedge of its node-edge when that edge lies inside one patch
/// (is_patch_interior()), else -1.
std::vector<int32_t> glued_partners(const EdgeTable& et, const Triangles& tris, const std::vector<PhasePair>& pairs);

/// The corner classes: corners of one node joined across glued edges (each
/// class is one fan of one patch, and becomes one OpenMesh vertex). Sets
/// vertex_of_corner[3t + k], the class of corner k of triangle t, numbered
/// node by node (each node's classes in the order of their first triangle),
/// and copy_off (num_nodes + 1 entries): node n's classes are
/// [copy_off[n], copy_off[n + 1]).
void number_corner_classes(const NodeTriangles& nt, const Triangles& tris, const std::vector<int32_t>& partner,
                           std::vector<int32_t>& vertex_of_corner, std::vector<int32_t>& copy_off);

/// Adds the faces of `tris` to `mesh`, whose vertices (one per corner class)
/// are added already: face t is triangle t, its halfedge the one from corner 2
/// to corner 0 (as add_face() stores it), the edges numbered as add_face() in
/// triangle order would number them; a glued halfedge shares its edge with its
/// partner, every other one has its own edge with a boundary opposite, and a
/// vertex on a boundary has its outgoing boundary halfedge.
/// @return false, leaving `mesh` untouched, when the classes are not fans that
///         this can link alone: two unglued halfedges joining the same two
///         vertices, or a vertex with more than one gap (add_face() decides those)
bool connect_patch_faces(OMesh& mesh, const Triangles& tris, const std::vector<int32_t>& vertex_of_corner,
                         const EdgeTable& et, const std::vector<int32_t>& partner);

} // namespace vm::detail
