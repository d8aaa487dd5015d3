// Uses only the installed headers and libraries (mpi/distributed.hpp, voronoimesh_mpi): every
// rank creates its part of the built-in demo (the paper's four overlapping spheres),
// rank 0 assembles it, checks it is the mesh one process makes and writes it to the
// PLY file named on the command line. Exit code 0 on every rank only if all of that
// worked; install_test.sh checks the written file again with the installed CLI.

#include <voronoimesh/core/errors.hpp>
#include <voronoimesh/io/write_mesh.hpp>
#include <voronoimesh/run/meshing.hpp>
#include <voronoimesh/mpi/distributed.hpp>
#include <voronoimesh/fields/scene.hpp>

#include <mpi.h>

#include <cstdio>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int code = 0;
  try {
    if (argc != 2) throw vm::InvalidInput("usage: mpi_consumer OUT.ply");
    const vm::Scene scene = vm::demo_scene();
    vm::MeshOptions options;
    options.grid = std::array{32, 32, 32}; // coarser than the demo's 64: fast, and the structure survives
    options.threads = 1;         // the ranks share the test machine's cores
    const vm::mpi::MeshPart part = vm::mpi::create_part(MPI_COMM_WORLD, scene, options);
    const vm::NodeMesh mesh = vm::mpi::assemble(MPI_COMM_WORLD, part);
    // Rank 0's own work, agreed on like the distributed calls: a failure there fails every rank.
    vm::mpi::run_collectively(MPI_COMM_WORLD, [&] {
      if (rank != 0) return;
      const vm::NodeMesh alone = vm::create_mesh(scene, options);
      if (mesh.points != alone.points || mesh.triangles != alone.triangles || mesh.pairs != alone.pairs)
        throw vm::Error("the assembled mesh is not the mesh of one process");
      vm::io::write_mesh(mesh, argv[1]);
      std::printf("mpi consumer: %d ranks, %zu nodes, %zu triangles, the mesh of one process\n", ranks,
                  mesh.num_nodes(), mesh.num_triangles());
    });
  } catch (const vm::Error& e) {
    if (rank == 0) std::fprintf(stderr, "mpi consumer: %s\n", e.what());
    code = 1;
  }
  MPI_Finalize();
  return code;
}
