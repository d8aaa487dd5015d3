// Create reading the field itself holds the values of the lattice nodes near
// interfaces only (create/node_values.hpp): every node keeps its winner, and
// the nodes a cut can read keep their values. It must make the very mesh that
// holding every node's values makes, repairs and closing included.

#include "create/create_slabs.hpp"
#include "create/lattice.hpp"
#include "create/node_values.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/array_input.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace {

using namespace vm;

/// A scene of `phases` phases whose values are small integers on `grid`: exact
/// ties at most nodes, which create's repair rounds must undo.
Scene integer_scene(uint64_t seed, const GridSpec& grid, int phases) {
  std::mt19937_64 rng(seed);
  std::vector<std::vector<double>> values(size_t(phases), std::vector<double>(size_t(grid.node_count())));
  for (auto& phase : values)
    for (double& v : phase) v = double(rng() % 3);
  std::vector<std::span<const double>> spans(values.begin(), values.end());
  return scene_from_phase_values(grid, spans, PhaseValuesOptions{});
}

/// Two phases on a 10^3 grid: phase 1 wins at grid node (5, 5, 5) only, a cube
/// centre of the bcc lattice, whose other neighbours all belong to phase 0.
Scene island_scene() {
  GridSpec grid;
  grid.cells = {10, 10, 10};
  std::vector<std::vector<double>> values(2, std::vector<double>(size_t(grid.node_count())));
  std::fill(values[0].begin(), values[0].end(), 1.0);
  values[1][size_t(grid.node_index(5, 5, 5))] = 2.0;
  std::vector<std::span<const double>> spans(values.begin(), values.end());
  return scene_from_phase_values(grid, spans, PhaseValuesOptions{});
}

struct Case {
  std::string name;
  Scene scene;
  Lattice lattice;
  bool close;
};

std::vector<Case> cases() {
  GridSpec tied;
  tied.cells = {10, 8, 12};
  std::vector<Case> all;
  for (Lattice lattice : {Lattice::bcc, Lattice::cube6}) {
    all.push_back({"four spheres", test::example_scene("four_spheres.json", 24), lattice, false});
    all.push_back({"island at one node", island_scene(), lattice, false});
    all.push_back({"voronoi30 closed", test::example_scene("voronoi30.json", 20), lattice, true});
    for (uint64_t seed = 1; seed <= 3; ++seed)
      all.push_back({"integer ties " + std::to_string(seed), integer_scene(seed, tied, 2 + int(seed)), lattice,
                     seed == 2});
  }
  return all;
}

/// create_slabs() in one process from `values`.
NodeMesh create_from(const detail::NodeSource& source, detail::NodeValues& values, const CreateParams& params,
                     CreateStats& stats) {
  const detail::TetLattice lattice(source.grid(), params.lattice);
  detail::CreatePeers alone;
  detail::SlabsMesh part;
  stats = detail::create_slabs(source, values, params, {0, lattice.num_slabs() - 1}, alone, part);
  NodeMesh mesh;
  mesh.points = std::move(part.points);
  mesh.triangles = std::move(part.triangles);
  mesh.pairs = std::move(part.pairs);
  return mesh;
}

TEST(NodeValues, near_interfaces_hold_every_node_a_cut_reads_with_the_values_of_all) {
  for (const Case& c : cases()) {
    const GridSpec grid = grid_for_lattice(c.scene.grid, c.lattice);
    const SampledField samples = SampledField::sample(*c.scene.field, grid);
    const detail::TetLattice lattice(grid, c.lattice);
    const double snap = 0.2 * grid.h(), untie = kUntieFraction * grid.h();
    const detail::NodeValues all(samples, lattice, snap, untie);
    const detail::NodeValues near(detail::NodeSource(*c.scene.field, grid, 4), lattice, snap, untie, c.close);
    int64_t held = 0;
    for (int64_t n = 0; n < lattice.num_nodes(); ++n) {
      ASSERT_EQ(near.label(n), all.label(n)) << c.name << ", node " << n;
      bool border = false;
      lattice.for_each_neighbour(n, [&](int64_t m) { border = border || all.label(m) != all.label(n); });
      const detail::GridPoint p = lattice.grid_point(n);
      const bool on_box = p[0] == 0 || p[1] == 0 || p[2] == 0 || p[0] == grid.cells[0] || p[1] == grid.cells[1] ||
                          p[2] == grid.cells[2];
      ASSERT_TRUE(near.held(n) || !(border || (c.close && on_box))) << c.name << ", node " << n;
      if (!near.held(n)) continue;
      ++held;
      ASSERT_EQ(near.snapped(n), all.snapped(n)) << c.name << ", node " << n;
      for (int32_t phase = 0; phase < samples.num_phases(); ++phase)
        ASSERT_EQ(near.value(n, phase), all.value(n, phase)) << c.name << ", node " << n << ", phase " << phase;
    }
    EXPECT_EQ(held, near.held_nodes()) << c.name;
    if (c.name == "four spheres") EXPECT_LT(held, lattice.num_nodes() / 2) << c.name; // the point of it
  }
}

TEST(Create, from_the_field_makes_the_mesh_that_holding_every_node_makes) {
  int repaired = 0;
  for (const Case& c : cases()) {
    CreateParams params;
    params.lattice = c.lattice;
    params.close = c.close;
    const GridSpec grid = grid_for_lattice(c.scene.grid, c.lattice);
    const SampledField samples = SampledField::sample(*c.scene.field, grid);
    const detail::TetLattice lattice(grid, c.lattice);
    detail::NodeValues all(samples, lattice, params.snap * grid.h(), kUntieFraction * grid.h());
    CreateStats every_node;
    const NodeMesh expected = create_from(samples, all, params, every_node);

    NodeMesh mesh;
    const CreateStats stats = create_initial_mesh(*c.scene.field, grid, 4, params, mesh);
    EXPECT_EQ(mesh.points, expected.points) << c.name;
    EXPECT_EQ(mesh.triangles, expected.triangles) << c.name;
    EXPECT_EQ(mesh.pairs, expected.pairs) << c.name;
    EXPECT_EQ(stats.untied_nodes, every_node.untied_nodes) << c.name;
    EXPECT_EQ(stats.repair_rounds, every_node.repair_rounds) << c.name;
    EXPECT_GT(stats.held_nodes, 0u) << c.name;
    EXPECT_LE(int64_t(stats.held_nodes), lattice.num_nodes()) << c.name;
    EXPECT_GT(mesh.num_triangles(), 0u) << c.name;
    repaired += stats.repair_rounds > 0;

    NodeMesh from_samples; // the samples, read near interfaces only
    create_initial_mesh(samples, params, from_samples);
    EXPECT_EQ(from_samples.triangles, expected.triangles) << c.name;
  }
  EXPECT_GT(repaired, 2); // the repair rounds, which hold more nodes, are exercised
}

} // namespace
