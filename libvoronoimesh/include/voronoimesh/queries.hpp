#pragma once
/// @file queries.hpp
/// Questions a program asks of a finished mesh: which surfaces there are and
/// how large, how much volume each phase encloses, where the triple curves run
/// and how long they are, which phase a file label is. NodeMesh (node_mesh.hpp)
/// holds the nodes, triangles and phase pairs themselves; find_junctions()
/// (junctions.hpp) the phases at each node, the triple curves and quadruple points.

#include "voronoimesh/junctions.hpp"
#include "voronoimesh/node_mesh.hpp"

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
std::vector<Surface> surfaces(const NodeMesh& m);

/// The volume of each phase inside the domain box m.domain, by phase id, from
/// its boundary by the divergence theorem (exact for the piecewise-flat mesh).
/// A phase whose boundary is closed either lies inside the box (its volume is
/// what the boundary encloses) or surrounds every other phase and covers the
/// box's walls (what its boundary encloses is then negative, and its volume is
/// the box's plus that). nullopt where the mesh cannot tell: a phase with open
/// boundary edges (surfaces of an open mesh that end on the box), a phase
/// without triangles, the exterior phase of a closed mesh (closed_domain.hpp).
/// Every other phase of a closed mesh (MeshOptions::close) has one, and
/// together they fill the box. Size: one more than the largest phase id in
/// m.pairs (or m.phase_names.size() if larger). Linear-logarithmic in the mesh size.
std::vector<std::optional<double>> phase_volumes(const NodeMesh& m);

/// The positions of a triple curve's nodes, in chain order (a closed curve's
/// first point repeated at the end), e.g. to draw it or fit a spline.
std::vector<Vec3> curve_points(const NodeMesh& m, const TripleCurve& curve);

/// The length of a triple curve: the sum of its edge lengths.
double curve_length(const NodeMesh& m, const TripleCurve& curve);

/// The phase id whose file label is `label` (NodeMesh::phase_labels; the id
/// itself when they are empty), or -1 if no phase has it.
int32_t phase_of_label(const NodeMesh& m, int32_t label);

} // namespace vm
