#include "commands.hpp"

#include "voronoimesh/closed_domain.hpp"

#include "voronoimesh/errors.hpp"
#include "voronoimesh/io/ply.hpp"

#include <algorithm>
#include <memory>

namespace vmcli {
namespace {

/// Refuses a field that cannot be the one the mesh was made from: phase ids the
/// field does not have, or nodes outside its domain.
void check_field_matches(const vm::NodeMesh& mesh, const std::string& mesh_path, const vm::Scene& scene,
                         const std::string& field_path) {
  int top = -1;
  for (const auto& p : mesh.pairs) top = std::max(top, p[1]);
  if (top >= scene.field->num_phases())
    throw vm::InvalidInput(vm::located(field_path, "has " + std::to_string(scene.field->num_phases()) +
                                                       " phases, but " + mesh_path + " uses phase " + std::to_string(top)));
  const vm::Box& box = scene.grid.domain;
  const double tol = 1e-6 * (box.max - box.min).norm();
  for (const vm::Vec3& p : mesh.points)
    if (((box.min.array() - tol) > p.array()).any() || (p.array() > (box.max.array() + tol)).any())
      throw vm::InvalidInput(vm::located(field_path, "its domain does not contain the nodes of " + mesh_path));
}

} // namespace

void add_smooth_commands(CLI::App& app, int& exit_code) {
  struct Options {
    std::string mesh, field;
    OutputOptions output;
    ImproveOptions improve;
    InputCliOptions input;
    int top_k = 4;
    CommonOptions common;
  };
  auto s = std::make_shared<Options>();
  CLI::App* smooth = app.add_subcommand(
      "smooth", "Improve a mesh with a pipeline of passes (default: smooth, project, clamp, flip) and write it.");
  smooth->add_option("mesh", s->mesh, "Mesh file (.ply written by voronoimesh)")->required();
  smooth->add_option("--field", s->field, std::string("The input the mesh was made from. ") + kInputHelp);
  smooth->add_option("--top-k", s->top_k, "Phases kept per voxel of a --field volume (as given to create)")
      ->capture_default_str();
  add_input_options(smooth, s->input);
  add_output_options(smooth, s->output, true);
  add_improve_options(smooth, s->improve, 20);
  add_common_options(smooth, s->common, true);
  smooth->callback([s, &exit_code] {
    exit_code = run_guarded([&] {
      check_outputs(s->output);
      const vm::PassRegistry registry = pass_registry(s->improve.plugins, s->common.quiet);
      check_improve_options(s->improve, registry);
      auto limit = thread_limit(s->common);
      Progress progress(!s->common.quiet);
      vm::NodeMesh mesh = vm::io::read_ply(s->mesh);
      require_valid(mesh, s->mesh);
      std::optional<vm::Scene> scene;
      if (!s->field.empty()) {
        scene = read_input(s->field, s->input, s->top_k, progress, true); // quiet: a field that does not fit the mesh is reported on one line
        if (vm::is_closed_mesh(mesh, scene->field->num_phases()))
          scene->field = vm::with_outside_phase(scene->field, scene->grid.domain);
        check_field_matches(mesh, s->mesh, *scene, s->field);
      }
      improve_stage(mesh, scene ? scene->field.get() : nullptr, s->improve, registry, s->common, progress);
      write_outputs(mesh, s->output, s->common);
      return kOk;
    });
  });

  auto f = std::make_shared<Options>();
  CLI::App* flip = app.add_subcommand("flip", "Flip edges to improve triangle quality (paper Algorithm 5) and write the mesh.");
  flip->add_option("mesh", f->mesh, "Mesh file (.ply written by voronoimesh)")->required();
  add_output_options(flip, f->output, false);
  add_common_options(flip, f->common, true);
  flip->callback([f, &exit_code] {
    exit_code = run_guarded([&] {
      check_outputs(f->output);
      auto limit = thread_limit(f->common);
      Progress progress(!f->common.quiet);
      vm::NodeMesh mesh = vm::io::read_ply(f->mesh);
      require_valid(mesh, f->mesh);
      f->improve.iterations = 1;
      f->improve.pipeline = "flip:max_rounds=1000";
      improve_stage(mesh, nullptr, f->improve, vm::builtin_registry(), f->common, progress);
      write_outputs(mesh, f->output, f->common);
      return kOk;
    });
  });
}

} // namespace vmcli
