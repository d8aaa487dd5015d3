/// @file cmd_smooth.cpp
/// `voronoimesh smooth` (and its synonym `improve`): the improvement pipeline
/// on a mesh read from a file.

#include "commands.hpp"
#include "report.hpp"

#include <memory>

namespace vmcli {

void add_smooth_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string mesh, field;
    OutputOptions output;
    ImproveOptions improve;
    InputCliOptions input;
    int top_k = vm::MeshOptions{}.top_k;
    CommonOptions common;
  };
  auto s = std::make_shared<Options>();
  CLI::App* smooth = app.add_subcommand(
      "smooth", "Improve a mesh read from a file: run the improvement pipeline on it (default: the paper's smooth, "
                "project, clamp and flip passes, Algorithm 1) and write it. Also called 'improve'.");
  smooth->alias("improve");
  smooth->add_option("mesh", s->mesh, "Mesh file (.ply written by voronoimesh)")->required();
  CLI::Option* field =
      smooth->add_option("--field", s->field,
                         std::string("The input the mesh was made from (its phase functions, which smoothing and "
                                     "projection need). ") +
                             kInputHelp);
  smooth->add_option("--top-k", s->top_k, "Phases kept per voxel of a --field volume (as given to create)")
      ->capture_default_str();
  add_input_options(smooth, s->input, field);
  add_output_options(smooth, s->output, true);
  add_improve_options(smooth, s->improve, 20);
  add_common_options(smooth, s->common, true);
  smooth->callback([s, &exit_code] {
    exit_code = run_guarded([&] {
      const vm::PassRegistry registry = pass_registry(s->improve.plugins, s->common.quiet);
      vm::MeshJob job;
      job.mesh = s->mesh;
      job.input = s->field;
      job.input_options = input_options(s->input);
      job.options.top_k = s->top_k;
      job.options.threads = s->common.threads;
      job.options.passes = &registry;
      job.outputs = run_outputs(s->output, s->common);
      set_improve_options(s->improve, job);
      // No line on the field read: a field that does not fit the mesh is reported on one line.
      Report report(s->common.quiet, s->output.path, false);
      vm::run_job(job, &report);
      return kOk;
    });
  });
}

} // namespace vmcli
