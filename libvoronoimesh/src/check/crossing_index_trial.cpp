/// @file check/crossing_index_trial.cpp
/// CrossingIndex::crossings_with(): a trial of edits checked against the
/// indexed mesh through its cells, instead of a search of the whole trial.

#include "check/crossing_index.hpp"

#include "core/parallel.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>

namespace vm::detail {
namespace {

/// Whether two triangles, each given by its nodes and corner points, intersect
/// improperly (intersect_improperly(), which knows what they share by their
/// node ids): both put into one array of six points.
bool cross(const Triangle& a, const std::array<Vec3, 3>& a_at, int8_t a_axis, const Triangle& b,
           const std::array<Vec3, 3>& b_at, int8_t b_axis) {
  std::array<Vec3, 6> points;
  Triangle local_a{0, 1, 2}, local_b;
  for (size_t k = 0; k < 3; ++k) {
    points[k] = a_at[k];
    const auto shared = std::find(a.begin(), a.end(), b[k]);
    local_b[k] = shared != a.end() ? int32_t(shared - a.begin()) : int32_t(3 + k);
    points[3 + k] = b_at[k];
  }
  return intersect_improperly(points, local_a, local_b, a_axis, b_axis);
}

} // namespace

CrossingIndex::TrialCrossings CrossingIndex::crossings_with(std::span<const Vec3> points,
                                                            std::span<const Triangle> triangles,
                                                            std::span<const TrialTriangle> extra,
                                                            std::span<const int32_t> left_out) const {
  std::vector<Bounds> box(extra.size());
  std::vector<int8_t> axis(extra.size());
  for (size_t e = 0; e < extra.size(); ++e) {
    const auto& at = extra[e].corners;
    box[e] = triangle_bounds(at, Triangle{0, 1, 2});
    axis[e] = projection_axis(at[0], at[1], at[2]);
  }
  // Each extra triangle on its own (the mesh's boxes lie in their filing
  // boxes, refresh() saw to that), its pairs in order of the mesh triangle.
  std::vector<std::vector<int32_t>> crossed(extra.size());
  parallel_for_each_index(
      extra.size(),
      [&](size_t e) {
        std::vector<int32_t> near;
        filed_meeting(box[e], near);
        for (int32_t& slot : near) slot = triangle_of_[size_t(slot)];
        std::sort(near.begin(), near.end());
        for (int32_t s : near) {
          if (!box[e].overlaps(boxes_[size_t(s)]) || std::binary_search(left_out.begin(), left_out.end(), s)) continue;
          const Triangle& tri = triangles[size_t(s)];
          const std::array<Vec3, 3> at{points[size_t(tri[0])], points[size_t(tri[1])], points[size_t(tri[2])]};
          if (cross(extra[e].nodes, extra[e].corners, axis[e], tri, at, projection_axis(at[0], at[1], at[2])))
            crossed[e].push_back(s);
        }
      },
      1);
  TrialCrossings found;
  for (size_t e = 0; e < extra.size(); ++e)
    for (int32_t s : crossed[e]) found.with_mesh.push_back({int32_t(e), s});
  // Extra triangles against each other, their candidate pairs found through
  // a grid as a one-off check finds them (testing every pair was quadratic in
  // the trial: with batches of junction collapses the closed voxel-faithful
  // liver's improvement took 220 s, and 67 s with a sweep along x, its box
  // faces' triangles all at one x; 34 s now).
  tbb::enumerable_thread_specific<std::vector<BoxPair>> among;
  for_each_overlapping_box_pair(box, {}, [&](std::span<const BoxPair> candidates) {
    std::vector<BoxPair>& out = among.local();
    for (const auto [e, f] : candidates)
      if (cross(extra[size_t(e)].nodes, extra[size_t(e)].corners, axis[size_t(e)], extra[size_t(f)].nodes,
                extra[size_t(f)].corners, axis[size_t(f)]))
        out.push_back({e, f});
  });
  for (const auto& part : among) found.among_extra.insert(found.among_extra.end(), part.begin(), part.end());
  std::sort(found.among_extra.begin(), found.among_extra.end()); // in the order of the extra triangles
  return found;
}

} // namespace vm::detail
