// Benchmark of create (paper Algorithm 2): one scene, one grid, one thread
// count per run, so peak memory can be measured per configuration.
//
//   bench_create SCENE.json GRID THREADS [REPEATS]
//
// Prints one Markdown table row: scene, grid, threads, tets visited, tets cut,
// triangles, best create time, of which the validation that guards against
// snapping pinches, ns per tet visited, sampling time, peak RSS.

#include "voronoimesh/create.hpp"
#include "voronoimesh/scene.hpp"

#include <sys/resource.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: bench_create SCENE.json GRID THREADS [REPEATS]\n");
    return 2;
  }
  const std::string path = argv[1];
  const int grid = std::atoi(argv[2]);
  const int threads = std::atoi(argv[3]);
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 5;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

  vm::Scene scene = vm::load_scene(path);
  scene.grid.cells = {grid, grid, grid};
  vm::CreateParams params;
  const vm::GridSpec g = vm::grid_for_lattice(scene.grid, params.lattice);
  auto t0 = std::chrono::steady_clock::now();
  vm::SampledField field = vm::SampledField::sample(*scene.field, g);
  const double sampling = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  double best = 1e300, check = 0;
  vm::CreateStats stats;
  vm::NodeMesh mesh;
  for (int r = 0; r < repeats; ++r) {
    stats = vm::create_initial_mesh(field, params, mesh);
    if (stats.seconds < best) best = stats.seconds, check = stats.check_seconds;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("| %s | %d^3 | %d | %llu | %llu | %zu | %.1f | %.1f | %.1f | %.2f | %.0f |\n",
              std::filesystem::path(path).stem().c_str(), grid, threads,
              (unsigned long long)stats.tets_visited, (unsigned long long)stats.tets_cut, mesh.num_triangles(),
              best * 1e3, check * 1e3, best * 1e9 / double(stats.tets_visited), sampling, usage.ru_maxrss / 1024.0);
  return 0;
}
