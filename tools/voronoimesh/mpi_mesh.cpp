/// @file mpi_mesh.cpp
/// `voronoimesh mesh --mpi`: every rank runs this; the library's distributed
/// calls (voronoimesh/mpi.hpp) agree on failures, and so does every step of a
/// rank's own (run_collectively), so no rank waits for one that gave up.

#include "commands.hpp"

#include "voronoimesh/closed_domain.hpp"
#include "voronoimesh/errors.hpp"
#include "voronoimesh/mpi.hpp"
#include "voronoimesh/validate.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

namespace vmcli {

namespace {

vm::MeshOptions mesh_options(const MeshCommandOptions& o) {
  vm::MeshOptions m;
  if (!o.create.grid.empty()) {
    if (o.create.grid.size() != 1 && o.create.grid.size() != 3)
      throw vm::InvalidInput("--grid: give one number or three (nx,ny,nz)");
    for (size_t a = 0; a < 3; ++a) m.grid[a] = o.create.grid[o.create.grid.size() == 1 ? 0 : a];
  }
  m.snap = o.create.snap;
  m.lattice = o.create.lattice == "cube6" ? vm::Lattice::cube6 : vm::Lattice::bcc;
  m.top_k = o.create.top_k;
  m.close = o.create.close;
  m.validate = !o.create.skip_validation;
  m.threads = o.common.threads;
  return m;
}

void print_summary(const vm::mpi::MeshPart& part, const vm::mpi::DistributedStats& s) {
  const auto [least, most] = std::minmax_element(s.interface_tets.begin(), s.interface_tets.end());
  uint64_t total = 0;
  for (uint64_t t : s.interface_tets) total += t;
  const double mean = double(total) / double(s.interface_tets.size());
  std::fprintf(stderr,
               "create (mpi, %zu ranks): %lld vertices, %lld triangles; create %.3f s (slowest rank); rank 0: "
               "%.3f s, %.0f%% in MPI; interface tetrahedra per rank %llu..%llu (max/mean %.2f)\n",
               s.interface_tets.size(), (long long)part.global_nodes, (long long)part.global_triangles,
               s.create.seconds, s.seconds, s.seconds > 0 ? 100 * s.mpi_seconds / s.seconds : 0.0,
               (unsigned long long)*least, (unsigned long long)*most, mean > 0 ? double(*most) / mean : 1.0);
}

} // namespace

int mesh_with_mpi(const MeshCommandOptions& o) {
  MPI_Init(nullptr, nullptr);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const bool quiet = o.common.quiet || rank != 0;
  const bool pieces = std::filesystem::path(o.output.path).extension() == ".pvtu";
  const int code = run_guarded(
      [&] {
        vm::Scene scene;
        vm::PassRegistry registry;
        vm::MeshOptions options;
        bool distributed = false; // improved over the ranks, not on rank 0
        std::optional<vm::Pipeline> pipeline;
        vm::mpi::run_collectively(MPI_COMM_WORLD, [&] {
          registry = pass_registry(o.improve.plugins, quiet);
          check_improve_options(o.improve, registry);
          pipeline = vm::Pipeline::parse(o.improve.pipeline, registry);
          distributed = o.improve.iterations > 0 && vm::mpi::distributes(*pipeline) &&
                        !o.improve.stop_when_converged && o.improve.history.empty();
          if (pieces) {
            if (o.improve.iterations > 0 && !distributed)
              throw vm::InvalidInput("-o " + o.output.path + ": pieces per rank (.pvtu) need a distributed " +
                                     "improvement (passes smooth, project, clamp, flip; no --stop-when-converged " +
                                     "or --history) or --iterations 0");
            if (!o.output.per_phase.empty()) throw vm::InvalidInput("--per-phase: not with pieces per rank (.pvtu)");
            check_writable(o.output.path);
          } else {
            check_outputs(o.output);
          }
          options = mesh_options(o);
          Progress silent(false);
          scene = read_input(o.input, o.input_options, o.create.top_k, silent, quiet);
        });
        vm::mpi::DistributedStats stats;
        vm::mpi::MeshPart part = vm::mpi::create_part(MPI_COMM_WORLD, scene, options, &stats);
        if (!quiet) print_summary(part, stats);
        const auto phases = o.create.close ? vm::with_outside_phase(scene.field, part.domain) : scene.field;
        if (distributed) {
          auto limit = thread_limit(o.common);
          vm::mpi::DistributedStats improved;
          vm::mpi::improve_part(MPI_COMM_WORLD, part, *phases, *pipeline, o.improve.iterations, !o.improve.unguarded,
                                &improved);
          if (!quiet)
            std::fprintf(stderr, "improve (mpi): %d iterations of %s; rank 0: %.3f s, %.0f%% in MPI\n",
                         o.improve.iterations, o.improve.pipeline.c_str(), improved.seconds,
                         improved.seconds > 0 ? 100 * improved.mpi_seconds / improved.seconds : 0.0);
        }
        if (pieces) {
          vm::mpi::write_pvtu(MPI_COMM_WORLD, part, o.output.path);
          return kOk;
        }
        vm::NodeMesh mesh = vm::mpi::assemble(MPI_COMM_WORLD, part);
        vm::mpi::run_collectively(MPI_COMM_WORLD, [&] {
          if (rank != 0) return;
          if (distributed) {
            vm::require_valid(mesh, "the improved mesh");
          } else if (o.improve.iterations > 0) {
            // Passes, stopping rules or histories that are not distributed: rank 0 alone.
            if (!quiet) std::fprintf(stderr, "improve: on rank 0 alone (the pipeline or options are not distributed)\n");
            auto limit = thread_limit(o.common);
            Progress progress(!o.common.quiet);
            improve_stage(mesh, phases.get(), o.improve, registry, o.common, progress);
          }
          write_outputs(mesh, o.output, o.common);
        });
        return kOk;
      },
      rank == 0);
  MPI_Finalize();
  return code;
}

} // namespace vmcli
