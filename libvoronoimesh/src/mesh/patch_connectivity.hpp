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

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// The glued partner of each triangle halfedge (h = 3t + k, mesh/topology.hpp):
/// the other halfedge of its node-edge when that edge lies inside one patch
/// (is_patch_interior()), else -1.
std::vector<int32_t> glued_partners(const EdgeTable& et, const Triangles& tris, const std::vector<PhasePair>& pairs);

/// Throws TopologyError for what OpenMesh cannot take safely: a repeated node
/// in a triangle aborts inside libOpenMeshCore (openmesh-probe.md, pitfall 1),
/// and phase pairs must fit Vec2s; also for node ids out of range and a pair
/// count that differs from the triangle count. Names the triangle.
void check_node_mesh(const NodeMesh& m);

/// Throws TopologyError when more phases meet at node n (`count`) than a
/// PhaseSet holds.
void check_phase_count(size_t n, size_t count);

/// The PhaseSet of a node's distinct phases, sorted (NodePhases::of()), at
/// most as many as it holds (check_phase_count()).
inline PhaseSet phase_set(std::span<const int32_t> phases) {
  PhaseSet s;
  s.fill(-1);
  std::copy(phases.begin(), phases.end(), s.begin());
  return s;
}

/// The corner classes of node n, whose triangles (ascending) are `ts`:
/// corner_at[i] gets n's corner (3t + k) in ts[i] and class_at[i] its class,
/// the classes numbered in the order of their first triangle; returns how many
/// there are. `parent` is room the call reuses.
int32_t corner_classes_at(int32_t n, std::span<const int32_t> ts, const Triangles& tris,
                          const std::vector<int32_t>& partner, std::vector<int32_t>& parent, int32_t* corner_at,
                          int32_t* class_at);

/// The corner classes: corners of one node joined across glued edges (each
/// class is one fan of one patch, and becomes one OpenMesh vertex). Sets
/// vertex_of_corner[3t + k], the class of corner k of triangle t, numbered
/// node by node (each node's classes in the order of their first triangle),
/// and copy_off (num_nodes + 1 entries): node n's classes are
/// [copy_off[n], copy_off[n + 1]).
void number_corner_classes(const NodeTriangles& nt, const Triangles& tris, const std::vector<int32_t>& partner,
                           std::vector<int32_t>& vertex_of_corner, std::vector<int32_t>& copy_off);

/// True when two of `halfedges` (those of one node-edge) join the same two
/// vertices (classes of vertex_of_corner): connect_patch_faces() cannot link
/// such an edge unless it is glued (its first halfedge has a partner); only
/// add_faces_one_by_one() can, whose add_face() glues or refuses them.
bool joins_vertices_twice(std::span<const int32_t> halfedges, const std::vector<int32_t>& vertex_of_corner);

/// joins_vertices_twice() for some unglued edge of `et`.
bool some_edge_joins_vertices_twice(const EdgeTable& et, const std::vector<int32_t>& vertex_of_corner,
                                    const std::vector<int32_t>& partner);

/// Adds the faces of `tris` to `mesh`, whose vertices (one per corner class)
/// are added already: face t is triangle t, its halfedge the one from corner 2
/// to corner 0 (as add_face() stores it), the edges numbered as add_face() in
/// triangle order would number them; a glued halfedge shares its edge with its
/// partner, every other one has its own edge with a boundary opposite, and a
/// vertex on a boundary has its outgoing boundary halfedge. No edge may join
/// vertices twice (some_edge_joins_vertices_twice()).
/// @return false, leaving `mesh` untouched, when the classes are not fans that
///         this can link alone: a vertex with more than one gap (add_face() decides those)
bool connect_patch_faces(OMesh& mesh, const Triangles& tris, const std::vector<int32_t>& vertex_of_corner,
                         const std::vector<int32_t>& partner);

/// Adds the faces of `m` through OpenMesh's add_face(), for corner classes
/// that connect_patch_faces() cannot link alone.
/// @throws TopologyError naming the first triangle OpenMesh refuses
void add_faces_one_by_one(OMesh& mesh, const NodeMesh& m, const std::vector<int32_t>& vertex_of_corner);

} // namespace vm::detail
