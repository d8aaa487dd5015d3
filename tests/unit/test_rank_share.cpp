// What a rank of a distributed create holds (mpi/distributed.hpp; the MPI tests compare
// whole meshes): the lattice nodes of a window of grid layers, the samples of
// those layers, and validation of its own vertices alone.

#include "check/validate_part.hpp"
#include "create/lattice.hpp"
#include "fixtures.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/sampled_field.hpp"

#include <gtest/gtest.h>

namespace {

using namespace vm;

TEST(Lattice, window_holds_the_nodes_of_its_layers_numbered_densely) {
  for (Lattice kind : {Lattice::bcc, Lattice::cube6}) {
    GridSpec grid;
    grid.cells = {4, 6, 10};
    const detail::TetLattice lattice(grid, kind);
    for (int z0 = 0; z0 <= 10; ++z0)
      for (int z1 = z0; z1 <= 10; ++z1) {
        const detail::NodeWindow w = lattice.window(z0, z1);
        std::vector<int> seen(size_t(w.size()), 0);
        int64_t inside = 0;
        for (int64_t id = 0; id < lattice.num_nodes(); ++id) {
          const int32_t z = lattice.grid_point(id)[2];
          ASSERT_EQ(w.contains(id), z >= z0 && z <= z1) << "node " << id << ", layers " << z0 << ".." << z1;
          if (!w.contains(id)) continue;
          ++inside;
          ASSERT_GE(w.local(id), 0);
          ASSERT_LT(w.local(id), w.size());
          ++seen[size_t(w.local(id))];
        }
        EXPECT_EQ(inside, w.size());
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), w.size()) << "layers " << z0 << ".." << z1;
      }
    const detail::NodeWindow all = lattice.window(0, 10);
    for (int64_t id = 0; id < lattice.num_nodes(); ++id) EXPECT_EQ(all.local(id), id);
  }
}

TEST(SampledField, layers_hold_the_samples_of_the_whole_grid) {
  const Scene scene = test::example_scene("four_spheres.json", 12);
  const SampledField whole = SampledField::sample(*scene.field, scene.grid, 3);
  const SampledField part = SampledField::sample(*scene.field, scene.grid, 3, {4, 7});
  EXPECT_EQ(part.first_node(), scene.grid.node_index(0, 0, 4));
  for (int64_t n = part.first_node(); n < scene.grid.node_index(0, 0, 8); ++n) {
    ASSERT_TRUE(std::ranges::equal(part.ids(n), whole.ids(n))) << "node " << n;
    ASSERT_TRUE(std::ranges::equal(part.values(n), whole.values(n))) << "node " << n;
    ASSERT_EQ(part.floor_value(n), whole.floor_value(n)) << "node " << n;
  }
  EXPECT_THROW(SampledField::sample(*scene.field, scene.grid, 3, {5, 13}), InvalidInput);
  const SampledField copy = SampledField::from_samples(
      scene.grid, part.num_phases(), part.k(), part.layers(), {part.all_ids().begin(), part.all_ids().end()},
      {part.all_values().begin(), part.all_values().end()}, {part.all_floors().begin(), part.all_floors().end()});
  EXPECT_EQ(copy.min_value(), part.min_value());
  EXPECT_EQ(copy.max_value(), part.max_value());
  EXPECT_THROW(SampledField::from_samples(scene.grid, 5, 3, {4, 8}, {}, {}, {}), InvalidInput);
}

// A defect is found when one of its nodes is checked, and only then.
TEST(Validate, first_nodes_check_only_those_nodes) {
  NodeMesh m = test::four_spheres(12);
  EXPECT_TRUE(detail::validate_first_nodes(m, m.points.size()).ok());
  // Flip one triangle: its edges' orientation breaks at its three nodes.
  std::swap(m.triangles[7][1], m.triangles[7][2]);
  const ValidationReport all = validate(m);
  ASSERT_FALSE(all.ok());
  const ValidationReport same = detail::validate_first_nodes(m, m.points.size());
  EXPECT_EQ(same.nodes, all.nodes);
  EXPECT_EQ(same.problem_count, all.problem_count);
  const int32_t lowest = *std::min_element(m.triangles[7].begin(), m.triangles[7].end());
  EXPECT_TRUE(detail::validate_first_nodes(m, size_t(lowest)).ok());
  EXPECT_FALSE(detail::validate_first_nodes(m, size_t(lowest) + 1).ok());
}

} // namespace
