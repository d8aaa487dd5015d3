/// @file check/crossing_index_trial.cpp
/// CrossingIndex::crossings_with(): a trial of edits checked against the
/// indexed mesh through its cells, instead of a search of the whole trial.

#include "check/crossing_index.hpp"

#include "core/parallel.hpp"

namespace vm::detail {

CrossingIndex::TrialCrossings CrossingIndex::crossings_with(std::span<const Vec3> points,
                                                            std::span<const Triangle> triangles,
                                                            std::span<const Triangle> extra,
                                                            std::span<const uint8_t> left_out) const {
  std::vector<Bounds> box(extra.size());
  std::vector<int8_t> axis(extra.size());
  for (size_t e = 0; e < extra.size(); ++e) {
    const Triangle& tri = extra[e];
    box[e] = triangle_bounds(points, tri);
    axis[e] = projection_axis(points[size_t(tri[0])], points[size_t(tri[1])], points[size_t(tri[2])]);
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
          if (left_out[size_t(s)] || !box[e].overlaps(boxes_[size_t(s)])) continue;
          const Triangle& tri = triangles[size_t(s)];
          const int8_t s_axis = projection_axis(points[size_t(tri[0])], points[size_t(tri[1])], points[size_t(tri[2])]);
          if (intersect_improperly(points, extra[e], tri, axis[e], s_axis)) crossed[e].push_back(s);
        }
      },
      1);
  TrialCrossings found;
  for (size_t e = 0; e < extra.size(); ++e) {
    for (int32_t s : crossed[e]) found.with_mesh.push_back({int32_t(e), s});
    for (size_t f = e + 1; f < extra.size(); ++f)
      if (box[e].overlaps(box[f]) && intersect_improperly(points, extra[e], extra[f], axis[e], axis[f]))
        found.among_extra.push_back({int32_t(e), int32_t(f)});
  }
  return found;
}

} // namespace vm::detail
