/// @file mpi/run_job.cpp
/// vm::mpi::run_job(): the run path of run/meshing.hpp over the ranks.

#include "voronoimesh/mpi/distributed.hpp"

#include "run/run_job.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/outside_phase.hpp"

#include <mpi.h>

#include <filesystem>
#include <optional>

namespace vm::mpi {

namespace {

int comm_size(MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  return size;
}

} // namespace

void RunObserver::created_part(const MeshPart&, const DistributedStats&) {}
void RunObserver::improved_parts(int, const std::string&, const DistributedStats&) {}

void run_job(MPI_Comm comm, const MeshJob& job, RunObserver* observer) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const MeshOptions& o = job.options;
  const bool pieces = std::filesystem::path(job.outputs.mesh).extension() == ".pvtu";
  Scene scene;
  std::optional<Pipeline> pipeline;
  bool distributed = false; // improved over the ranks, not on rank 0
  run_collectively(comm, [&] {
    if (!job.mesh.empty())
      throw InvalidInput("mpi: a distributed run creates its mesh; improve a mesh read from a file in one process");
    vm::detail::check_options(o);
    pipeline = vm::detail::parse_pipeline(o);
    distributed = o.iterations > 0 && pipeline->distributes() && job.outputs.history.empty();
    if (pieces) {
      if (o.iterations > 0 && !distributed)
        throw InvalidInput(located(job.outputs.mesh, "pieces per rank (.pvtu) need a distributed improvement (passes "
                                                     "that run distributed; no history) or "
                                                     "no iterations"));
      if (!job.outputs.per_phase.empty()) throw InvalidOption("per_phase", "not with pieces per rank (.pvtu)");
      vm::detail::check_writable(job.outputs.mesh);
      // No piece nor the index may be the input.
      std::vector<std::string> files = pvtu_pieces(job.outputs.mesh, comm_size(comm));
      files.push_back(job.outputs.mesh);
      for (const std::string& file : files) {
        RunOutputs one;
        one.mesh = file;
        vm::detail::check_outputs_apart(one, {job.input});
      }
    } else {
      check_job(job);
    }
    InputOptions input = job.input_options;
    input.top_k = o.top_k;
    scene = read_input(job.input, input, observer);
  });
  DistributedStats created;
  MeshPart part = create_part(comm, scene, o, &created);
  if (observer) observer->created_part(part, created);
  if (distributed) {
    const auto limit = vm::detail::thread_limit(o);
    DistributedStats improved;
    // A closed mesh has one more phase, outside the box; the passes need its function too.
    const auto phases = part.outside_phase >= 0 ? with_outside_phase(scene.field, part.domain) : scene.field;
    improve_part(comm, part, *phases, *pipeline, o.iterations, o.guard_crossings, &improved,
                 vm::detail::stops_when_converged(o, scene));
    if (observer) observer->improved_parts(improved.iterations, pipeline_for(o, nullptr), improved);
  }
  if (pieces) {
    write_pvtu(comm, part, job.outputs.mesh);
    return;
  }
  NodeMesh mesh = assemble(comm, part);
  run_collectively(comm, [&] {
    if (rank != 0) return;
    MeshJob rest = job;
    if (distributed) {
      if (o.validate) require_valid(mesh, "the improved mesh");
      rest.options.iterations = 0;
    } else {
      rest.options.stop_when_converged = vm::detail::stops_when_converged(o, scene);
      if (o.iterations > 0 && observer)
        observer->note("improve: on rank 0 alone (the pipeline or options are not distributed)");
    }
    vm::detail::finish_job(mesh, scene.field, rest, observer);
  });
}

} // namespace vm::mpi
