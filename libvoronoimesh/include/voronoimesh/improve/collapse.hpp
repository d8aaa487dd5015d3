#pragma once
/// @file improve/collapse.hpp
/// Removal of degenerate triangles at junctions by collapsing an edge. Beyond the
/// paper: where quadruple points lie closer than a grid cell, triangles with all
/// three corners on junction curves can become degenerate; clamping then freezes
/// their corners (a degenerate triangle allows no move) and, their other edges
/// being junctions, no flip can remove them. Where a tiny face ends, nodes bunch
/// on its triple curve: triangles with one short edge along the curve, which no
/// flip may touch either.
///
/// Collapsing is no pass of its own: it is the second half of the flip pass
/// (flip_edges(), FlipParams::collapse_below), which removes what its flips
/// could not.

#include "voronoimesh/improve/guard.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

namespace vm {

/// Parameters of collapse_junction_slivers(), which the flip pass runs after its
/// flips (FlipParams::collapse_below; the pass parameter collapse_below).
struct CollapseParams {
  /// Triangles below this quality with two or three corners on junctions (or
  /// the box) are collapsed. 0 turns collapsing off.
  double below_quality = 0.15;
  /// At most this many collapses per call, or an eighth as many as the
  /// candidates found if that is more: slivers grow in number with the mesh
  /// (1,000 grains at grid 128 have 6,727 candidates at the first call), and 64
  /// a call left 339 triangles below q 0.1 there after 20 iterations (182 now).
  int max_collapses = 64;
  /// Refuse collapses after which a moved triangle crosses another surface.
  bool guard_crossings = true;
  /// A guard kept across the run (improve/guard.hpp), told how the rebuilt
  /// mesh renumbers triangles and nodes so that it need not start over; null: none.
  CrossingGuard* guard = nullptr;
  /// Null, or phase functions whose kept points (PhaseField::kept_points(): a
  /// voxel-faithful volume's thin structures) no collapse may take out of their phase.
  const PhaseField* kept = nullptr;
};

/// Collapses, for each such triangle, its shortest edge (b -> a) whose node b has
/// its phases and box faces among a's, so a already lies on every constraint of b:
/// b's triangles are moved to a and the triangles on both a and b disappear, in
/// every surface at once. Where b lies on box faces that a, a junction node
/// within a quarter of the triangle's longest edge of them, is not on (and b's
/// phases are among a's), a moves onto those faces and b merges into it there.
/// Where no edge of the triangle may collapse, or every collapse would leave a
/// triangle no better, one of its corners merges into a junction neighbour off
/// it that lies on all its constraints, whichever leaves its triangles best.
/// Collapses that share no triangle go in one batch; a
/// batch (or, if it fails, each collapse) is kept only if no triangle turns over,
/// the mesh stays valid, no surface folds at a kept node (two of its triangles
/// on one edge turned more than MeshStats::kFoldDeg apart, as `stats` counts
/// folds) and (with guard_crossings) no triangle at a kept node crosses another
/// surface. Rebuilds `mesh` (node ids change) when anything was
/// collapsed.
/// @param mesh   the mesh, changed in place (node ids change when anything was collapsed); its
///               triangles() current (after flips, InterfaceMesh::faces_changed())
/// @param params which triangles to collapse, how many at most, and the crossing guard
/// @return the number of collapses
size_t collapse_junction_slivers(InterfaceMesh& mesh, const CollapseParams& params = {});

} // namespace vm
