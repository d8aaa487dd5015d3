/// @file cmd_mesh.cpp
/// `voronoimesh mesh`, the main job: create, improve, write.

#include "commands.hpp"
#include "report.hpp"
#include "sequence.hpp"

#include "voronoimesh/core/errors.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <utility>

#include <sys/stat.h>

namespace vmcli {

#ifndef VORONOIMESH_MPI
int mesh_with_mpi(const MeshCommandOptions&) {
  return run_guarded([]() -> int {
    throw vm::InvalidInput("--mpi: this voronoimesh was built without MPI (configure with -DVM_MPI=ON)");
  });
}
#endif

namespace {

/// Refuses, before any step runs, a sequence whose numbered output for one step
/// is the input of any step: each run checks its output against its own input
/// only, so step 2 of `mesh p_1.ply p_2.ply -o p_%d.ply` would write over p_1.ply.
/// Each file is looked up once (device and inode, so that a link and its
/// target are one file), not each pair of files.
void refuse_outputs_over_inputs(const std::vector<Step>& steps, const std::string& pattern) {
  std::map<std::pair<dev_t, ino_t>, const std::string*> inputs;
  struct stat st {};
  for (const Step& step : steps)
    if (::stat(step.input.c_str(), &st) == 0) inputs.emplace(std::pair{st.st_dev, st.st_ino}, &step.input);
  for (const Step& step : steps) {
    const std::string output = numbered(pattern, step.number);
    if (::stat(output.c_str(), &st) != 0) continue; // an output that does not exist yet is no input
    if (const auto it = inputs.find({st.st_dev, st.st_ino}); it != inputs.end())
      throw vm::InvalidInput(output + ": is also an input of this sequence (" + *it->second +
                             "); an output may not replace what the run reads");
  }
}

/// One run per step of the sequence o.inputs names, each written to the step's
/// number in -o; then the .pvd of VTK outputs.
int mesh_sequence(const MeshCommandOptions& o) {
  return run_guarded([&] {
    if (o.mpi) throw vm::InvalidInput("--mpi: meshes one input; a sequence runs in one process");
    if (!o.output.per_phase.empty()) throw vm::InvalidInput("--per-phase: not with a sequence of inputs");
    if (!o.improve.history.empty()) throw vm::InvalidInput("--history: not with a sequence of inputs");
    if (!is_numbered(o.output.path))
      throw vm::InvalidInput("-o: a sequence needs a numbered output such as out/step_%04d.vtu, got '" +
                             o.output.path + "'");
    const std::vector<Step> steps = sequence_steps(o.inputs);
    refuse_outputs_over_inputs(steps, o.output.path);
    const vm::PassRegistry registry = pass_registry(o.improve.plugins, o.common.quiet);
    std::vector<std::string> written;
    std::vector<double> times;
    for (size_t i = 0; i < steps.size(); ++i) {
      MeshCommandOptions step = o;
      step.input = steps[i].input;
      step.output.path = numbered(o.output.path, steps[i].number);
      Report report(o.common.quiet, step.output.path);
      report.note("step " + std::to_string(i + 1) + " of " + std::to_string(steps.size()) + ": " + step.input +
                  " -> " + step.output.path);
      const auto start = std::chrono::steady_clock::now();
      vm::run_job(creating_job(step, registry), &report);
      report.note("step " + std::to_string(i + 1) + " done in " +
                  std::to_string(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()) +
                  " s");
      written.push_back(step.output.path);
      times.push_back(double(steps[i].number));
    }
    const std::string ext = std::filesystem::path(o.output.path).extension().string();
    if (ext == ".vtu" || ext == ".vtp") {
      const std::string pvd = pvd_name(o.output.path);
      write_pvd(pvd, written, times);
      if (!o.common.quiet) std::fprintf(stderr, "wrote %s: %zu steps\n", pvd.c_str(), written.size());
    }
    return kOk;
  });
}

} // namespace

void add_mesh_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<MeshCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh", "The main job: create the initial mesh, then improve it (paper Algorithm 1), and write it (PLY, OBJ, "
              "STL, MSH, VTU, VTP or MEDIT).");
  cmd->add_option("input", o->inputs,
                  std::string(kInputHelp) +
                      " Without it, the built-in demo: four overlapping spheres. Several inputs, or one numbered "
                      "pattern such as step_%04d.nrrd (every file it matches, in number order), are a sequence: one "
                      "mesh per step, -o numbered likewise (out/step_%04d.vtu), and for .vtu/.vtp a ParaView "
                      "collection out/step.pvd with each step's number as its time");
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
                "passes that do not run distributed (plugins, stats) and --history improve on rank 0 alone");
  cmd->callback([o, &exit_code] {
    if (o->inputs.size() > 1 || (o->inputs.size() == 1 && is_numbered(o->inputs[0]))) {
      exit_code = mesh_sequence(*o);
      return;
    }
    o->input = o->inputs.empty() ? std::string() : o->inputs[0];
    if (o->mpi) {
      exit_code = mesh_with_mpi(*o);
      return;
    }
    exit_code = run_guarded([&] {
      const vm::PassRegistry registry = pass_registry(o->improve.plugins, o->common.quiet);
      Report report(o->common.quiet, o->output.path);
      vm::run_job(creating_job(*o, registry), &report);
      return kOk;
    });
  });
}

} // namespace vmcli
