#pragma once
/// @file improve/polish.hpp
/// Moves that raise the worst triangles where the paper's forces have settled
/// (the polish pass; not in the paper).

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstddef>
#include <vector>

namespace vm {

/// Parameters of add_polish_moves() (the polish pass).
struct PolishParams {
  /// The nodes of triangles below this quality are polished.
  double below = 0.7;
};

/// Adds to `delta` (one entry per node, the pending moves) a move of nodes of
/// the triangles below PolishParams::below that raises the smallest quality of
/// the node's triangles: surface nodes in their tangent plane, curve nodes
/// along their curve, the best of a few trial moves, taken back to the node's
/// surface or curve by Newton steps (eq. 4), if it still beats where the node
/// is. A node on the box moves within its box faces (a surface node there
/// along the line where its surface meets them); quadruple and higher points,
/// and curve nodes on the box, stay. Nodes are
/// taken worst triangles first, none next to another one taken (each judged
/// with its neighbours where they are), so the moves do not depend on the
/// threads. No triangle of a moved node turns by 60 degrees or more.
/// DistMesh forces settle where the springs balance, which near a tightly
/// turning triple curve can leave a thin triangle that the quality floor then
/// keeps from getting worse but nothing makes better.
/// @param mesh   the mesh
/// @param field  the original phase functions
/// @param params the quality below which a triangle's corners are polished
/// @param delta  the pending moves; the polish moves are added
/// @return the nodes moved
size_t add_polish_moves(const InterfaceMesh& mesh, const PhaseField& field, const PolishParams& params,
                        std::vector<Vec3>& delta);

} // namespace vm
