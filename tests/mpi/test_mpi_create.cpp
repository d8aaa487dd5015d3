// Distributed create (mpi/distributed.hpp), run under mpirun with 2 and 4 ranks: the mesh
// the ranks make together is the one one process makes, node for node and
// triangle for triangle in the same order, and a failure on one rank is an
// error on every rank, not a hang. Rank 0 compares; every rank runs every test
// in the same order (each test makes the same collective calls on all ranks).

#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/array_input.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/mpi/distributed.hpp"
#include "voronoimesh/run/meshing.hpp"

#include "mpi_test_helpers.hpp"
#include "random_scenes.hpp"
#include "tiny_loop_volume.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>

namespace {

using namespace vm;
using namespace vm::test;

/// The parts' global ids and owners agree with the assembled mesh: every
/// vertex of a part is the assembled vertex of its id, each id owned by one
/// rank, and each part triangle is the assembled triangle its id names.
void expect_parts_match(const mpi::MeshPart& part, const NodeMesh& whole) {
  std::vector<double> rows; // id, owner, x, y, z per vertex; then -1, first triangle, 0, 0, 0
  for (size_t v = 0; v < part.points.size(); ++v)
    rows.insert(rows.end(), {double(part.global_ids[v]), double(part.owners[v]), part.points[v].x(),
                             part.points[v].y(), part.points[v].z()});
  int count = int(rows.size());
  std::vector<int> counts(static_cast<size_t>(ranks())), offsets(static_cast<size_t>(ranks()));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<double> all(rank() == 0 ? size_t(offsets.back() + counts.back()) : 0);
  MPI_Gatherv(rows.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
              MPI_COMM_WORLD);
  if (rank() != 0) return;
  std::vector<int> owner(whole.points.size(), -1);
  for (size_t i = 0; i + 4 < all.size(); i += 5) {
    const size_t id = size_t(all[i]);
    ASSERT_LT(id, whole.points.size());
    EXPECT_EQ(Vec3(all[i + 2], all[i + 3], all[i + 4]), whole.points[id]) << "vertex " << id;
    EXPECT_TRUE(owner[id] == -1 || owner[id] == int(all[i + 1])) << "vertex " << id << " has two owners";
    owner[id] = int(all[i + 1]);
  }
  EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0) << "vertices in no part";
  for (size_t t = 0; t < part.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(part.global_ids[size_t(part.triangles[t][size_t(c)])],
                whole.triangles[size_t(part.triangle_ids[t])][size_t(c)]);
}

/// Creates `scene` on every rank together and in one process on rank 0, and
/// compares: the same nodes, triangles and pairs in the same order. Returns
/// what the distributed create did. The mesh must not be empty unless
/// `may_be_empty` (a random scene).
mpi::DistributedStats expect_same_as_one_process(const Scene& scene, MeshOptions o, bool may_be_empty = false) {
  o.threads = 1; // ranks share two cores
  mpi::DistributedStats stats;
  const mpi::MeshPart part = mpi::create_part(MPI_COMM_WORLD, scene, o, &stats);
  const NodeMesh together = mpi::assemble(MPI_COMM_WORLD, part);
  expect_parts_match(part, together);
  EXPECT_EQ(stats.slabs.size(), size_t(ranks()));
  if (rank() != 0) return stats;
  const NodeMesh alone = create_mesh(scene, o);
  if (!may_be_empty) EXPECT_GT(alone.num_triangles(), 0u);
  expect_same_mesh(together, alone);
  return stats;
}

TEST(MpiCreate, four_spheres_is_the_one_process_mesh) {
  expect_same_as_one_process(example("four_spheres.json", 32), {});
}

TEST(MpiCreate, closed_cube6_four_spheres_is_the_one_process_mesh) {
  MeshOptions o;
  o.lattice = Lattice::cube6;
  o.close = true;
  expect_same_as_one_process(example("four_spheres.json", 20), o);
}

TEST(MpiCreate, voronoi30_is_the_one_process_mesh) { expect_same_as_one_process(example("voronoi30.json", 36), {}); }

TEST(MpiCreate, label_volume_is_the_one_process_mesh) { expect_same_as_one_process(grains(), {}); }

// Closed triple curves far smaller than a cell are closed on every rank
// as in one process: tiny_loop_labels(), its edge slices repeated (as
// smoothing repeats them) to 16 slices, for slabs enough.
TEST(MpiCreate, tiny_loops_closed_as_in_one_process) {
  const std::vector<int32_t> crop = tiny_loop_labels();
  GridSpec grid;
  grid.cells = {5, 5, 15};
  grid.domain.max = Vec3(5, 5, 15);
  std::vector<int32_t> labels;
  for (int z = 0; z <= 15; ++z) { // 4 slices below, 6 above: the lattice's parity kept
    const auto slice = crop.begin() + 36 * std::clamp(z - 4, 0, 5);
    labels.insert(labels.end(), slice, slice + 36);
  }
  const mpi::DistributedStats stats = expect_same_as_one_process(scene_from_labels(grid, labels), {});
  EXPECT_GT(stats.create.tiny_loop_nodes, 0u);
}

// The property tier's random cases (tests/property), created by the ranks
// together: ties, repairs, thin slabs and tiny loops fall on the ranks' slab
// boundaries wherever chance puts them. A rank that sees a tiny loop whole
// sees every triangle at it (the ghost slab beyond its own holds the
// tetrahedra around the loop's vertices), so it judges the loop's window as
// one process does; one that sees part of it sees an open curve, no loop.
TEST(MpiCreate, random_cases_are_the_one_process_mesh) {
  constexpr uint64_t kSeed = 104, kCases = 64;
  int closed = 0, run = 0;
  for (uint64_t index = 0; index < kCases; ++index) {
    const RandomCase c = random_case(kSeed, index);
    if (!has_a_slab_per_rank(c.scene.grid, c.options.lattice)) continue;
    SCOPED_TRACE(c.description());
    ++run;
    closed += expect_same_as_one_process(c.scene, c.options, true).create.tiny_loop_nodes > 0;
  }
  EXPECT_GE(run, int(kCases) * 3 / 4);
  EXPECT_GE(closed, 4) << "too few cases with tiny loops to say anything about them";
}

// Integer values tie everywhere: create needs repair rounds, and every rank
// must make the repairs one process makes (test_create_ties.cpp).
TEST(MpiCreate, repairs_of_tied_data_are_those_of_one_process) {
  std::mt19937_64 rng(20261121);
  int repaired = 0;
  for (int trial = 0; trial < 4; ++trial) {
    GridSpec grid;
    grid.cells = {8, 8, 12 + 2 * trial};
    const int phases = 3 + trial % 3;
    std::vector<std::vector<double>> values(size_t(phases), std::vector<double>(size_t(grid.node_count())));
    for (auto& phase : values)
      for (double& v : phase) v = double(rng() % 3);
    std::vector<std::span<const double>> spans(values.begin(), values.end());
    const Scene scene = scene_from_phase_values(grid, spans);
    MeshOptions o;
    o.lattice = trial % 2 ? Lattice::bcc : Lattice::cube6;
    o.snap = trial % 3 == 0 ? 0.0 : 0.2;
    repaired += expect_same_as_one_process(scene, o).create.untied_nodes > 0;
  }
  EXPECT_GE(repaired, 2);
}

// Blocks of samples made where the data live, of uneven sizes.
TEST(MpiCreate, blocks_of_samples_give_the_one_process_mesh) {
  const Scene scene = example("four_spheres.json", 24);
  const GridSpec grid = grid_for_lattice(scene.grid, Lattice::bcc);
  const int layers = grid.cells[2] + 1, n = ranks(), r = rank();
  // Rank r holds a share growing with r.
  auto start = [&](int q) { return q * q * layers / (n * n); };
  const SampledField block = SampledField::sample(*scene.field, grid, 4, {start(r), start(r + 1) - 1});
  const mpi::MeshPart part = mpi::create_part(MPI_COMM_WORLD, block, CreateParams{});
  const NodeMesh together = mpi::assemble(MPI_COMM_WORLD, part);
  if (rank() != 0) return;
  NodeMesh alone;
  create_initial_mesh(SampledField::sample(*scene.field, grid), CreateParams{}, alone);
  EXPECT_EQ(together.points, alone.points);
  EXPECT_EQ(together.triangles, alone.triangles);
  EXPECT_EQ(together.pairs, alone.pairs);
}

// A phase that is NaN in the top layers only: the rank sampling them fails,
// and every rank throws its error.
TEST(MpiCreate, nan_in_one_block_fails_every_rank) {
  Scene scene = parse_scene(R"json({"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": 16, "phases": [
      {"kind": "sphere", "center": [0.5, 0.5, 0.5], "radius": 0.3},
      {"kind": "expr", "expr": "z > 0.9 ? sqrt(-1) : 0.1 - abs(x - 0.5)"}]})json",
                            "nan_scene");
  MeshOptions o;
  o.threads = 1;
  expect_every_rank_throws<InvalidInput>([&] { mpi::create_part(MPI_COMM_WORLD, scene, o); },
                                         "rank " + std::to_string(ranks() - 1) + " of " + std::to_string(ranks()),
                                         "NaN");
  // The ranks are still in step: a collective call after the failure works.
  const mpi::MeshPart part = mpi::create_part(MPI_COMM_WORLD, example("four_spheres.json", 16), o);
  EXPECT_GT(mpi::assemble(MPI_COMM_WORLD, part).num_triangles() + size_t(rank()), 0u);
}

// Blocks that do not cover the grid: every rank refuses, none waits.
TEST(MpiCreate, blocks_that_leave_a_gap_fail_every_rank) {
  const Scene scene = example("four_spheres.json", 16);
  const GridSpec grid = grid_for_lattice(scene.grid, Lattice::bcc);
  const int per = (grid.cells[2] + 1) / ranks();
  // Rank 1 leaves out its first layer.
  const std::array<int32_t, 2> mine{rank() * per + (rank() == 1), rank() + 1 == ranks() ? grid.cells[2] : (rank() + 1) * per - 1};
  const SampledField block = SampledField::sample(*scene.field, grid, 4, mine);
  expect_every_rank_throws<InvalidInput>([&] { mpi::create_part(MPI_COMM_WORLD, block, CreateParams{}); }, "of ",
                                         "rank 1 holds layers");
}

TEST(MpiCreate, more_ranks_than_slabs_are_refused) {
  if (ranks() < 3) GTEST_SKIP() << "needs 3 ranks or more";
  Scene scene = example("four_spheres.json", 4); // 2 slabs
  expect_every_rank_throws<InvalidInput>([&] { mpi::create_part(MPI_COMM_WORLD, scene, MeshOptions{}); }, "rank 0",
                                         "slabs of the lattice");
}

/// Sets VORONOIMESH_NODE_MEMORY (the node memory create_part() counts on) on
/// this rank while alive.
class NodeMemory {
public:
  explicit NodeMemory(const char* bytes) { setenv("VORONOIMESH_NODE_MEMORY", bytes, 1); }
  ~NodeMemory() { unsetenv("VORONOIMESH_NODE_MEMORY"); }
  NodeMemory(const NodeMemory&) = delete;
  NodeMemory& operator=(const NodeMemory&) = delete;
};

// 200 KiB per node, shared by every rank of this one node: the first rank's
// block of a 16^3 grid (17 x 17 x 8 nodes of 56 B on 2 ranks, x 4 on 4) is
// refused before sampling.
TEST(MpiCreate, a_block_beyond_the_node_memory_is_refused_on_every_rank) {
  MeshOptions o;
  o.threads = 1;
  {
    const NodeMemory limit("200K");
    expect_every_rank_throws<InvalidInput>(
        [&] { mpi::create_part(MPI_COMM_WORLD, example("four_spheres.json", 16), o); }, "rank 0 of " + std::to_string(ranks()),
        "grid: layers 0.." );
    try {
      mpi::create_part(MPI_COMM_WORLD, example("four_spheres.json", 16), o);
    } catch (const InvalidInput& e) {
      // Each rank counts on its share: the node's memory over the ranks on it.
      EXPECT_NE(std::string(e.what()).find("(0.20 MiB VORONOIMESH_NODE_MEMORY, " + std::to_string(ranks()) + " ranks)"),
                std::string::npos)
          << e.what();
    }
  }
  // Enough for each rank's share: the same job goes through.
  const NodeMemory limit("1G");
  const mpi::MeshPart part = mpi::create_part(MPI_COMM_WORLD, example("four_spheres.json", 16), o);
  EXPECT_GT(mpi::assemble(MPI_COMM_WORLD, part).num_triangles() + size_t(rank()), 0u);
}

// Blocks already sampled: the window each rank would receive is refused before
// it moves.
TEST(MpiCreate, a_window_beyond_the_node_memory_is_refused_on_every_rank) {
  const Scene scene = example("four_spheres.json", 16);
  const GridSpec grid = grid_for_lattice(scene.grid, Lattice::bcc);
  const int layers = grid.cells[2] + 1;
  const SampledField block = SampledField::sample(*scene.field, grid, 4,
                                                  {rank() * layers / ranks(), (rank() + 1) * layers / ranks() - 1});
  const NodeMemory limit("100K");
  expect_every_rank_throws<InvalidInput>([&] { mpi::create_part(MPI_COMM_WORLD, block, CreateParams{}); },
                                         "rank 0 of " + std::to_string(ranks()), "grid: slabs 0..");
}

TEST(MpiCreate, a_malformed_node_memory_is_refused_on_every_rank) {
  const NodeMemory limit("lots");
  expect_every_rank_throws<InvalidInput>(
      [&] { mpi::create_part(MPI_COMM_WORLD, example("four_spheres.json", 16), MeshOptions{}); }, "rank 0 of ",
      "VORONOIMESH_NODE_MEMORY: expected a positive number of bytes");
}

} // namespace
