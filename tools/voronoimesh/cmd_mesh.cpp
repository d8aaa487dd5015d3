#include "commands.hpp"

#include <memory>

namespace vmcli {

void add_mesh_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string input;
    OutputOptions output;
    CreateOptions create;
    ImproveOptions improve;
    CommonOptions common;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "mesh", "The main job: create the initial mesh, then improve it (paper Algorithm 1), and write it (PLY, OBJ, "
              "STL, MSH, VTU, VTP or MEDIT).");
  cmd->add_option("input", o->input,
                  "Scene file (JSON, see docs/scenes.md). Without it, the built-in demo: four overlapping spheres.");
  add_output_options(cmd, o->output, true);
  add_create_options(cmd, o->create);
  add_improve_options(cmd, o->improve, 20);
  add_common_options(cmd, o->common, true);
  cmd->callback([o, &exit_code] {
    exit_code = run_guarded([&] {
      check_outputs(o->output);
      check_improve_options(o->improve);
      auto limit = thread_limit(o->common);
      Progress progress(!o->common.quiet);
      vm::Scene scene = o->input.empty() ? vm::demo_scene() : vm::load_scene(o->input);
      vm::NodeMesh mesh = create_stage(scene, o->create, o->common, progress);
      improve_stage(mesh, scene.field.get(), o->improve, o->common, progress);
      write_outputs(mesh, o->output, o->common);
      return kOk;
    });
  });
}

} // namespace vmcli
