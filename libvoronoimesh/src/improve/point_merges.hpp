#pragma once
/// @file improve/point_merges.hpp
/// Groups of junction nodes that the remesh pass merges into one of them,
/// placed where the phase functions say the junction is, before its
/// collapses: small digon faces (improve/digon_faces.hpp) and curve ends that
/// ran past their quadruple point (improve/curve_overshoots.hpp). What both
/// need: the group, the nodes its check may fail at, Newton's method for the
/// point where four phases meet, and a choice of groups that do not touch.

#include "mesh/node_rings.hpp"

#include "voronoimesh/fields/phase_field.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace vm::detail {

/// Nodes merged into one: `keep`, and every node of `merged` merged into it,
/// which then goes to `to`.
struct PointMerge {
  int32_t keep;
  std::vector<int32_t> merged;
  Vec3 to;
};

/// The nodes of `merge` (`keep` and the merged ones) and their neighbours,
/// ascending, each once: where a check of the merge can fail.
std::vector<int32_t> nodes_around(const NodeRings& mesh, const PointMerge& merge);

/// The merges of `merges`, in their order, that touch none kept before them
/// (no node of one is a node or neighbour of another's: nodes_around()), so
/// that each is judged on the mesh around it as it is; sorted by `keep`.
std::vector<PointMerge> keep_apart(const NodeRings& mesh, std::vector<PointMerge> merges);

/// The merges of `merges` but those whose point would land within a tenth of
/// a target edge length (`target`, by node) of another point of its phases: a
/// node outside the merge that has four of the kept node's phases. The sampled
/// field can make two points of one tie; where one of them already sits at
/// the tie, a merge that takes the other there leaves the two a hair apart,
/// with every triangle between them flat, unless they are corners of one
/// digon face (which a later call merges). On 1,000 grains at grid 96 a curve
/// end was merged into its point, which went 1.2 h onto the other point: an
/// edge of 2e-5 h and triangles of q 0.0000 for good. (Refusing merges that
/// land within a whole target of another point also refused the chains of
/// digons that a later call would have merged with it: seeds30_2 0.411 ->
/// 0.095.)
std::vector<PointMerge> off_other_points(const NodeRings& mesh, std::vector<PointMerge> merges,
                                         std::span<const double> target);

/// Where Newton's method on phi_0 = phi_1 = phi_2 = phi_3 (the phases of a
/// quadruple point) leads from x, no step longer than `reach`; none if it does
/// not converge (to a millionth of `reach`).
std::optional<Vec3> meeting_point(const PhaseField& field, const PhaseSet& phases, Vec3 x, double reach);

/// A quadruple point off the box.
inline bool is_corner(const NodeRings& mesh, int32_t n) {
  return phase_count(mesh.phases()[size_t(n)]) == 4 && mesh.box_faces()[size_t(n)] == 0;
}

/// A node inside a triple curve, off the box.
inline bool is_curve_node(const NodeRings& mesh, int32_t n) {
  return phase_count(mesh.phases()[size_t(n)]) == 3 && mesh.box_faces()[size_t(n)] == 0;
}

} // namespace vm::detail
