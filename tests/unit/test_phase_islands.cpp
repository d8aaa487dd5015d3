// Pockets of a phase that the phase functions do not have (improve/phase_islands.hpp):
// found where the lattice made one, and left where the phase leads inside, however small.

#include "improve/phase_islands.hpp"
#include "mesh/node_rings.hpp"

#include "voronoimesh/fields/scene.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using namespace vm;

/// The pockets detail::phase_islands() finds in `scene`'s created mesh, judged by `judge`'s phase
/// functions (the scene's by default), with a target of one grid spacing at every node.
std::vector<detail::PointMerge> pockets(const Scene& scene, const Scene* judge = nullptr) {
  const NodeMesh m = test::created_mesh(scene);
  const detail::NodeRings rings(m);
  const std::vector<double> target(m.num_nodes(), m.grid_spacing);
  return detail::phase_islands(rings, target, *(judge ? judge : &scene)->field, 2);
}

// Seventeen random cells (bench/junction_scenes.sh's seeds17_4): where cells 2,
// 7, 11 and 15 nearly tie by the box face y = 1 the lattice lets cell 11 lead in
// a pocket against the face, cut off from the rest of the cell: three triangles
// on four nodes, one of them a quadruple point 1.8 h from where the four meet,
// where cells 2 and 15 lead. It merges into a node on the face.
TEST(PhaseIslands, the_pocket_the_lattice_made_is_found_and_merges_onto_the_box) {
  const Scene scene = load_scene(std::string(VM_TESTS_DATA_DIR) + "/scenes/seeds17_4.json");
  const std::vector<detail::PointMerge> found = pockets(scene);
  ASSERT_EQ(found.size(), 1u);
  const NodeMesh m = test::created_mesh(scene);
  const detail::NodeRings rings(m);
  const detail::PointMerge& pocket = found[0];
  EXPECT_EQ(pocket.merged.size(), 3u);
  EXPECT_TRUE(rings.has_phase(pocket.keep, 11));
  for (int32_t n : pocket.merged) EXPECT_TRUE(rings.has_phase(n, 11));
  EXPECT_EQ(rings.box_faces()[size_t(pocket.keep)], 1u << 3); // the face y = 1
  EXPECT_EQ(pocket.to.y(), 1.0);
}

// A drop of one phase, 0.8 h in radius, where two others meet, besides a large
// ball of the same phase: the lattice makes it a pocket of a few triangles,
// which the drop's own phase functions keep (it leads inside), while judged by
// phase functions without the drop it is one the lattice made.
TEST(PhaseIslands, a_pocket_its_phase_leads_in_is_kept) {
  auto scene_with = [](const std::string& drops) {
    return parse_scene(R"({"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": 32, "phases": [
      {"name": "below", "kind": "expr", "expr": "0.51 - z"},
      {"name": "above", "kind": "expr", "expr": "z - 0.51"},
      {"name": "drops", "kind": "expr", "expr": ")" + drops + R"("}]})",
                       "drops.json");
  };
  const std::string ball = "0.15 - sqrt((x - 0.3)^2 + (y - 0.5)^2 + (z - 0.5)^2)";
  const std::string drop = "0.025 - sqrt((x - 0.6875)^2 + (y - 0.5)^2 + (z - 0.5)^2)";
  const Scene with_drop = scene_with("max(" + ball + ", " + drop + ")");
  EXPECT_TRUE(pockets(with_drop).empty());
  const Scene without_drop = scene_with(ball);
  const std::vector<detail::PointMerge> found = pockets(with_drop, &without_drop);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].to.x(), 0.6875, 0.5 / 32);
}

} // namespace
