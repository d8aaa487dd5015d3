#include "commands.hpp"

#include <memory>

namespace vmcli {

void add_create_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string input;
    OutputOptions output;
    CreateOptions create;
    InputCliOptions input_options;
    CommonOptions common;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "create", "Create the initial mesh of the Voronoi interface (paper Algorithm 2) and write it (PLY, OBJ, STL, "
                "MSH, VTU, VTP or MEDIT).");
  cmd->add_option("input", o->input,
                  std::string(kInputHelp) + " Without it, the built-in demo: four overlapping spheres.");
  add_output_options(cmd, o->output, true);
  add_create_options(cmd, o->create);
  add_input_options(cmd, o->input_options);
  add_common_options(cmd, o->common, true);
  cmd->callback([o, &exit_code] {
    exit_code = run_guarded([&] {
      check_outputs(o->output);
      auto limit = thread_limit(o->common);
      Progress progress(!o->common.quiet);
      vm::Scene scene = read_input(o->input, o->input_options, o->create.top_k, progress, o->common.quiet);
      vm::NodeMesh mesh = create_stage(scene, o->create, o->common, progress);
      write_outputs(mesh, o->output, o->common);
      return kOk;
    });
  });
}

} // namespace vmcli
