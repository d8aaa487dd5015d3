#pragma once
/// @file improve/smooth.hpp
/// Force-based smoothing (paper sect. 4.2.1 and Algorithm 4, lines 1-5).

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <vector>

namespace vm {

/// Parameters of add_smoothing_forces() (the smooth pass); defaults are the paper's.
struct SmoothParams {
  /// Rest length l0 = rest_factor x RMS edge length (eq. 3). 1.2 is the paper's
  /// (and DistMesh's) empirical factor: slightly long springs spread the nodes.
  double rest_factor = 1.2;
};

/// RMS edge length over all node-level edges (eq. 3 without the factor), except
/// the edges on the box faces of a closed mesh (fields/outside_phase.hpp).
/// The same for any thread count and node numbering (a fixed-point sum).
/// @param mesh the mesh
/// @return the RMS edge length, in the units of the points; 0 without edges
double rms_edge_length(const InterfaceMesh& mesh);

/// Mean length of the edges at node n (to its node-level neighbours).
/// @param mesh the mesh
/// @param n    a node id, in [0, mesh.num_nodes())
/// @return the mean length, in the units of the points; 0 for a node without edges
double mean_edge_length_at(const InterfaceMesh& mesh, int32_t n);

/// Number of constraints on node n: its phases plus the domain box faces it lies
/// on. 2 is a surface node, 3 a triple-curve node (or a surface node on the box),
/// 4 and more a point that forces must not move.
/// @param mesh the mesh
/// @param n    a node id, in [0, mesh.num_nodes())
int junction_order(const InterfaceMesh& mesh, int32_t n);

/// Removes the components of `d` that would take a node off the box faces in
/// `box_faces` (InterfaceMesh::box_faces() bits).
/// @param d         the displacement, changed in place
/// @param box_faces the box faces the node lies on: bit 2a for the min side of axis a, bit 2a+1 for the max
void constrain_to_box(Vec3& d, uint8_t box_faces);

/// Adds to `delta` (one entry per node) the force on every node (Algorithm 4),
/// by its order of constraints: its phases and box faces, not counting the
/// outside phase of a closed mesh (whose surfaces are the box faces):
///  - order > 3: none (quadruple and higher points are not moved by forces);
///  - order 3, or a neighbour of order >= 3: the half-Laplacian attraction
///    f_L = (y - x)/2 averaged over neighbours of the same or a higher type
///    (phases and box faces of x contained in y's); except on a closed triple
///    curve of three nodes, where each node moves along the curve toward
///    the farther of its two neighbours there, by a quarter of the difference
///    (the Laplacian would bunch them; not in the paper);
///  - otherwise the DistMesh repulsion f_D = (x-y)/|x-y| max(l0 - |x-y|, 0),
///    averaged over all neighbours;
///  every force is kept along the node's surface or curve: its components
///  along grad phi_a - grad phi_b of `field` (for each other phase b of the
///  node) and across its box faces are removed. The paper does this for surface
///  nodes; on a triple curve the half-Laplacian's pull toward the curve's centre
///  of curvature would otherwise hold nodes off the curve (about 0.1 h).
/// @param mesh   the mesh
/// @param field  the phase functions, for the surface normals
/// @param params the rest length factor: l0 = params.rest_factor x rms_edge_length(mesh) (eq. 3)
/// @param delta  the displacement of every node, one entry per node; the forces are added to it
void add_smoothing_forces(const InterfaceMesh& mesh, const PhaseField& field, const SmoothParams& params,
                          std::vector<Vec3>& delta);

/// The same with the rest length l0 given: a distributed run takes the RMS edge
/// length over the whole mesh, not over one rank's part of it.
/// @param mesh        the mesh
/// @param field       the phase functions, for the surface normals
/// @param rest_length the rest length l0 of eq. 3, in the units of the points
/// @param delta       the displacement of every node, one entry per node; the forces are added to it
void add_smoothing_forces_with_rest_length(const InterfaceMesh& mesh, const PhaseField& field, double rest_length,
                                           std::vector<Vec3>& delta);

} // namespace vm
