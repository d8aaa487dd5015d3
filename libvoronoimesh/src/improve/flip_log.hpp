#pragma once
/// @file improve/flip_log.hpp
/// The flips of one call of the flip pass, in order, any of them undone exactly.
///
/// Flipping an edge back restores its quad's first diagonal but not the mesh:
/// OpenMesh keeps each face on the same halfedge of the edge, so the two faces
/// come back swapped (and the corners' outgoing halfedges and the faces' first
/// halfedges moved). Face numbers are what the crossing index files triangles
/// by, so an undo that swaps them makes every flipped triangle look changed to
/// the next check. Four flips of an edge restore its halfedge cycles, and the
/// handles a flip moves are kept here, so undo() gives back the mesh as it was,
/// face numbers and ring order included.
///
/// Some flips can be undone alone: flip Y's undo is exact when no flip after Y
/// that stays shares a node with Y (with_dependents()), since then the four
/// corners and two faces of Y are as Y left them. The mesh is then the one the
/// other flips alone make, in their order: a flip that stays and came after an
/// undone one shares no node with it (so its quad, gain and new edge are what
/// they would have been), and one that came before it is undone by nothing.

#include "voronoimesh/mesh/interface_mesh.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm::detail {

class FlipLog {
public:
  /// Flips `edge` of `mesh`'s OpenMesh (the caller checked that it may: flip_gain()) and logs
  /// it with its quad's nodes: the edge's two, then the two opposite. triangles() is not updated here.
  void flip(InterfaceMesh& mesh, OMesh::EdgeHandle edge, const std::array<int32_t, 4>& quad);
  /// Flags, besides those flagged in `undo` (one flag a logged flip), every
  /// flip after a flagged one that shares a node with it, in log order (so a
  /// flip flagged that way flags those after it too), but those in `undone`
  /// (undone before: no longer in the mesh, they hold nothing back): what must
  /// be undone with them for undo() to be exact. `node_count`: the mesh's nodes.
  void with_dependents(std::vector<uint8_t>& undo, const std::vector<uint8_t>& undone, size_t node_count) const;
  /// Undoes the flips flagged in `which` (one flag a logged flip, closed under
  /// with_dependents()), last first, and updates the mesh's triangles and
  /// rings. The log keeps them: flag each flip once over all calls.
  void undo(InterfaceMesh& mesh, const std::vector<uint8_t>& which);

  bool empty() const { return edges_.empty(); }
  size_t size() const { return edges_.size(); }
  /// The flipped edges, in order (an edge may appear more than once).
  const std::vector<int32_t>& edges() const { return edges_; }
  /// The nodes of each flipped edge before its flip.
  std::array<int32_t, 2> edge_nodes(size_t flip) const { return {quads_[flip][0], quads_[flip][1]}; }
  /// The nodes of a flip's quad: its edge's two before the flip, then the two opposite.
  const std::array<int32_t, 4>& quad(size_t flip) const { return quads_[flip]; }
  /// The two faces of a flipped edge (a flip changes just those).
  std::array<int32_t, 2> faces_of(size_t flip) const {
    return {before_[flip].faces[0].idx(), before_[flip].faces[1].idx()};
  }
  /// The two faces of every flipped edge from flip `first` on, in order.
  std::vector<int32_t> faces(size_t first = 0) const;

private:
  /// What a flip moves besides its halfedge cycles: the first halfedge of its
  /// two faces and the outgoing halfedge of its four corners.
  struct Handles {
    std::array<OMesh::FaceHandle, 2> faces;
    std::array<OMesh::HalfedgeHandle, 2> face_first;
    std::array<OMesh::VertexHandle, 4> corners;
    std::array<OMesh::HalfedgeHandle, 4> corner_out;
  };
  std::vector<int32_t> edges_;
  std::vector<std::array<int32_t, 4>> quads_;
  std::vector<Handles> before_;
};

} // namespace vm::detail
