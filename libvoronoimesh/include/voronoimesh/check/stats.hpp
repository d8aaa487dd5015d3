#pragma once
/// @file check/stats.hpp
/// Counts and quality measures of an interface mesh.

#include "voronoimesh/mesh/node_mesh.hpp"
#include "voronoimesh/mesh/triangle_quality.hpp"

#include <array>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace vm {

/// Counts and quality measures of a mesh (compute_stats()).
struct MeshStats {
  size_t vertices = 0;          ///< nodes (points), used or not
  size_t triangles = 0;         ///< triangles, malformed ones included
  size_t phases = 0;            ///< distinct phase ids used by triangles
  size_t surfaces = 0;          ///< connected patches of one phase pair
  size_t triple_curves = 0;     ///< junction curves between higher-order points (find_junctions())
  size_t quadruple_points = 0;  ///< nodes where 4 or more phases meet
  size_t higher_order_points = 0; ///< of those, nodes where 5 or more meet
  /// Smallest triangle quality q (triangle_quality()).
  double min_quality = 0, mean_quality = 0; ///< mean triangle quality q
  double quality_p01 = 0;       ///< 1st percentile of q: 99% of triangles are at least this good
  size_t below_half = 0;        ///< triangles with q < 0.5
  /// Triangles below this quality are slivers.
  static constexpr double kSliverQuality = 0.1;
  size_t slivers = 0;           ///< triangles with q < kSliverQuality
  /// Two triangles of one surface sharing an edge whose normals lie more than
  /// this apart turn back on each other there (a fold).
  static constexpr double kFoldDeg = 150;
  /// Surface edges that fold: the surface turns back across them by more than
  /// kFoldDeg. Where the mesh resolves its surfaces they turn a few tens of
  /// degrees at most across an edge; a fold is a layer or a rim thinner than
  /// the edges (or a cell), whose two sheets the mesh has laid onto each other.
  size_t folds = 0;
  /// Smallest angle of any triangle, in degrees.
  double min_angle_deg = 0, max_angle_deg = 0; ///< largest angle of any triangle, in degrees
  /// Width of the bins of smallest_angles, in degrees.
  static constexpr int kAngleBinDeg = 10;
  /// Triangles by their smallest angle, in bins of kAngleBinDeg degrees from 0
  /// (the last bin ends at 60, the most a smallest angle can be): what meshers
  /// that bound angles are compared by (CGAL's facet_angle: 30 degrees, the
  /// first three bins empty).
  std::array<size_t, 60 / kAngleBinDeg> smallest_angles{};
  /// Corners below this many degrees count as sharp (sharp_corners): the first
  /// bin of smallest_angles, to set them against.
  static constexpr double kSharpCornerDeg = 10;
  /// The smallest corner a surface makes at a junction point (a node whose
  /// phases and the box faces it lies on number four or more: a quadruple
  /// point, a triple curve's end on the box, a surface's end on a box edge), in
  /// degrees: 180 when none is smaller. The surface's triangles there fill the
  /// corner, so one of them has a smallest angle no larger than it whatever the
  /// remeshing, as long as the point and its curves stay where the phases put
  /// them. Where min_angle_deg is close to it, only moving junctions (or
  /// changing which phases meet) could raise the worst angle.
  double smallest_corner_deg = 180;
  /// Corners of surfaces at junction points below kSharpCornerDeg.
  size_t sharp_corners = 0;
  /// Shortest edge (distinct node edges), in the units of the points.
  double min_edge = 0, max_edge = 0, rms_edge = 0; ///< RMS edge length, in the units of the points
  /// @var max_edge
  /// Longest edge, in the units of the points.

  /// Of a closed mesh (NodeMesh::outside_phase), the triangles on the box faces:
  /// the outside phase's boundary, a lattice of right triangles (q 0.866) that
  /// would hide the interfaces' own quality in the figures above. 0 for other meshes.
  size_t box_triangles = 0;
  /// Of a closed mesh, the smallest and mean q of the other triangles (the
  /// interfaces between phases inside the box); 0 for other meshes.
  double interface_min_quality = 0, interface_mean_quality = 0;
  /// @var interface_mean_quality
  /// Of a closed mesh, the mean q of the triangles not on the box faces.

  /// Pairs of triangles that intersect (find_self_intersections); not measured by
  /// compute_stats, which must stay cheap: set by callers that check.
  std::optional<size_t> self_intersections;
};

/// Measures `m`: counts, junctions (find_junctions()) and triangle quality. Linear in the mesh size.
/// Triangles with out-of-range or repeated node ids, or without a pair, are left out of every count but
/// `triangles` (validate() reports them).
/// @param m the mesh
/// @return its counts and measures; self_intersections is left unset
MeshStats compute_stats(const NodeMesh& m);

/// MeshStats::folds alone, for a run to report them without the rest.
/// @param m the mesh
/// @return the surface edges across which the surface turns back by more than MeshStats::kFoldDeg
size_t count_folds(const NodeMesh& m);

/// A corner of a triangle as worst_triangles() reports it: what meets there.
struct TriangleCorner {
  int32_t node = -1;            ///< the node's id
  Vec3 position = Vec3::Zero(); ///< where it is
  /// The phases of the triangles at the node, ascending: two on a surface,
  /// three on a triple curve, four or more at a quadruple or higher point.
  std::vector<int32_t> phases;
  int box_faces = 0; ///< faces of the domain box the node lies on (0: inside)
};

/// One of the worst triangles of a mesh (worst_triangles()).
struct WorstTriangle {
  size_t triangle = 0;                   ///< its index
  double quality = 0;                    ///< q (triangle_quality())
  double min_angle_deg = 0;              ///< its smallest angle
  PhasePair pair{};                      ///< the phases it separates
  std::array<TriangleCorner, 3> corners; ///< its corners, in its node order
  /// Where its smallest angle is the whole corner its surface makes at a
  /// junction point (it is the surface's only triangle at that node;
  /// MeshStats::smallest_corner_deg): that node, and the corner, which no
  /// triangulation keeping the point and its curves can beat; -1 and NaN
  /// elsewhere.
  int32_t corner_node = -1;
  double corner_deg = std::numeric_limits<double>::quiet_NaN(); ///< see corner_node
};

/// The `count` triangles of lowest quality, worst first (ties by index), with
/// what meets at their corners: where a mesh loses its quality and why (a
/// sliver between two triple curves, at a quadruple point, on the box).
/// Malformed triangles (validate() reports them) are left out. Linear in the
/// mesh size.
/// @param m the mesh
/// @param count how many at most
/// @return the worst triangles, worst first
std::vector<WorstTriangle> worst_triangles(const NodeMesh& m, size_t count);

/// A fold of a mesh (sharpest_folds()): a surface edge across which the
/// surface turns back (MeshStats::folds).
struct Fold {
  double turn_deg = 0;                ///< the angle between its two triangles' normals, above MeshStats::kFoldDeg
  PhasePair pair{};                   ///< the surface's phases
  std::array<size_t, 2> triangles{};  ///< the surface's two triangles on the edge
  std::array<TriangleCorner, 2> ends; ///< the edge's ends, and what meets there
};

/// The `count` sharpest folds (largest turn first, ties by edge), with what
/// meets at their ends: where two sheets of a surface lie on each other, which
/// no quality measure shows. Linear in the mesh size.
/// @param m the mesh
/// @param count how many at most
/// @return the sharpest folds, sharpest first
std::vector<Fold> sharpest_folds(const NodeMesh& m, size_t count);

/// Human-readable multi-line summary.
/// @param s the measures to show
std::string to_text(const MeshStats& s);
/// One JSON object.
/// @param s the measures to write
/// @param worst worst_triangles() to add as "worst_triangles" (none: the key is left out)
/// @param m the mesh they are of: phases are written as its files show them (NodeMesh::phase_labels)
/// @param folds sharpest_folds() to add as "sharpest_folds" (none: the key is left out)
/// @param more  further keys, each with a JSON text as its value (measures of other stages, such as
///              `stats --field`'s "offsets")
std::string to_json(const MeshStats& s, std::span<const WorstTriangle> worst = {}, const NodeMesh* m = nullptr,
                    std::span<const Fold> folds = {},
                    std::span<const std::pair<std::string, std::string>> more = {});

/// The worst triangles as text, a few lines each, with phases as `m`'s files
/// show them and their names where `m` has them.
/// @param worst worst_triangles() of `m`
/// @param m the mesh
std::string to_text(std::span<const WorstTriangle> worst, const NodeMesh& m);

/// The folds as text, a few lines each, like the worst triangles.
/// @param folds sharpest_folds() of `m`
/// @param m the mesh
std::string to_text(std::span<const Fold> folds, const NodeMesh& m);

} // namespace vm
