#pragma once
/// @file stats.hpp
/// Counts and quality measures of an interface mesh.

#include "voronoimesh/node_mesh.hpp"

#include <optional>
#include <string>

namespace vm {

/// Triangle quality q = 4 sqrt(3) area / (sum of squared edge lengths); 1 for an
/// equilateral triangle, 0 for a degenerate one (paper sect. 4.3).
double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c);

/// Counts and quality measures of a mesh (compute_stats()).
struct MeshStats {
  size_t vertices = 0;
  size_t triangles = 0;
  size_t phases = 0;            ///< distinct phase ids used by triangles
  size_t surfaces = 0;          ///< connected patches of one phase pair
  size_t triple_curves = 0;     ///< junction curves between higher-order points (find_junctions())
  size_t quadruple_points = 0;  ///< nodes where 4 or more phases meet
  size_t higher_order_points = 0; ///< of those, nodes where 5 or more meet
  double min_quality = 0, mean_quality = 0;
  double quality_p01 = 0;       ///< 1st percentile of q: 99% of triangles are at least this good
  size_t below_half = 0;        ///< triangles with q < 0.5
  size_t slivers = 0;           ///< triangles with q < 0.1
  double min_angle_deg = 0, max_angle_deg = 0;
  double min_edge = 0, max_edge = 0, rms_edge = 0;
  /// Pairs of triangles that intersect (find_self_intersections); not measured by
  /// compute_stats, which must stay cheap: set by callers that check.
  std::optional<size_t> self_intersections;
};

/// Measures `m`: counts, junctions (find_junctions()) and triangle quality. Linear in the mesh size.
MeshStats compute_stats(const NodeMesh& m);

/// Human-readable multi-line summary.
std::string to_text(const MeshStats& s);
/// One JSON object.
std::string to_json(const MeshStats& s);

} // namespace vm
