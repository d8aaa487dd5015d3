#pragma once
// What the MPI tests share: the rank, examples at a grid, whether a grid has
// slabs for every rank, and a check that a failure reaches every rank.

#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/array_input.hpp"
#include "voronoimesh/fields/scene.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <optional>
#include <random>
#include <string>
#include <vector>

namespace vm::test {

inline int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

inline int ranks() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

/// True when `grid` on `lattice` (bcc when unset) has a lattice slab for every
/// rank: create_part() refuses fewer (more_ranks_than_slabs_are_refused).
inline bool has_a_slab_per_rank(const GridSpec& grid, std::optional<Lattice> lattice) {
  const Lattice kind = lattice.value_or(Lattice::bcc);
  return grid_for_lattice(grid, kind).cells[2] / (kind == Lattice::bcc ? 2 : 1) >= ranks();
}

inline Scene example(const std::string& name, int grid) {
  Scene scene = load_scene(std::string(VM_EXAMPLES_DIR) + "/" + name);
  scene.grid.cells = {grid, grid, grid};
  return scene;
}

/// A label volume: grains, a label per node from the nearest of 12 random seeds.
inline Scene grains() {
  GridSpec grid;
  grid.cells = {24, 22, 26};
  std::mt19937_64 rng(8);
  std::vector<Vec3> seeds;
  for (int s = 0; s < 12; ++s) seeds.push_back(Vec3(double(rng() % 1000), double(rng() % 1000), double(rng() % 1000)) / 1000);
  std::vector<int32_t> labels(size_t(grid.node_count()));
  for (int64_t k = 0; k <= grid.cells[2]; ++k)
    for (int64_t j = 0; j <= grid.cells[1]; ++j)
      for (int64_t i = 0; i <= grid.cells[0]; ++i) {
        const Vec3 x = grid.node_position(i, j, k);
        int best = 0;
        for (int s = 1; s < 12; ++s)
          if ((x - seeds[size_t(s)]).norm() < (x - seeds[size_t(best)]).norm()) best = s;
        labels[size_t(grid.node_index(i, j, k))] = 10 * best;
      }
  return scene_from_labels(grid, labels);
}

/// The ranks' assembled mesh is the one-process mesh: the same nodes (positions
/// bit for bit), triangles, pairs and phases, and it validates. Callers
/// check that it is not empty where it must not be.
inline void expect_same_mesh(const NodeMesh& together, const NodeMesh& alone) {
  EXPECT_EQ(together.points, alone.points);
  EXPECT_EQ(together.triangles, alone.triangles);
  EXPECT_EQ(together.pairs, alone.pairs);
  EXPECT_EQ(together.phase_names, alone.phase_names);
  EXPECT_EQ(together.phase_labels, alone.phase_labels);
  const ValidationReport report = validate(together);
  EXPECT_TRUE(report.ok()) << report.summary();
}

/// Runs `f` on every rank and checks that every rank throws E naming `rank`.
template <class E, class F> void expect_every_rank_throws(F&& f, const std::string& rank_text, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "rank " << rank() << " did not throw";
  } catch (const E& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(rank_text), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

} // namespace vm::test
