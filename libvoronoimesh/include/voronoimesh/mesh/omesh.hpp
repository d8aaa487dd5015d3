#pragma once
/// @file mesh/omesh.hpp
/// OMesh: OpenMesh's triangle mesh with removals that cost what they remove.
/// OpenMesh deletes by marking and compacts in garbage_collection(), which
/// visits every element (118-127 ms on a million triangles, as much as a
/// whole rebuild: docs/edits-in-place.md); here each removed element's slot
/// is filled by the last element of its kind instead, and only the handles
/// that pointed at the moved one are mended.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace vm {

/// OpenMesh traits: double-precision points.
struct MeshTraits : public OpenMesh::DefaultTraitsDouble {};

/// Where a swap-removal put an element: the last element of its kind, at index
/// `from`, now sits at `to` (the slot of a removed one), and the arrays are one
/// shorter. Where from == to the removed element was the last one.
struct SlotMove {
  int32_t from = -1; ///< the moved element's index before
  int32_t to = -1;   ///< its index after
};

/// The moves a removal made, in the order made: an array indexed like the
/// mesh's faces (edges, vertices) stays in step by replaying them,
/// `a[m.to] = a[m.from]; a.pop_back();` for each move m.
struct SlotMoves {
  std::vector<SlotMove> faces;    ///< moves of faces
  std::vector<SlotMove> edges;    ///< moves of edges (halfedges 2e and 2e + 1 with edge e)
  std::vector<SlotMove> vertices; ///< moves of vertices
};

/// The elements `moves` left at another index, as (index before, index
/// after), ascending by the index before; every other element is where it was
/// or was removed. Costs the moves, not the array: for what follows an edit
/// sparsely (CrossingIndex::renumber_after_removal()).
std::vector<std::pair<int32_t, int32_t>> moved_by(std::span<const SlotMove> moves);

/// The OpenMesh triangle mesh of InterfaceMesh (double-precision points),
/// with swap-removal of faces.
class OMesh : public OpenMesh::TriMesh_ArrayKernelT<MeshTraits> {
public:
  /// Removes faces, and the edges and vertices they leave without a face:
  /// the halfedges of a removed face that keep their edge become boundary,
  /// linked into boundary loops as OpenMesh's delete_face() links them, and
  /// each vertex left with a boundary keeps a boundary halfedge as its
  /// outgoing one. A vertex may be left with more than one boundary gap
  /// (OpenMesh's "complex" vertex); add_face() can close them again. Indices
  /// then close up by swap-removal (the elements' properties move with them),
  /// so the cost is that of the removed elements and their neighbours, not of
  /// the mesh. No status properties are needed.
  /// Faces in `holes` are unlinked the same way but keep their slots, empty
  /// (a hole moves like any face when it is the last one), for faces that
  /// take their place and index (fill_hole()).
  /// @param faces the faces to remove, distinct, indices into faces()
  /// @param moves appended to: the moves of faces, edges and vertices made
  /// @param holes faces to unlink whose slots stay, distinct, none in `faces`
  void remove_faces(std::span<const int32_t> faces, SlotMoves& moves, std::span<const int32_t> holes = {});
  /// Moves the last face (one just added) into `hole`, an empty slot that
  /// remove_faces() left, and shortens the faces by one.
  /// @param hole the slot, below the last face
  void fill_hole(int32_t hole);

private:
  /// Unlinks face f from its halfedges, and the edges it leaves without a
  /// face from the mesh; appends those edges to `dead_edges` and f's vertices
  /// to `touched`.
  void unlink_face(int32_t f, std::vector<int32_t>& dead_edges, std::vector<int32_t>& touched);
  /// Unlinks edge e, which has no face on either side, from its boundary
  /// loops and from its vertices' outgoing halfedges; a vertex it leaves
  /// without edges gets an invalid halfedge.
  void unlink_edge(EdgeHandle e);
  /// Moves the last face into slot f (which no halfedge names any more); the
  /// last may be a hole.
  void fill_face_slot(int32_t f, int32_t last);
  /// Moves the last edge into slot e (unlinked).
  void fill_edge_slot(int32_t e, int32_t last);
  /// Moves the last vertex into slot v (no halfedge ends there).
  void fill_vertex_slot(int32_t v, int32_t last);
};

} // namespace vm
