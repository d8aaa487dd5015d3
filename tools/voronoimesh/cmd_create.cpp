#include "commands.hpp"

#include "voronoimesh/create.hpp"
#include "voronoimesh/errors.hpp"
#include "voronoimesh/io/ply.hpp"
#include "voronoimesh/sampled_field.hpp"
#include "voronoimesh/scene.hpp"
#include "voronoimesh/stats.hpp"
#include "voronoimesh/validate.hpp"

#include <tbb/global_control.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

namespace vmcli {
namespace {

struct CreateOptions {
  std::string input;
  std::string output;
  std::vector<int> grid;
  double snap = vm::CreateParams{}.snap;
  std::string lattice = "bcc";
  int threads = 0;
  int top_k = 4;
  bool ascii = false;
  bool skip_validation = false;
  bool quiet = false;
};

/// Refuses, before allocating anything, a grid whose sampled field alone would
/// not fit in this machine's memory.
void refuse_if_too_big(uint64_t bytes, const vm::GridSpec& grid) {
  const uint64_t physical = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  if (bytes > physical / 10 * 8) {
    char msg[256];
    std::snprintf(msg, sizeof msg, "--grid: a %dx%dx%d grid needs about %.1f GiB, this machine has %.1f GiB",
                  grid.cells[0], grid.cells[1], grid.cells[2], double(bytes) / (1u << 30),
                  double(physical) / (1u << 30));
    throw vm::InvalidInput(msg);
  }
}

/// One status line on a terminal, overwritten stage by stage; silent otherwise.
class Progress {
public:
  explicit Progress(bool enabled) : enabled_(enabled) {}
  void stage(const std::string& what) {
    if (!enabled_) return;
    std::fprintf(stderr, "\r\033[K%s%s", what.c_str(), what.empty() ? "" : "...");
    std::fflush(stderr);
  }

private:
  bool enabled_;
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

int run_create(const CreateOptions& o) {
  std::optional<tbb::global_control> threads;
  if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));

  vm::Scene scene = o.input.empty() ? vm::demo_scene() : vm::load_scene(o.input);
  if (!o.grid.empty()) {
    if (o.grid.size() != 1 && o.grid.size() != 3)
      throw vm::InvalidInput("--grid: give one number or three (nx,ny,nz)");
    for (int a = 0; a < 3; ++a) {
      int n = o.grid[o.grid.size() == 1 ? 0 : a];
      if (n < 1 || n > 4096) throw vm::InvalidInput("--grid: must be between 1 and 4096, got " + std::to_string(n));
      scene.grid.cells[a] = n;
    }
  }
  if (o.top_k < 1 || o.top_k > 16) throw vm::InvalidInput("--top-k: must be between 1 and 16");
  vm::CreateParams params;
  params.snap = o.snap;
  params.lattice = o.lattice == "cube6" ? vm::Lattice::cube6 : vm::Lattice::bcc;
  const vm::GridSpec grid = vm::grid_for_lattice(scene.grid, params.lattice);
  refuse_if_too_big(vm::estimate_create_memory(grid, o.top_k, params.lattice), grid);

  Progress progress(!o.quiet && isatty(STDERR_FILENO));
  auto t0 = std::chrono::steady_clock::now();
  progress.stage("sampling " + std::to_string(grid.node_count()) + " grid nodes");
  vm::SampledField field = vm::SampledField::sample(*scene.field, grid, o.top_k);
  const double t_sample = seconds_since(t0);

  progress.stage("creating the mesh");
  vm::NodeMesh mesh;
  vm::CreateStats cs = vm::create_initial_mesh(field, params, mesh);
  progress.stage("");
  for (int p = 0; p < scene.field->num_phases(); ++p) mesh.phase_names.push_back(scene.field->phase_name(p));

  if (!o.skip_validation) {
    vm::ValidationReport report = vm::validate(mesh);
    if (!report.ok())
      throw vm::TopologyError("the created mesh failed validation (" + std::to_string(report.problem_count) +
                              " problems; please report this with the scene), first: " + report.problems.front());
  }
  vm::io::write_ply(mesh, o.output, o.ascii);
  if (!o.quiet) {
    std::fprintf(stderr,
                 "voronoimesh create: grid %dx%dx%d (%s), %zu vertices, %zu triangles -> %s\n"
                 "  sampling %.3f s, create %.3f s (%llu tets visited, %llu cut; check %.3f s), snapped nodes %llu,"
                 " snapping undone at %llu\n",
                 grid.cells[0], grid.cells[1], grid.cells[2], o.lattice.c_str(), mesh.num_nodes(),
                 mesh.num_triangles(), o.output.c_str(), t_sample, cs.seconds,
                 (unsigned long long)cs.tets_visited, (unsigned long long)cs.tets_cut, cs.check_seconds,
                 (unsigned long long)cs.snapped_nodes, (unsigned long long)cs.unsnapped_nodes);
  }
  return kOk;
}

} // namespace

void add_create_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CreateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "create", "Create the initial mesh of the Voronoi interface (paper Algorithm 2) and write it as PLY.");
  cmd->add_option("input", o->input,
                  "Scene file (JSON, see docs/scenes.md). Without it, the built-in demo: four overlapping spheres.");
  cmd->add_option("-o,--output", o->output, "Output mesh (.ply)")->required();
  cmd->add_option("--grid", o->grid, "Grid cells per axis, N or NX,NY,NZ (overrides the scene's \"grid\")")
      ->delimiter(',');
  cmd->add_option("--snap", o->snap, "Snapping threshold in units of the grid spacing h; 0 turns it off")
      ->capture_default_str();
  cmd->add_option("--lattice", o->lattice, "Background tetrahedra: bcc (every second grid point) or cube6")
      ->check(CLI::IsMember({"bcc", "cube6"}))
      ->capture_default_str();
  cmd->add_option("--top-k", o->top_k, "Phases kept per grid point (memory does not grow with the phase count)")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)");
  cmd->add_flag("--ascii", o->ascii, "Write ASCII PLY instead of binary");
  cmd->add_flag("--no-validate", o->skip_validation, "Skip the topological check of the result");
  cmd->add_flag("-q,--quiet", o->quiet, "Print nothing on success");
  cmd->callback([o, &exit_code] { exit_code = run_guarded([&] { return run_create(*o); }); });
}

} // namespace vmcli
