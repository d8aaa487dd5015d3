// Benchmark of mesh improvement (paper sect. 4.2-4.3): one scene, grid and
// thread count per run. Creates the initial mesh, then runs the paper's pipeline
// (smooth, project, clamp, flip) for ITERATIONS iterations.
//
//   bench_improve SCENE.json GRID THREADS ITERATIONS [unguarded]
//
// "unguarded" turns the crossing guard (guard.hpp) off, to measure its cost.
// Prints one Markdown table row: scene, grid, threads, triangles, total time,
// time per iteration, time per iteration per node (µs), each pass's share per
// iteration (smooth, project, clamp + commit, flip), final min and mean quality.

#include "voronoimesh/create.hpp"
#include "voronoimesh/pipeline.hpp"
#include "voronoimesh/scene.hpp"

#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: bench_improve SCENE.json GRID THREADS ITERATIONS [unguarded]\n");
    return 2;
  }
  const int grid = std::atoi(argv[2]), threads = std::atoi(argv[3]), iterations = std::atoi(argv[4]);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  vm::Scene scene = vm::load_scene(argv[1]);
  scene.grid.cells = {grid, grid, grid};
  vm::SampledField field = vm::SampledField::sample(*scene.field, vm::grid_for_lattice(scene.grid, vm::Lattice::bcc));
  vm::NodeMesh initial;
  vm::create_initial_mesh(field, {}, initial);
  vm::InterfaceMesh mesh = vm::InterfaceMesh::from_node_mesh(initial);

  const vm::PassRegistry registry = vm::builtin_registry();
  const vm::Pipeline pipeline = vm::Pipeline::parse(vm::kDefaultPipeline, registry);
  std::vector<double> per_pass(pipeline.steps().size(), 0.0);
  double total = 0, min_q = 0, mean_q = 0;
  vm::RunOptions run;
  run.iterations = iterations;
  run.guard_crossings = !(argc > 5 && std::string(argv[5]) == "unguarded");
  run.observer = [&](const vm::IterationReport& r, const vm::InterfaceMesh&) {
    total += r.seconds;
    for (size_t i = 0; i < r.pass_seconds.size(); ++i) per_pass[i] += r.pass_seconds[i];
    min_q = r.min_quality, mean_q = r.mean_quality;
  };
  pipeline.run(mesh, scene.field.get(), run);
  const double it = iterations;
  std::printf("| %s | %d^3 | %d | %zu | %.3f | %.2f | %.3f |", std::filesystem::path(argv[1]).stem().c_str(), grid,
              threads, mesh.num_triangles(), total, total / it * 1e3, total / it * 1e6 / double(mesh.num_nodes()));
  for (double p : per_pass) std::printf(" %.2f |", p / it * 1e3);
  std::printf(" %.3f | %.3f |\n", min_q, mean_q);
  return 0;
}
