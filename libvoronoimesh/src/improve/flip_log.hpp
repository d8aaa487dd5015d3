#pragma once
/// @file improve/flip_log.hpp
/// The flips of one attempt of the flip pass, in order, undone exactly.
///
/// Flipping an edge back restores its quad's first diagonal but not the mesh:
/// OpenMesh keeps each face on the same halfedge of the edge, so the two faces
/// come back swapped (and the corners' outgoing halfedges and the faces' first
/// halfedges moved). Face numbers are what the crossing index files triangles
/// by, so an undo that swaps them makes every flipped triangle look changed to
/// the next check. Four flips of an edge restore its halfedge cycles, and the
/// handles a flip moves are kept here, so undo() gives back the mesh as it was,
/// face numbers and ring order included.

#include "voronoimesh/mesh/interface_mesh.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm::detail {

class FlipLog {
public:
  /// Flips `edge` of `mesh`'s OpenMesh (the caller checked that it may: flip_gain()) and logs
  /// it with its nodes before the flip. triangles() is not updated here.
  void flip(InterfaceMesh& mesh, OMesh::EdgeHandle edge, const std::array<int32_t, 2>& nodes);
  /// Undoes every logged flip, last first, updates the mesh's triangles and
  /// rings, and empties the log.
  void undo(InterfaceMesh& mesh);

  bool empty() const { return edges_.empty(); }
  size_t size() const { return edges_.size(); }
  /// The flipped edges, in order (an edge may appear more than once).
  const std::vector<int32_t>& edges() const { return edges_; }
  /// The nodes of each flipped edge before its flip.
  const std::vector<std::array<int32_t, 2>>& nodes() const { return nodes_; }
  /// The two faces of every flipped edge (a flip changes just those), in order.
  std::vector<int32_t> faces() const;

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
  std::vector<std::array<int32_t, 2>> nodes_;
  std::vector<Handles> before_;
};

} // namespace vm::detail
