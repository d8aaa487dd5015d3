// Distributed improvement (mpi.hpp, improve_part()), run under mpirun with 2
// and 4 ranks: after 20 iterations of the moving passes (with and without the
// crossing guard) and of the paper's pipeline with flips, the ranks' mesh is
// the one one process makes, positions bit for bit, and it is valid; passes that
// are not distributed yet are refused on every rank.

#include "voronoimesh/errors.hpp"
#include "voronoimesh/meshing.hpp"
#include "voronoimesh/mpi.hpp"
#include "voronoimesh/registry.hpp"
#include "voronoimesh/validate.hpp"

#include "mpi_test_helpers.hpp"

#include <gtest/gtest.h>

namespace {

using namespace vm;
using namespace vm::test;

constexpr const char* kMovingPasses = "smooth,project,clamp";
// The paper's pipeline; collapses (not in the paper) are not distributed yet.
constexpr const char* kWithFlips = "smooth,project,clamp,flip:collapse_below=0";

void expect_same_as_one_process(const Scene& scene, int iterations, bool guard_crossings,
                                const char* passes = kMovingPasses) {
  MeshOptions o;
  o.threads = 1; // ranks share two cores
  const Pipeline pipeline = Pipeline::parse(passes, builtin_registry());
  mpi::MeshPart part = mpi::create_part(MPI_COMM_WORLD, scene, o);
  mpi::improve_part(MPI_COMM_WORLD, part, *scene.field, pipeline, iterations, guard_crossings);
  const NodeMesh together = mpi::assemble(MPI_COMM_WORLD, part);
  if (rank() != 0) return;
  InterfaceMesh alone = InterfaceMesh::from_node_mesh(create_mesh(scene, o));
  RunOptions run;
  run.iterations = iterations;
  run.guard_crossings = guard_crossings;
  pipeline.run(alone, scene.field.get(), run);
  const NodeMesh expected = alone.to_node_mesh();
  ASSERT_EQ(together.points.size(), expected.points.size());
  EXPECT_EQ(together.points, expected.points);
  EXPECT_EQ(together.triangles, expected.triangles);
  EXPECT_EQ(together.pairs, expected.pairs);
  const ValidationReport report = validate(together);
  EXPECT_TRUE(report.ok()) << report.summary();
}

TEST(MpiImprove, four_spheres_after_20_iterations_is_the_one_process_mesh) {
  expect_same_as_one_process(example("four_spheres.json", 32), 20, true);
}

// voronoi30 has quadruple points closer than a grid cell: the guard undoes moves
// there in the first iterations (test_improve.cpp), across the ranks' cuts too.
TEST(MpiImprove, voronoi30_after_20_iterations_is_the_one_process_mesh) {
  expect_same_as_one_process(example("voronoi30.json", 36), 20, true);
}

TEST(MpiImprove, without_the_guard_too) { expect_same_as_one_process(example("voronoi30.json", 36), 20, false); }

// Flips near a cut are decided in sub-rounds (mpi/flip_peers.hpp): the ranks
// flip what one process flips, and the crossing checks agree on culprits.
TEST(MpiImprove, four_spheres_with_flips_is_the_one_process_mesh) {
  expect_same_as_one_process(example("four_spheres.json", 32), 20, true, kWithFlips);
}

TEST(MpiImprove, voronoi30_with_flips_is_the_one_process_mesh) {
  expect_same_as_one_process(example("voronoi30.json", 36), 20, true, kWithFlips);
}

TEST(MpiImprove, passes_not_yet_distributed_are_refused_on_every_rank) {
  const Scene scene = example("four_spheres.json", 16);
  mpi::MeshPart part = mpi::create_part(MPI_COMM_WORLD, scene, MeshOptions{});
  for (auto [passes, problem] : {std::pair{"smooth,project,clamp,flip", "collapses are not distributed"},
                                 {"smooth,stats", "'stats' is not distributed"}}) {
    const Pipeline pipeline = Pipeline::parse(passes, builtin_registry());
    expect_every_rank_throws<InvalidInput>(
        [&] { mpi::improve_part(MPI_COMM_WORLD, part, *scene.field, pipeline, 1); }, "rank 0", problem);
  }
}

} // namespace
