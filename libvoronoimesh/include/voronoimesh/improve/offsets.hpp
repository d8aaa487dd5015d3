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
  size_t nodes = 0;      ///< nodes of the class
  double rms = 0;        ///< RMS offset, in the units of the points (of the nodes not unresolved)
  double max = 0;        ///< largest offset, in the units of the points (likewise)
  int32_t farthest = -1; ///< the node with the largest offset (-1: none)
  /// Junction nodes whose phases meet nowhere near them (interface_offsets()),
  /// left out of rms and max; always 0 for surface nodes.
  size_t unresolved = 0;
};

/// Offsets by node class: surface nodes (two phases meet), triple-curve nodes
/// (three) and quadruple or higher points (four or more).
using InterfaceOffsets = std::array<NodeOffsets, 3>;

/// How far each node lies from where its phases are equal: on the surface, the
/// triple curve or the quadruple point it stands for.
/// - A surface node's offset is the length of the Newton step onto phi_i =
///   phi_j (the first-order distance: exact for planes, such as Voronoi seeds'
///   bisectors, within O(offset^2) otherwise), measured in 3D, also on the box.
/// - A junction node (three or more phases) is led by least-squares Newton
///   steps onto every pair of its phases, moving only within the box faces it
///   lies on, to where they meet: its offset is the distance to that point.
///   Where the steps do not settle within the domain, or another phase leads
///   at the point they reach, the phase functions have no such junction near
///   the node (a grid too coarse to resolve a topology finer than itself made
///   the mesh's: a quadruple point of four phases that nearly tie where a
///   fifth leads); the node is counted as `unresolved`, not in rms and max.
///   (Before 2026-12-07 it was the first Newton step's length, in 3D: such a
///   node showed steps of up to 16 h on random seed scenes.)
/// Directions no pair constrains (singular values below 1e-3 of the largest)
/// are left out of every step. Nodes of no triangle are not counted. Linear in
/// the mesh size, parallel.
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
/// as "rms_h" and "max_h" in multiples of `spacing`), for the junction classes
/// the "unresolved" nodes, and the farthest node with its position.
/// @param offsets interface_offsets() of `m`
/// @param m       the mesh
/// @param spacing the length the offsets are also given in multiples of
std::string to_json(const InterfaceOffsets& offsets, const NodeMesh& m, double spacing);

} // namespace vm
