/// @file cmd_mesh.cpp
/// `voronoimesh mesh`, the main job: create, improve, write.

#include "commands.hpp"
#include "report.hpp"

#include "voronoimesh/core/errors.hpp"

#include <memory>

namespace vmcli {

#ifndef VORONOIMESH_MPI
int mesh_with_mpi(const MeshCommandOptions&) {
  return run_guarded([]() -> int {
    throw vm::InvalidInput("--mpi: this voronoimesh was built without MPI (configure with -DVM_MPI=ON)");
  });
}
#endif

void add_mesh_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<MeshCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh", "The main job: create the initial mesh, then improve it (paper Algorithm 1), and write it (PLY, OBJ, "
              "STL, MSH, VTU, VTP or MEDIT).");
  cmd->add_option("input", o->input,
                  std::string(kInputHelp) + " Without it, the built-in demo: four overlapping spheres.");
  add_output_options(cmd, o->output, true);
  add_create_options(cmd, o->create);
  add_input_options(cmd, o->input_options);
  add_improve_options(cmd, o->improve, 20);
  add_common_options(cmd, o->common, true);
  cmd->add_flag("--mpi", o->mpi,
                "Run under mpirun: create distributed over the ranks, each sampling and meshing its share of the "
                "grid's slabs (balanced by interface tetrahedra), then improve distributed, each rank moving and "
                "flipping in its band of z (the same mesh as one process). -o FILE.pvtu writes one .vtu piece per "
                "rank and a ParaView index; other formats are assembled and written by rank 0. Pipelines with "
                "passes that do not run distributed (plugins, stats), --stop-when-converged and --history improve "
                "on rank 0 alone");
  cmd->callback([o, &exit_code] {
    if (o->mpi) {
      exit_code = mesh_with_mpi(*o);
      return;
    }
    exit_code = run_guarded([&] {
      const vm::PassRegistry registry = pass_registry(o->improve.plugins, o->common.quiet);
      Report report(o->common.quiet, o->improve.iterations, o->output.path);
      vm::run_job(creating_job(*o, registry), &report);
      return kOk;
    });
  });
}

} // namespace vmcli
