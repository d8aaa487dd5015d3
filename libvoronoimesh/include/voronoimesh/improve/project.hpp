#pragma once
/// @file improve/project.hpp
/// Projection of nodes onto their surfaces, triple curves and quadruple points
/// (paper sect. 4.2.2, eq. 4), using the original (unsnapped) phase functions.

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <span>
#include <vector>

namespace vm {

/// Parameters of add_projection() (the project pass); defaults are the paper's.
struct ProjectParams {
  /// Pairs whose gradients differ by less than this (|grad phi_i - grad phi_j|)
  /// are skipped: the step would divide by almost zero (the paper's "special
  /// treatment" for poorly defined phase functions).
  double min_gradient_gap = 1e-6;
  /// Nodes where this many phases or more meet (0: none) take one least-squares
  /// Newton step onto all their pairs' equations phi_i = phi_j at once instead of
  /// eq. 4's mean of the pairs' steps (not in the paper). Eq. 4 converges slowly
  /// along a direction that every pair's gradient difference nearly misses (a
  /// quadruple point whose four phases' gradients nearly share a plane: on
  /// random Voronoi scenes some end 0.5 h off their point after 60 iterations);
  /// the least-squares step takes any direction at Newton's rate. Exact
  /// junctions show the exact corners' small angles (docs/algorithm.md, "Why the
  /// seed scenes miss min q 0.3"): from 3 (curve nodes too) it lowers the worst
  /// triangle; from 4 it raises it on average, and the scene default
  /// (kScenePipeline, improve/pipeline.hpp) takes it. 0 here: the paper's eq. 4.
  int least_squares_from = 0;
  /// A node's step is cut to this many times the mean length of its edges (0:
  /// uncut, the paper's). Eq. 4 is a Newton step, good where the node is within
  /// about an edge of its interface; where the phases' gradients nearly agree
  /// (a trilinear field's cell across which two labels' values run parallel,
  /// a one-voxel island's flank) it can ask for tens of edges, and the clamp
  /// pass lets a move along a node's own triangles through: one node of a
  /// voxel-faithful liver went 12 mm out (edges of 1.4), a spike of three triangles (not
  /// in the paper).
  double max_step = 1;
};

/// p(x, chi) of eq. 4: the mean of the Newton steps onto phi_i = phi_j over the
/// pairs of `phases`, scaled by 1/(|chi| - 1). Zero for fewer than two phases.
/// @param field  the original (unsnapped) phase functions
/// @param x      the node's position
/// @param phases chi, the phases meeting at the node (at most kMaxPhasesAtNode)
/// @param params which pairs to skip (ProjectParams::min_gradient_gap)
/// @return the step p(x, chi)
/// @throws InvalidInput for more than kMaxPhasesAtNode phases
Vec3 projection_step(const PhaseField& field, const Vec3& x, std::span<const int32_t> phases,
                     const ProjectParams& params = {});

/// The least-squares Newton step onto phi_i = phi_j for every pair of `phases`
/// (the step of ProjectParams::least_squares_from), moving only along the axes
/// that `box_faces` (bits as InterfaceMesh::box_faces()) leave free: repeated,
/// it leads a junction node to where its phases meet on its box faces
/// (interface_offsets()). Zero for fewer than two phases.
/// @param field     the phase functions
/// @param x         the node's position
/// @param phases    the phases meeting at the node (at most kMaxPhasesAtNode)
/// @param box_faces the box faces the node lies on
/// @throws InvalidInput for more than kMaxPhasesAtNode phases
Vec3 least_squares_step_on_faces(const PhaseField& field, const Vec3& x, std::span<const int32_t> phases,
                                 uint8_t box_faces);

/// projection_step() for node n of `mesh` at x, chi its phase set, kept on its
/// box faces: the step add_projection() adds for it.
/// @param mesh   the mesh; chi of a node is its phase set
/// @param field  the original (unsnapped) phase functions
/// @param n      a node id, in [0, mesh.num_nodes())
/// @param x      where the node is taken to be
/// @param params which pairs to skip (ProjectParams::min_gradient_gap)
/// @return the step p(x, chi) along the node's box faces
Vec3 node_projection_step(const InterfaceMesh& mesh, const PhaseField& field, int32_t n, const Vec3& x,
                          const ProjectParams& params = {});

/// Adds p(x, chi) of every node to `delta`, kept on the node's box faces and
/// cut to ProjectParams::max_step of the node's mean edge length.
/// @param mesh   the mesh; chi of a node is its phase set
/// @param field  the original (unsnapped) phase functions
/// @param params which pairs to skip (ProjectParams::min_gradient_gap), the longest step
/// @param delta  the displacement of every node, one entry per node; the steps are added to it
void add_projection(const InterfaceMesh& mesh, const PhaseField& field, const ProjectParams& params,
                    std::vector<Vec3>& delta);

} // namespace vm
