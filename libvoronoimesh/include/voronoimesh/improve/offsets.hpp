#pragma once
/// @file improve/offsets.hpp
/// How far a mesh's nodes lie from the interface of the phase functions it
/// was made from: its accuracy, which quality measures cannot show.

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <array>
#include <string>

namespace vm {

/// The offsets of one class of nodes (interface_offsets()).
struct NodeOffsets {
  size_t nodes = 0;     ///< nodes of the class
  double rms = 0;       ///< RMS offset, in the units of the points
  double max = 0;       ///< largest offset, in the units of the points
  int32_t farthest = -1; ///< the node with the largest offset (-1: none)
};

/// Offsets by node class: surface nodes (two phases meet), triple-curve nodes
/// (three) and quadruple or higher points (four or more).
using InterfaceOffsets = std::array<NodeOffsets, 3>;

/// How far each node lies from where its phases are equal: on the surface, the
/// triple curve or the quadruple point it stands for. The offset is the length
/// of the least-norm Newton step onto phi_i = phi_j for every pair of the
/// node's phases (the first-order distance: exact for planes, such as Voronoi
/// seeds' bisectors, within O(offset^2) otherwise). A node on the domain box
/// is measured in 3D, not along the box: its offset is a lower bound.
/// Directions no pair constrains (singular values below 1e-3 of the largest,
/// as where four phases' quadruple point lies far off along a near-degenerate
/// curve) are left out. Nodes of no triangle are not counted. Linear in the
/// mesh size, parallel.
/// @param m     the mesh; its phase ids must be phases of `field`
/// @param field the phase functions it was made from (the original, unsnapped ones)
/// @return the offsets of surface, triple-curve and quadruple-point nodes
InterfaceOffsets interface_offsets(const NodeMesh& m, const PhaseField& field);

/// Three lines, one per node class, with the offsets in units of `spacing`
/// (the grid spacing of the run, "h") and the farthest node of each.
/// @param offsets interface_offsets() of `m`
/// @param m       the mesh
/// @param spacing the length the offsets are given in multiples of
std::string to_text(const InterfaceOffsets& offsets, const NodeMesh& m, double spacing);

/// One JSON object: "spacing", and per class ("surface", "triple_curve",
/// "quadruple_point") its nodes, rms and max (in the units of the points, and
/// as "rms_h" and "max_h" in multiples of `spacing`) and the farthest node with
/// its position.
/// @param offsets interface_offsets() of `m`
/// @param m       the mesh
/// @param spacing the length the offsets are also given in multiples of
std::string to_json(const InterfaceOffsets& offsets, const NodeMesh& m, double spacing);

} // namespace vm
