#pragma once
/// @file smooth.hpp
/// Force-based smoothing (paper sect. 4.2.1 and Algorithm 4, lines 1-5).

#include "voronoimesh/field.hpp"
#include "voronoimesh/mesh.hpp"

#include <vector>

namespace vm {

/// Parameters of smooth(); defaults are the paper's.
struct SmoothParams {
  /// Rest length l0 = rest_factor x RMS edge length (eq. 3). 1.2 is the paper's
  /// (and DistMesh's) empirical factor: slightly long springs spread the nodes.
  double rest_factor = 1.2;
};

/// RMS edge length over all node-level edges (eq. 3 without the factor), except
/// the edges on the box faces of a closed mesh (closed_domain.hpp).
/// The same for any thread count and node numbering (a fixed-point sum).
double rms_edge_length(const InterfaceMesh& mesh);

/// Number of constraints on node n: its phases plus the domain box faces it lies
/// on. 2 is a surface node, 3 a triple-curve node (or a surface node on the box),
/// 4 and more a point that forces must not move.
int junction_order(const InterfaceMesh& mesh, int32_t n);

/// Removes the components of `d` that would take a node off the box faces in
/// `box_faces` (InterfaceMesh::box_faces() bits).
void constrain_to_box(Vec3& d, uint8_t box_faces);

/// Adds to `delta` (one entry per node) the force on every node (Algorithm 4):
///  - order > 3: none (quadruple and higher points are not moved by forces);
///  - order 3, or a neighbour of order >= 3: the half-Laplacian attraction
///    f_L = (y - x)/2 averaged over neighbours of the same or a higher type
///    (phases and box faces of x contained in y's);
///  - otherwise the DistMesh repulsion f_D = (x-y)/|x-y| max(l0 - |x-y|, 0),
///    averaged over all neighbours;
///  surface forces are made tangential (normal ~ grad phi_a - grad phi_b of
///  `field`), and every force is kept on the node's box faces.
void add_smoothing_forces(const InterfaceMesh& mesh, const PhaseField& field, const SmoothParams& params,
                          std::vector<Vec3>& delta);

/// The same with the rest length l0 given: a distributed run takes the RMS edge
/// length over the whole mesh, not over one rank's part of it.
void add_smoothing_forces_with_rest_length(const InterfaceMesh& mesh, const PhaseField& field, double rest_length,
                                           std::vector<Vec3>& delta);

} // namespace vm
