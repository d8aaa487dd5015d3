#pragma once
/// @file improve/remesh.hpp
/// Junction-aware remeshing toward a target edge length (beyond the paper, which
/// keeps the lattice's size): long edges are split and short ones collapsed, in
/// every surface that shares them at once, so the junction graph never changes.
/// The flip and smooth passes do the rest of isotropic remeshing (Botsch and
/// Kobbelt 2004): flips toward quality, tangential relaxation.
///
/// Node classes come from the phase sets: a surface node (two phases, no box
/// face) may collapse into any neighbour that lies on its surface; a curve node
/// (three phases, or two and a box face) only along its curve, into another
/// node inside the same curve, so every curve keeps at least one edge; corners (quadruple and higher points, box
/// corners and edges) are never collapsed. Splits only add nodes on existing
/// edges (each new triangle lies in its old one); collapses pass validation,
/// and with the guard on both pass the crossing check (a rounded midpoint can
/// stand a hair off a coplanar neighbour).

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstddef>
#include <vector>

namespace vm {

/// Parameters of remesh_edges() (the remesh pass). Lengths are in multiples of a
/// reference length (the pass's: the mesh's RMS edge length when the run began).
struct RemeshParams {
  /// The target edge length, and with `tolerance` the largest one.
  double size = 1.5;
  /// With the phase functions: the largest distance a triangle may keep from a
  /// curved surface (like CGAL's facet distance), which shortens the target
  /// where surfaces curve: L = sqrt(3.375 tolerance / curvature), so that a
  /// triangle's centroid stays within the tolerance of a sphere even with edges
  /// at 4/3 of the target (curvature: sqrt(k1^2 + k2^2) of the level sets of
  /// the phase functions). 0: uniform size.
  double tolerance = 0;
  /// The shortest target edge length (with `tolerance`).
  double min_size = 0.5;
  /// Neighbouring corners (quadruple and higher points) closer than this share
  /// of the target merge at their midpoint into one higher-order point, when
  /// the mesh stays valid: the curve between them is too short for any
  /// triangle at it to be more than a sliver. 0: corners never merge.
  double merge_corners = 0.1;
  /// With the phase functions: a face bounded by two triple curves between two
  /// quadruple points of the same phases (a "digon", which no Voronoi diagram
  /// has: a lattice artefact of a nearly degenerate vertex), both curves at most
  /// this many targets long, whose corners Newton's method leads to one point,
  /// merges into a quadruple point there when the mesh stays valid. 0: never.
  double merge_digons = 6;
  /// With the phase functions: a curve node next to a quadruple point where the
  /// point's fourth phase is larger than the curve's three (the curve runs past
  /// the point) merges into the point, which goes where its four phases meet,
  /// when the mesh stays valid. For a mesh whose nodes have been projected (the
  /// remesh pass sets it from its second iteration on).
  bool merge_overshoots = false;
  /// A collapse may leave no triangle below the smaller of this and the worst
  /// quality among the triangles it replaces.
  double min_quality = 0.3;
  /// Rounds of collapses per call, at most; each claims the rings around its
  /// collapses, so one round reaches only part of the short edges. A round that
  /// collapses fewer than 1% of the nodes is the call's last.
  int collapse_rounds = 4;
  /// No split round starts once the mesh has this many triangles (0: no limit):
  /// a target far below the mesh's edges (a closed box whose interfaces are a
  /// few tiny triangles) must not refine without bound.
  size_t max_triangles = 0;
  /// Refuse collapses after which a moved triangle crosses another surface.
  bool guard_crossings = true;
  /// Split long edges before collapsing short ones (Botsch and Kobbelt's order)
  /// instead of after. A mesh as created has short edges beside long ones, and
  /// no collapse may make an edge longer than 4/3 of the target, so collapsing
  /// first leaves those and splits every long edge beside them: a surplus the
  /// next call collapses again (1,000 grains at grid 128: 1.39M triangles ->
  /// 2.04M -> 1.29M; splitting first: 1.35M -> 1.28M).
  bool split_first = false;
  /// With the phase functions: a closed piece of a phase's boundary (at most
  /// 64 triangles) that is at most this many targets across, where
  /// another phase leads at its centre and just inside each of its triangles
  /// (a pocket the lattice made, cut off from the rest of the phase), merges
  /// into one node when the mesh stays valid; a phase keeps its other pieces,
  /// so no phase is lost. 0: never.
  double merge_islands = 2;
};

/// What remesh_edges() did.
struct RemeshStats {
  size_t splits = 0;    ///< edges split
  size_t collapses = 0; ///< edges collapsed
  /// Nodes merged into a quadruple point: of digon faces (RemeshParams::merge_digons) and of curves
  /// past their point (RemeshParams::merge_overshoots).
  size_t point_merges = 0;
  /// When anything changed: the old id of each triangle of the new mesh, -1
  /// for one the call made (with old_nodes for CrossingGuard::renumbered(), so
  /// that the guard's index carries over); empty when nothing changed.
  std::vector<int32_t> old_triangles;
  /// Likewise for each node: -1 for the splits' midpoints, which come last.
  std::vector<int32_t> old_nodes;
};

/// The target edge length at every node: params.size, or with a field and a
/// tolerance the length whose chord stays within the tolerance of the node's
/// most curved surface, in [min_size, size] (all times `reference`).
/// @param mesh      the mesh
/// @param field     the phase functions whose level sets give the curvature; null: uniform
/// @param reference the length the parameters are multiples of
/// @param params    size, tolerance and min_size
/// @return one length per node
std::vector<double> target_edge_lengths(const InterfaceMesh& mesh, const PhaseField* field, double reference,
                                        const RemeshParams& params);

/// One call of the remesh pass: rounds of collapses of edges shorter than 4/5
/// of the target (the smaller of their nodes'), shortest first, no two
/// neighbouring nodes removed in one round, never making an edge longer than 4/3
/// of the target (RemeshParams::collapse_rounds, each on the node-level mesh the last left);
/// then rounds of splits of every edge longer than 4/3 of the target at its
/// midpoint (projection brings new nodes onto their surface or curve later);
/// with RemeshParams::split_first the splits come first.
/// @param mesh      the mesh, changed in place (node and triangle ids change when anything changed)
/// @param field     the phase functions for the target lengths (target_edge_lengths()); null: uniform
/// @param reference the length the parameters are multiples of
/// @param params    the target and the checks
/// @return the splits and collapses made
RemeshStats remesh_edges(InterfaceMesh& mesh, const PhaseField* field, double reference, const RemeshParams& params);

} // namespace vm
