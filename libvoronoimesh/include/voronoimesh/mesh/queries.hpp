#pragma once
/// @file mesh/queries.hpp
/// Questions a program asks of a finished mesh: which surfaces there are and
/// how large, how much volume each phase encloses, where the triple curves run
/// and how long they are, which phase a file label is. NodeMesh (mesh/node_mesh.hpp)
/// holds the nodes, triangles and phase pairs themselves; find_junctions()
/// (mesh/junctions.hpp) the phases at each node, the triple curves and quadruple points.

#include "voronoimesh/mesh/junctions.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace vm {

/// The triangles of one phase pair: the interface between two phases (possibly
/// several connected patches).
struct Surface {
  PhasePair pair;                 ///< the two phases, pair[0] < pair[1]
  std::vector<int32_t> triangles; ///< its triangles, ascending
  double area = 0;                ///< total area, in the squared units of the points
};

/// Every phase pair that has triangles, ascending by pair. Linear in the mesh size.
/// @param m the mesh
/// @return one Surface per phase pair with triangles
std::vector<Surface> surfaces(const NodeMesh& m);

/// The volume of each phase inside the domain box m.domain, by phase id, from
/// its boundary by the divergence theorem (exact for the piecewise-flat mesh).
/// A phase whose boundary is closed either lies inside the box (its volume is
/// what the boundary encloses) or surrounds every other phase and covers the
/// box's walls (what its boundary encloses is then negative, and its volume is
/// the box's plus that). nullopt where the mesh cannot tell: a phase with open
/// boundary edges (surfaces of an open mesh that end on the box), a phase
/// without triangles, the exterior phase of a closed mesh (fields/outside_phase.hpp).
/// Every other phase of a closed mesh (MeshOptions::close) has one, and
/// together they fill the box. Size: one more than the largest phase id in
/// m.pairs (or m.phase_names.size() if larger). Linear-logarithmic in the mesh size.
/// @param m the mesh
/// @return the volume of each phase by phase id, in the cubed units of the points, or nullopt
std::vector<std::optional<double>> phase_volumes(const NodeMesh& m);

/// The positions of a triple curve's nodes, in chain order (a closed curve's
/// first point repeated at the end), e.g. to draw it or fit a spline.
/// @param m     the mesh
/// @param curve a triple curve of `m` (find_junctions())
/// @return one position per entry of curve.nodes
std::vector<Vec3> curve_points(const NodeMesh& m, const TripleCurve& curve);

/// The length of a triple curve: the sum of its edge lengths.
/// @param m     the mesh
/// @param curve a triple curve of `m` (find_junctions())
/// @return the length, in the units of the points
double curve_length(const NodeMesh& m, const TripleCurve& curve);

/// The phase id whose file label is `label` (NodeMesh::phase_labels; the id
/// itself when they are empty), or -1 if no phase has it.
/// @param m     the mesh
/// @param label a label as files show it
/// @return the phase id, or -1
int32_t phase_of_label(const NodeMesh& m, int32_t label);

} // namespace vm
