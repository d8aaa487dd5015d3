/// @file cmd_create.cpp
/// `voronoimesh create`: the initial mesh alone (`mesh` with no iterations).

#include "commands.hpp"
#include "report.hpp"

#include <memory>

namespace vmcli {

void add_create_command(CLI::App& app, int& exit_code) {
  // mesh's options without improvement, so that `create --mpi` is `mesh --mpi --iterations 0`.
  auto o = std::make_shared<MeshCommandOptions>();
  o->improve.iterations = 0;
  CLI::App* cmd = app.add_subcommand(
      "create", "Create the initial mesh of the Voronoi interface (paper Algorithm 2) and write it (PLY, OBJ, STL, "
                "MSH, VTU, VTP or MEDIT).");
  cmd->add_option("input", o->input,
                  std::string(kInputHelp) + " Without it, the built-in demo: four overlapping spheres.");
  add_output_options(cmd, o->output, true);
  add_create_options(cmd, o->create);
  add_input_options(cmd, o->input_options);
  add_common_options(cmd, o->common, true);
  cmd->add_flag("--mpi", o->mpi,
                "Run under mpirun: create distributed over the ranks, as `mesh --mpi --iterations 0` (-o FILE.pvtu "
                "writes one .vtu piece per rank and a ParaView index; other formats are assembled and written by "
                "rank 0)");
  cmd->callback([o, &exit_code] {
    if (o->mpi) {
      exit_code = mesh_with_mpi(*o);
      return;
    }
    exit_code = run_guarded([&] {
      const vm::PassRegistry registry = vm::builtin_registry();
      Report report(o->common.quiet, o->output.path);
      vm::run_job(creating_job(*o, registry), &report);
      return kOk;
    });
  });
}

} // namespace vmcli
