/// @file cmd_flip.cpp
/// `voronoimesh flip`: edge flips alone on a mesh read from a file.

#include "commands.hpp"
#include "report.hpp"

#include <memory>

namespace vmcli {

void add_flip_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string mesh;
    OutputOptions output;
    CommonOptions common;
  };
  auto f = std::make_shared<Options>();
  CLI::App* flip = app.add_subcommand(
      "flip", "Flip edges to improve triangle quality (paper Algorithm 5) until no flip helps, and write the mesh.");
  flip->add_option("mesh", f->mesh, "Mesh file (.ply written by voronoimesh)")->required();
  add_output_options(flip, f->output, false);
  add_common_options(flip, f->common, true);
  flip->callback([f, &exit_code] {
    exit_code = run_guarded([&] {
      vm::MeshJob job;
      job.mesh = f->mesh;
      job.options.iterations = 1;
      job.options.pipeline = "flip:max_rounds=1000";
      job.options.threads = f->common.threads;
      job.outputs = run_outputs(f->output, f->common);
      Report report(f->common.quiet, f->output.path);
      vm::run_job(job, &report);
      return kOk;
    });
  });
}

} // namespace vmcli
