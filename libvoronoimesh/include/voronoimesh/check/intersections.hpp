#pragma once
/// @file check/intersections.hpp
/// Exact detection of self-intersections of a node-level interface mesh.

#include "voronoimesh/mesh/node_mesh.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace vm {

/// What find_self_intersections() found.
struct IntersectionReport {
  /// Number of improperly intersecting triangle pairs, all of them.
  size_t count = 0;
  /// The smallest (at most max_reported) of those pairs, each as {t, s} with
  /// t < s, sorted lexicographically.
  std::vector<std::array<int32_t, 2>> pairs;
  /// True when no two triangles intersect.
  bool ok() const { return count == 0; }
};

/// Pairs of triangles that intersect anywhere other than in the vertices and
/// edges they share.
///
/// Each triangle is taken as the closed point set of its three corners (a
/// segment or a point when they are collinear or repeated). Two triangles t, s
/// intersect improperly when they have a common point outside the convex hull H
/// of the nodes they share, nodes being compared by id:
///  - no shared node: any common point counts, touching included (a corner on
///    the other's face, crossing or touching edges, distinct nodes at the same
///    position);
///  - one shared node v: any common point other than v, such as the two
///    triangles folding onto each other around v in one plane, or an edge of
///    one passing through the other;
///  - two shared nodes u, w: any common point off the segment uw, which for
///    non-degenerate triangles means they lie in one plane on the same side
///    of uw (folded onto each other); edges carried by 3 or more triangles at
///    angles are valid;
///  - three shared nodes: the triangles are duplicates and always count.
///
/// The decision is exact: orientation predicates are evaluated with a
/// floating-point filter and an exact expansion-arithmetic fallback, so there
/// is no tolerance (tiny or sliver triangles are judged as they are). This holds
/// when no intermediate product over- or underflows, which is the case for
/// coordinates whose nonzero magnitudes lie between about 1e-90 and 1e90.
///
/// Candidate pairs come from a multi-level uniform grid over the triangles'
/// bounding boxes (each triangle in the level whose cells are at least its
/// size); each candidate pair is tested once, in parallel. The result does not
/// depend on the number of threads.
///
/// @param m the mesh; node ids must lie in [0, num_nodes()).
/// @param max_reported how many pairs to list in the report (count is always complete).
/// @param involved when not empty (one flag per triangle), only pairs with at
///        least one flagged triangle are tested and counted.
/// @param across_surfaces_only test only pairs of triangles with different phase
///        pairs (most candidate pairs are neighbours within one surface).
/// @return the number of improperly intersecting pairs and the smallest of them
/// @throws InvalidInput on a node id out of range or a non-finite coordinate; also when `involved` is not
///         empty and has not one flag per triangle, or with `across_surfaces_only` when the mesh has not
///         one phase pair per triangle.
IntersectionReport find_self_intersections(const NodeMesh& m, size_t max_reported = 20,
                                           std::span<const uint8_t> involved = {},
                                           bool across_surfaces_only = false);

} // namespace vm
