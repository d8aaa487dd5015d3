#pragma once
/// @file check/surface_corners.hpp
/// The corners surfaces make at junction points, which bound the smallest angle
/// any triangulation keeping those points can reach.
///
/// Where four phases meet (or a triple curve meets the box, or a surface a box
/// edge), the point's place is fixed, and so is where its curves leave it. Each
/// surface there has a corner between two of them: its triangles at the point
/// fill that corner, so one of them has an angle no larger than it. A corner of
/// 2 degrees holds a triangle of at most 2 degrees whatever the remeshing, as
/// long as the point and its curves stay where the phases put them; only moving
/// them, or changing which phases meet there, can do better. Telling such
/// triangles from the ones a pass could still improve is what the corners are
/// for (`voronoimesh stats`, issue 18's junction scenes).

#include "mesh/topology.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <cstdint>
#include <vector>

namespace vm::detail {

/// One surface's corner at a junction point: the fan of its triangles at the
/// node (triangles of one phase pair joined across their edges at the node).
struct SurfaceCorner {
  double angle_deg = 0; ///< the fan's angles at the node, summed
  int32_t node = -1;
  PhasePair pair{};
  std::vector<int32_t> triangles; ///< the fan's
};

/// The corners of every surface at node `n`, one per fan; none unless `n` is a
/// junction point, whose place the phases fix: its phases and the box faces it
/// lies on number four or more.
/// @param m   the mesh
/// @param nt  its node triangles (only the triangles listed there count)
/// @param np  its node phases
/// @param box the box faces of each node (box_faces_of())
std::vector<SurfaceCorner> corners_at(const NodeMesh& m, const NodeTriangles& nt, const NodePhases& np,
                                      const std::vector<uint8_t>& box, int32_t n);

/// The smallest corner of any surface at any junction point (angle_deg 180 and
/// node -1 when the mesh has none below that), and how many corners lie below
/// `sharp_deg`.
struct CornerSummary {
  SurfaceCorner smallest{180, -1, {}, {}};
  size_t sharp = 0;
};
CornerSummary summarize_corners(const NodeMesh& m, const NodeTriangles& nt, const NodePhases& np,
                                const std::vector<uint8_t>& box, double sharp_deg);

} // namespace vm::detail
