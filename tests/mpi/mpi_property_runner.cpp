// The MPI tier of the property tests: random cases [first, first + count) of a
// seed (tests/property/random_scenes.hpp: ties, thin slabs, labels, closed
// boxes) created and improved over the ranks it runs on, and on rank 0 in one
// process; prints a line per case whose assembled mesh is not the one-process
// mesh (positions bit for bit, triangles, pairs) or does not validate, with the
// command that reproduces it. Cases with fewer lattice slabs than ranks (which
// create_part() refuses) or without a mesh are skipped. One thread per rank.
//
//   mpirun -np R mpi_property_runner [--seed S] [--first A] [--count N] [--case I]
//                                    [--iterations K] [--pipeline P] [--verbose]
//
// scripts/mpi_property_tests.sh runs it in batches. The suite's MpiImprove and
// MpiCreate tests run the first few dozen cases of one seed.

#include "mpi_test_helpers.hpp"
#include "random_scenes.hpp"

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/improve/registry.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/mpi/distributed.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <CLI/CLI.hpp>
#include <mpi.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <variant>

namespace {

using namespace vm;
using namespace vm::test;

struct Args {
  uint64_t seed = 1, first = 0, count = 100;
  int iterations = 10;
  std::string pipeline = kDefaultPipeline;
  bool verbose = false;
};

/// The arguments, or an exit code when they are bad or only --help was asked.
std::variant<Args, int> parse(int argc, char** argv) {
  Args a;
  CLI::App app("The MPI tier of the property tests: random cases over the ranks and in one process.",
               "mpi_property_runner");
  app.add_option("--seed", a.seed, "Seed of the random cases");
  app.add_option("--first", a.first, "First case");
  app.add_option("--count", a.count, "Number of cases");
  uint64_t one = 0;
  app.add_option("--case", one, "One case (--first I --count 1)")->excludes("--first", "--count");
  app.add_option("--iterations", a.iterations, "Iterations of the pipeline")->check(CLI::NonNegativeNumber);
  app.add_option("--pipeline", a.pipeline, "Pipeline of distributed passes");
  app.add_flag("--verbose", a.verbose, "Print each case's scene");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (rank() == 0) app.exit(e); // prints the help or the problem
    return e.get_exit_code();
  }
  if (app.count("--case")) a.first = one, a.count = 1;
  return a;
}

std::string text(const Vec3& p) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.17g, %.17g, %.17g)", p.x(), p.y(), p.z());
  return s;
}

/// The first way the ranks' mesh differs from the one-process mesh, or fails
/// validation; empty when it is the same and valid.
std::string first_difference(const NodeMesh& together, const NodeMesh& alone) {
  auto count = [](const char* what, size_t a, size_t b) {
    return std::to_string(a) + " " + what + " over the ranks, " + std::to_string(b) + " in one process";
  };
  if (together.points.size() != alone.points.size()) return count("nodes", together.points.size(), alone.points.size());
  if (together.triangles.size() != alone.triangles.size())
    return count("triangles", together.triangles.size(), alone.triangles.size());
  for (size_t v = 0; v < alone.points.size(); ++v)
    if (together.points[v] != alone.points[v])
      return "node " + std::to_string(v) + " at " + text(together.points[v]) + " over the ranks, " +
             text(alone.points[v]) + " in one process";
  for (size_t t = 0; t < alone.triangles.size(); ++t)
    if (together.triangles[t] != alone.triangles[t] || together.pairs[t] != alone.pairs[t])
      return "triangle " + std::to_string(t) + " differs (nodes or phase pair)";
  const ValidationReport report = validate(together);
  return report.ok() ? std::string() : "the ranks' mesh does not validate: " + report.problems.front();
}

/// The case's difference ("" when none), on rank 0; nothing, on every rank,
/// when the case makes no mesh. Throws as the meshing does.
std::optional<std::string> check(const RandomCase& c, const Pipeline& pipeline, int iterations) {
  MeshOptions o = c.options;
  o.threads = 1;
  mpi::MeshPart part = mpi::create_part(MPI_COMM_WORLD, c.scene, o);
  if (part.global_triangles == 0) return std::nullopt; // the same on every rank
  // A closed mesh's phase outside the box needs its function too.
  const auto phases = part.outside_phase >= 0 ? with_outside_phase(c.scene.field, part.domain) : c.scene.field;
  mpi::improve_part(MPI_COMM_WORLD, part, *phases, pipeline, iterations);
  const NodeMesh together = mpi::assemble(MPI_COMM_WORLD, part);
  if (rank() != 0) return std::string();
  InterfaceMesh alone = InterfaceMesh::from_node_mesh(create_mesh(c.scene, o));
  RunOptions run;
  run.iterations = iterations;
  pipeline.run(alone, phases.get(), run);
  return first_difference(together, alone.to_node_mesh());
}

} // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  const std::variant<Args, int> parsed = parse(argc, argv);
  if (const int* code = std::get_if<int>(&parsed)) {
    MPI_Finalize();
    return *code;
  }
  const Args& a = std::get<Args>(parsed);
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1); // ranks share the cores
  std::optional<Pipeline> pipeline;
  try {
    pipeline = Pipeline::parse(a.pipeline, builtin_registry());
    if (!pipeline->distributes()) throw InvalidInput("'" + a.pipeline + "' has passes that do not run distributed");
  } catch (const std::exception& e) {
    if (rank() == 0) std::fprintf(stderr, "mpi_property_runner: --pipeline: %s\n", e.what());
    MPI_Finalize();
    return 2;
  }
  uint64_t checked = 0, skipped = 0, failed = 0;
  for (uint64_t index = a.first; index < a.first + a.count; ++index) {
    const RandomCase c = random_case(a.seed, index);
    if (a.verbose && rank() == 0) std::printf("case %llu: %s\n", (unsigned long long)index, c.description().c_str());
    std::string difference;
    try {
      const std::optional<std::string> found =
          has_a_slab_per_rank(c.scene.grid, c.options.lattice) ? check(c, *pipeline, a.iterations) : std::nullopt;
      if (!found) {
        ++skipped;
        continue;
      }
      difference = *found;
    } catch (const std::exception& e) { // every rank throws alike, or the ranks hang (the script's time limit)
      difference = "rank " + std::to_string(rank()) + " threw: " + e.what();
    }
    ++checked;
    if (difference.empty()) continue;
    ++failed;
    std::printf("FAIL seed %llu case %llu (%s): %s\n  reproduce: mpirun -np %d mpi_property_runner --seed %llu --case "
                "%llu --iterations %d --pipeline %s --verbose\n",
                (unsigned long long)a.seed, (unsigned long long)index, scene_kind_name(c.kind), difference.c_str(),
                ranks(), (unsigned long long)a.seed, (unsigned long long)index, a.iterations, a.pipeline.c_str());
    std::fflush(stdout);
  }
  if (rank() == 0)
    std::printf("checked %llu cases, %llu failed, %llu skipped (fewer slabs than %d ranks, or no mesh)\n",
                (unsigned long long)checked, (unsigned long long)failed, (unsigned long long)skipped, ranks());
  int any = failed > 0, all = 0;
  MPI_Allreduce(&any, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return all;
}
