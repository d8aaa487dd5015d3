// Distributed create and improvement (mpi/distributed.hpp): wall time, peak memory, time
// inside MPI and bytes sent per rank, and how evenly the work is shared.
// Run under mpirun (bench/run_mpi.sh runs 1, 2 and 4 ranks):
//   mpirun -np N bench_mpi SCENE.json GRID [THREADS [ITERATIONS]]
// Rank 0 prints one Markdown row for create:
//   | scene | grid | ranks | triangles | seconds | work s max/min | peak MB per rank (max) | MPI % (max) | interface tets max/mean |
// seconds: the slowest rank's whole call (sampling, moving layers, create,
// numbering); work: a rank's call less its time inside MPI, slowest and
// fastest rank (their ratio is the imbalance); MPI %: the largest share of a
// rank's call spent inside MPI calls, waiting for slower ranks included.
// With ITERATIONS, then one row for that many iterations of the default
// pipeline over the ranks (improve_part):
//   | scene | grid | ranks | triangles | seconds | work s max/min | CPU s (max) | peak MB per rank (max) | MPI % (max) | MB sent per rank per iteration (max) | collectives per iteration | window / own triangles (max) |
// CPU s: a rank's CPU time, which shows its share of the work where ranks
// share cores; peak MB: the whole run's, create included; window / own: the
// triangles a rank's window holds for those it owns (the halo's redundant work).

#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/registry.hpp"
#include "voronoimesh/mpi/distributed.hpp"

#include <mpi.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (argc < 3) {
    if (rank == 0) std::fprintf(stderr, "usage: mpirun -np N bench_mpi SCENE.json GRID [THREADS [ITERATIONS]]\n");
    MPI_Finalize();
    return 2;
  }
  int code = 0;
  try {
    vm::Scene scene = vm::load_scene(argv[1]);
    const int grid = std::stoi(argv[2]);
    scene.grid.cells = {grid, grid, grid};
    vm::MeshOptions o;
    o.threads = argc > 3 ? std::stoi(argv[3]) : 1;
    vm::mpi::DistributedStats stats;
    MPI_Barrier(MPI_COMM_WORLD);
    vm::mpi::MeshPart part = vm::mpi::create_part(MPI_COMM_WORLD, scene, o, &stats);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double work = stats.seconds - stats.mpi_seconds;
    double mine[4] = {stats.seconds, double(usage.ru_maxrss) / 1024.0, 100 * stats.mpi_seconds / stats.seconds, work};
    double most[4], least_work = 0;
    MPI_Reduce(mine, most, 4, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    MPI_Reduce(&work, &least_work, 1, MPI_DOUBLE, MPI_MIN, 0, MPI_COMM_WORLD);
    // CPU time shows each rank's share of the work even where ranks share cores.
    const double cpu = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    std::fprintf(stderr,
                 "rank %d: slabs %d..%d, %zu triangles, %.3f s, work %.3f s, cpu %.3f s, %.1f MB peak, %.1f %% in MPI\n",
                 rank, part.slabs[0], part.slabs[1], part.triangles.size(), mine[0], work, cpu, mine[1], mine[2]);
    if (rank == 0) {
      uint64_t total = 0;
      for (uint64_t t : stats.interface_tets) total += t;
      const uint64_t max_tets = *std::max_element(stats.interface_tets.begin(), stats.interface_tets.end());
      std::printf("| %s | %d^3 | %d | %lld | %.2f | %.2f / %.2f | %.0f | %.1f | %.2f |\n",
                  std::filesystem::path(argv[1]).stem().c_str(), grid, ranks, (long long)part.global_triangles,
                  most[0], most[3], least_work, most[1], most[2],
                  double(max_tets) * ranks / double(std::max<uint64_t>(total, 1)));
    }
    const int iterations = argc > 4 ? std::stoi(argv[4]) : 0;
    if (iterations > 0) {
      const vm::Pipeline pipeline = vm::Pipeline::parse(vm::kDefaultPipeline, vm::builtin_registry());
      vm::mpi::DistributedStats improved;
      MPI_Barrier(MPI_COMM_WORLD);
      vm::mpi::improve_part(MPI_COMM_WORLD, part, *scene.field, pipeline, iterations, true, &improved);
      getrusage(RUSAGE_SELF, &usage);
      const double improve_cpu = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                                 1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) - cpu;
      const double improve_work = improved.seconds - improved.mpi_seconds;
      double mine_i[6] = {improved.seconds, double(usage.ru_maxrss) / 1024.0,
                          100 * improved.mpi_seconds / improved.seconds, improve_work,
                          double(improved.bytes_sent) / 1e6 / iterations, improve_cpu};
      double most_i[6], least_i = 0, halo = double(improved.window_triangles) / double(std::max<uint64_t>(1, improved.own_triangles)), most_halo = 0;
      MPI_Reduce(mine_i, most_i, 6, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
      MPI_Reduce(&improve_work, &least_i, 1, MPI_DOUBLE, MPI_MIN, 0, MPI_COMM_WORLD);
      MPI_Reduce(&halo, &most_halo, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
      std::fprintf(stderr, "rank %d: improve %.3f s, work %.3f s, cpu %.3f s, %.1f %% in MPI, %.2f MB sent/iteration, "
                           "%.1f collectives/iteration, window/own triangles %.2f\n",
                   rank, mine_i[0], improve_work, improve_cpu, mine_i[2], mine_i[4],
                   double(improved.collectives) / iterations, halo);
      if (rank == 0)
        std::printf("| %s | %d^3 | %d | %lld | %.2f | %.2f / %.2f | %.2f | %.0f | %.1f | %.2f | %.0f | %.2f |\n",
                    std::filesystem::path(argv[1]).stem().c_str(), grid, ranks, (long long)part.global_triangles,
                    most_i[0], most_i[3], least_i, most_i[5], most_i[1], most_i[2], most_i[4],
                    double(improved.collectives) / iterations, most_halo);
    }
  } catch (const std::exception& e) {
    if (rank == 0) std::fprintf(stderr, "bench_mpi: %s\n", e.what());
    code = 1;
  }
  MPI_Finalize();
  return code;
}
