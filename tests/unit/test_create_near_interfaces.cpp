// Create reading the field itself holds the values of the lattice nodes near
// interfaces only (create/node_values.hpp): every node keeps its winner, and
// the nodes a cut can read keep their values. It must make the very mesh that
// holding every node's values makes, repairs and closing included.

#include "create/create_slabs.hpp"
#include "create/lattice.hpp"
#include "create/node_values.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/array_input.hpp"

#include "voronoimesh/fields/input.hpp"

#include "fixtures.hpp"
#include "nrrd_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
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

// Runs of nodes decided at once where keys run along rows (a label volume's
// regions of one phase) hold exactly the nodes that comparing each node with
// each neighbour holds.
TEST(NodeValues, held_nodes_are_those_next_to_another_key_or_unsure) {
  for (const Lattice kind : {Lattice::bcc, Lattice::cube6})
    for (const bool box : {false, true}) {
      GridSpec grid;
      grid.cells = {70, 40, 36}; // rows of 36 bcc nodes: runs of 16 and shorter ends
      const detail::TetLattice lattice(grid, kind);
      std::mt19937_64 rng(7);
      std::vector<int32_t> key(size_t(lattice.num_nodes()));
      for (int64_t n = 0; n < lattice.num_nodes(); ++n) {
        const detail::GridPoint p = lattice.grid_point(n);
        key[size_t(n)] = (p[0] / 36 + p[1] / 20 + p[2] / 18) % 3; // blocks of one key
        if (rng() % 400 == 0) key[size_t(n)] = rng() % 2 ? -1 : 5; // unsure nodes, lone keys
      }
      const std::vector<uint8_t> held = detail::held_near_interfaces(lattice, key, box);
      int64_t count = 0;
      for (int64_t n = 0; n < lattice.num_nodes(); ++n) {
        const detail::GridPoint p = lattice.grid_point(n);
        const bool on_box = p[0] == 0 || p[1] == 0 || p[2] == 0 || p[0] == grid.cells[0] || p[1] == grid.cells[1] ||
                            p[2] == grid.cells[2];
        bool expected = key[size_t(n)] < 0 || (box && on_box);
        lattice.for_each_neighbour(n, [&](int64_t m) { expected = expected || key[size_t(m)] != key[size_t(n)]; });
        ASSERT_EQ(held[size_t(n)] != 0, expected) << "node " << n << " at " << p[0] << ", " << p[1] << ", " << p[2];
        count += expected;
      }
      EXPECT_LT(count, lattice.num_nodes() / 2) << "most nodes lie in runs of one key";
    }
}

/// `field` with nothing said of regions one phase fills alone
/// (PhaseField::same_top_values()'s default): sampled node by node.
class NodeByNode final : public PhaseField {
public:
  explicit NodeByNode(const PhaseField& field) : field_(field) {}
  int num_phases() const override { return field_.num_phases(); }
  std::string phase_name(int i) const override { return field_.phase_name(i); }
  void values(const Vec3& x, std::span<double> out) const override { field_.values(x, out); }
  double value(int i, const Vec3& x) const override { return field_.value(i, x); }
  Vec3 gradient(int i, const Vec3& x) const override { return field_.gradient(i, x); }
  void top_values(const Vec3& x, std::span<int32_t> ids, std::span<double> vals) const override {
    field_.top_values(x, ids, vals);
  }

private:
  const PhaseField& field_;
};

// A label volume's field says where one phase fills a run of lattice nodes,
// which are then sampled once: the nodes get what sampling each gives them.
TEST(NodeValues, runs_one_phase_fills_hold_what_each_node_sampled_holds) {
  constexpr int n = 56;
  std::vector<uint8_t> labels;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const bool ball = std::hypot(i - 27.3, j - 25.6, k - 28.1) < 17;
        labels.push_back(uint8_t(i == 6 && j == 7 && k == 8 ? 3 : k >= 30 && k < 34 ? 2 : ball ? 1 : 0));
      }
  const Scene scene = load_input(
      test::write_nrrd("runs.nrrd", "type: uchar\ndimension: 3\nsizes: 56 56 56\nspacings: 1 1 1\n", labels));
  const NodeByNode node_by_node(*scene.field);
  for (const Lattice kind : {Lattice::bcc, Lattice::cube6}) {
    const GridSpec grid = grid_for_lattice(scene.grid, kind);
    const detail::TetLattice lattice(grid, kind);
    const double snap = 0.2 * grid.h(), untie = kUntieFraction * grid.h();
    const detail::NodeValues runs(detail::NodeSource(*scene.field, grid, 4), lattice, snap, untie, false);
    const detail::NodeValues each(detail::NodeSource(node_by_node, grid, 4), lattice, snap, untie, false);
    ASSERT_EQ(runs.held_nodes(), each.held_nodes());
    for (int64_t node = 0; node < lattice.num_nodes(); ++node) {
      ASSERT_EQ(runs.label(node), each.label(node)) << "node " << node;
      ASSERT_EQ(runs.held(node), each.held(node)) << "node " << node;
      if (!runs.held(node)) continue;
      for (int32_t phase = 0; phase < scene.field->num_phases(); ++phase)
        ASSERT_EQ(runs.value(node, phase), each.value(node, phase)) << "node " << node << ", phase " << phase;
    }
    EXPECT_LT(runs.held_nodes(), lattice.num_nodes() / 4) << "most nodes lie in runs of one phase";
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
