/// @file stages.cpp
/// The stages the subcommands share: options, progress, create and improve.

#include "commands.hpp"
#include "interrupt.hpp"

#include "voronoimesh/closed_domain.hpp"
#include "voronoimesh/errors.hpp"
#include "voronoimesh/history.hpp"
#include "voronoimesh/io/write_mesh.hpp"
#include "voronoimesh/mesh.hpp"
#include "voronoimesh/sampled_field.hpp"
#include "voronoimesh/validate.hpp"

#include <unistd.h>

#include <charconv>
#include <chrono>
#include <filesystem>
#include <cstdio>

namespace vmcli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

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

} // namespace

void check_writable(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw vm::IoError(vm::located(path, "cannot write: directory " + dir.string() + " does not exist"));
  if (access(dir.c_str(), W_OK) != 0)
    throw vm::IoError(vm::located(path, "cannot write: directory " + dir.string() + " is not writable"));
  if (fs::is_directory(path, ec)) throw vm::IoError(vm::located(path, "cannot write: it is a directory"));
}

void add_common_options(CLI::App* cmd, CommonOptions& o, bool writes_mesh) {
  cmd->add_option("--threads", o.threads, "Worker threads (default: all cores); results do not depend on it");
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing on success");
  if (writes_mesh)
    cmd->add_flag("--ascii", o.ascii,
                  "Write ASCII PLY and STL instead of binary (TetGen reads only ASCII STL; other formats are text)");
}

void add_output_options(CLI::App* cmd, OutputOptions& o, bool per_phase) {
  cmd->add_option("-o,--output", o.path,
                  "Output mesh; the extension picks the format: .ply, .obj (a group per phase pair), .stl (one "
                  "STL per phase pair, named <stem>_<pair>.stl, e.g. out_0-outside_1-sphere1.stl), .msh (Gmsh 4.1 "
                  "with physical surfaces, curves and points), .vtu or .vtp (ParaView), .mesh (MEDIT, for MMG and "
                  "TetGen)")
      ->required()
      ->type_name("FILE");
  if (per_phase)
    cmd->add_option("--per-phase", o.per_phase,
                    "Also write one STL per phase into DIR (made if missing), named phase_<label>[-<name>].stl: the "
                    "phase's boundary with outward normals, a closed surface for a phase inside the domain")
        ->type_name("DIR");
}

void check_outputs(const OutputOptions& o) {
  vm::io::check_output_format(o.path);
  check_writable(o.path);
  if (o.per_phase.empty()) return;
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(o.per_phase, ec) && !fs::is_directory(o.per_phase, ec))
    throw vm::IoError(vm::located(o.per_phase, "--per-phase: not a directory"));
  // An existing directory must be writable; a new one needs a writable parent.
  check_writable(fs::exists(o.per_phase, ec) ? (fs::path(o.per_phase) / "phase.stl").string() : o.per_phase);
}

void write_outputs(const vm::NodeMesh& mesh, const OutputOptions& o, const CommonOptions& common) {
  stop_if_interrupted(); // a run stopped by Ctrl-C writes nothing
  vm::io::WriteOptions options;
  options.ascii = common.ascii;
  const std::vector<std::string> files = vm::io::write_mesh(mesh, o.path, options);
  if (!common.quiet && files != std::vector<std::string>{o.path})
    std::fprintf(stderr, "output: %zu STL files, one per phase pair (%s_<pair>.stl)\n", files.size(),
                 (std::filesystem::path(o.path).parent_path() / std::filesystem::path(o.path).stem()).c_str());
  if (o.per_phase.empty()) return;
  const std::vector<std::string> phases = vm::io::write_per_phase_stl(mesh, o.per_phase, options);
  if (!common.quiet)
    std::fprintf(stderr, "per-phase: %zu STL files in %s (phase_<label>.stl)\n", phases.size(), o.per_phase.c_str());
}

std::optional<tbb::global_control> thread_limit(const CommonOptions& o) {
  if (o.threads < 0) throw vm::InvalidInput("--threads: must be positive");
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
  return limit;
}

Progress::Progress(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}

void Progress::stage(const std::string& what) {
  if (!enabled_) return;
  std::fprintf(stderr, "\r\033[K%s", what.c_str());
  std::fflush(stderr);
}

void Progress::done() { stage(""); }

void add_create_options(CLI::App* cmd, CreateOptions& o) {
  cmd->add_option("--grid", o.grid, "Grid cells per axis, N or NX,NY,NZ (overrides the scene's \"grid\")")
      ->delimiter(',');
  cmd->add_option("--snap", o.snap, "Snapping threshold in units of the grid spacing h; 0 turns it off")
      ->capture_default_str();
  cmd->add_option("--lattice", o.lattice, "Background tetrahedra: bcc (every second grid point) or cube6")
      ->check(CLI::IsMember({"bcc", "cube6"}))
      ->capture_default_str();
  cmd->add_option("--top-k", o.top_k, "Phases kept per grid point (memory does not grow with the phase count)")
      ->capture_default_str();
  cmd->add_flag("--no-validate", o.skip_validation, "Skip the topological check of the result");
  cmd->add_flag("--close", o.close,
                "Close the domain: the box faces become surfaces between each phase and an extra phase 'exterior', "
                "so every phase is a closed, watertight volume (for volume meshing)");
}

vm::NodeMesh create_stage(vm::Scene scene, const CreateOptions& o, const CommonOptions& common, Progress& progress) {
  if (!o.grid.empty()) {
    if (o.grid.size() != 1 && o.grid.size() != 3)
      throw vm::InvalidInput("--grid: give one number or three (nx,ny,nz)");
    for (int a = 0; a < 3; ++a) {
      int n = o.grid[o.grid.size() == 1 ? 0 : size_t(a)];
      if (n < 1 || n > 4096) throw vm::InvalidInput("--grid: must be between 1 and 4096, got " + std::to_string(n));
      scene.grid.cells[size_t(a)] = n;
    }
  }
  if (o.top_k < 1 || o.top_k > 16) throw vm::InvalidInput("--top-k: must be between 1 and 16");
  vm::CreateParams params;
  params.snap = o.snap;
  params.lattice = o.lattice == "cube6" ? vm::Lattice::cube6 : vm::Lattice::bcc;
  params.close = o.close;
  const vm::GridSpec grid = vm::grid_for_lattice(scene.grid, params.lattice);
  refuse_if_too_big(vm::estimate_create_memory(grid, o.top_k, params.lattice), grid);

  auto t0 = std::chrono::steady_clock::now();
  progress.stage("sampling " + std::to_string(grid.node_count()) + " grid nodes...");
  vm::SampledField field = vm::SampledField::sample(*scene.field, grid, o.top_k);
  const double t_sample = seconds_since(t0);

  progress.stage("creating the mesh...");
  vm::NodeMesh mesh;
  vm::CreateStats cs = vm::create_initial_mesh(field, params, mesh);
  vm::name_phases(mesh, *(o.close ? vm::with_outside_phase(scene.field, grid.domain) : scene.field));
  progress.done();
  if (!o.skip_validation && !cs.validated) vm::require_valid(mesh, "the created mesh");
  if (!common.quiet)
    std::fprintf(stderr,
                 "create: grid %dx%dx%d (%s), %zu vertices, %zu triangles; sampling %.3f s, create %.3f s "
                 "(%llu tets, %llu cut; check %.3f s); snapping undone at %llu nodes\n",
                 grid.cells[0], grid.cells[1], grid.cells[2], o.lattice.c_str(), mesh.num_nodes(),
                 mesh.num_triangles(), t_sample, cs.seconds, (unsigned long long)cs.tets_visited,
                 (unsigned long long)cs.tets_cut, cs.check_seconds, (unsigned long long)cs.unsnapped_nodes);
  stop_if_interrupted(); // create itself runs to its end; nothing after it does
  return mesh;
}

void add_input_options(CLI::App* cmd, InputCliOptions& o) {
  const char* labels = "Label volumes";
  cmd->add_option("--drop-labels", o.input.drop_labels, "Labels whose voxels become background, L,L,...")
      ->delimiter(',')->group(labels);
  cmd->add_option("--merge-labels", o.merge, "Label groups merged into their smallest label, A+B,C+D+E,...")
      ->delimiter(',')->group(labels);
  cmd->add_option("--background", o.input.background, "The background label (a phase named 'background')")
      ->capture_default_str()->group(labels);
  cmd->add_flag("--no-background", o.input.no_background,
                "Background voxels are no phase: the labels around them fill them, meeting halfway across gaps "
                "(grain maps with unindexed voxels); a gap wider than the smoothing radius or band is an error")
      ->group(labels);
  cmd->add_flag("--signed-distance", o.signed_distance,
                "Phase functions by exact signed distance (clamped to --band) instead of the smoothed indicator")
      ->group(labels);
  cmd->add_option("--smoothing", o.input.smoothing, "Gaussian sigma of the smoothed indicator, in voxels")
      ->capture_default_str()->group(labels);
  cmd->add_option("--band", o.input.band, "Half-width of the signed-distance band, in voxels")
      ->capture_default_str()->group(labels);
  cmd->add_option("--voxels-per-cell", o.input.voxels_per_cell,
                  "Mesh a volume on cells of about F voxels per axis (2: about a quarter of the triangles of the voxel "
                  "grid); --grid overrides it")
      ->capture_default_str()->group(labels);
  cmd->add_flag("--ignore-direction", o.input.ignore_direction,
                "Use the voxel axes as they are when the volume's direction matrix is oblique")
      ->group(labels);
}

vm::Scene read_input(const std::string& path, InputCliOptions o, int top_k, Progress& progress, bool quiet) {
  for (const std::string& group : o.merge) {
    std::vector<int32_t> labels;
    size_t start = 0;
    for (size_t plus = 0; plus != std::string::npos; start = plus + 1) {
      plus = group.find('+', start);
      const std::string part = group.substr(start, plus == std::string::npos ? std::string::npos : plus - start);
      int32_t value = 0;
      const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
      if (ec != std::errc() || end != part.data() + part.size() || part.empty())
        throw vm::InvalidInput("--merge-labels: expected groups of integer labels as A+B, got '" + group + "'");
      labels.push_back(value);
    }
    o.input.merge_labels.push_back(labels);
  }
  o.input.label_function = o.signed_distance ? vm::LabelFunction::signed_distance : vm::LabelFunction::smoothed_indicator;
  o.input.top_k = top_k;
  if (path.empty()) {
    vm::refuse_options_that_do_not_apply(o.input, false, false, "a scene", "the built-in demo");
    return vm::demo_scene();
  }
  progress.stage("reading " + path + "...");
  const auto t0 = std::chrono::steady_clock::now();
  vm::Scene scene = vm::load_input(path, o.input);
  progress.done();
  if (!quiet)
    std::fprintf(stderr, "input: %d phases, grid %dx%dx%d; read and phase functions %.3f s\n", scene.field->num_phases(),
                 scene.grid.cells[0], scene.grid.cells[1], scene.grid.cells[2], seconds_since(t0));
  return scene;
}

void add_improve_options(CLI::App* cmd, ImproveOptions& o, int default_iterations) {
  o.iterations = default_iterations;
  cmd->add_option("--iterations", o.iterations, "Iterations of the pipeline")->capture_default_str();
  cmd->add_option("--pipeline", o.pipeline,
                  "Passes per iteration, e.g. smooth,project,clamp,flip:skip_quality=0.95 (see 'voronoimesh passes')")
      ->capture_default_str();
  add_plugin_option(cmd, o.plugins);
  cmd->add_flag("--stop-when-converged", o.stop_when_converged,
                "Stop once min and mean quality stop improving (by 1e-3 for 3 iterations)");
  cmd->add_flag("--no-crossing-guard", o.unguarded,
                "Do not undo moves and flips that make two surfaces cross (faster; only safe on well-resolved scenes)");
  cmd->add_option("--history", o.history,
                  "Write per-iteration histograms of inradius, circumradius, edge length, quality, angles and vertex "
                  "degree (paper Fig. 7) to FILE: .svg (a picture), .csv or .json");
}

void check_improve_options(const ImproveOptions& o, const vm::PassRegistry& registry) {
  if (o.iterations < 0) throw vm::InvalidInput("--iterations: must be 0 or more");
  vm::Pipeline::parse(o.pipeline, registry);
  if (!o.history.empty()) {
    vm::QualityHistory::check_format(o.history);
    check_writable(o.history);
  }
}

void improve_stage(vm::NodeMesh& mesh, const vm::PhaseField* field, const ImproveOptions& o,
                   const vm::PassRegistry& registry, const CommonOptions& common, Progress& progress) {
  check_improve_options(o, registry);
  const vm::Pipeline pipeline = vm::Pipeline::parse(o.pipeline, registry);
  if (pipeline.needs_field() && !field)
    throw vm::InvalidInput("--pipeline: '" + o.pipeline + "' needs the phase functions: give --field SCENE.json");
  vm::InterfaceMesh im = vm::InterfaceMesh::from_node_mesh(mesh);
  vm::RunOptions run;
  run.iterations = o.iterations;
  run.stop_when_converged = o.stop_when_converged;
  run.guard_crossings = !o.unguarded;
  run.stop_requested = interrupted;
  double first_min = 0, first_mean = 0, total = 0;
  vm::QualityHistory history;
  run.observer = [&](const vm::IterationReport& r, const vm::InterfaceMesh& current) {
    if (r.iteration == 0) first_min = r.min_quality, first_mean = r.mean_quality;
    if (!o.history.empty()) history.record(r.iteration, current.to_node_mesh());
    total += r.seconds;
    char line[192];
    std::snprintf(line, sizeof line, "iteration %d/%d: min q %.3f, mean q %.3f, %zu flips, %zu moves undone, %.1f ms",
                  r.iteration, o.iterations, r.min_quality, r.mean_quality, r.flips, r.undone_moves, r.seconds * 1e3);
    progress.stage(line);
  };
  const int done = pipeline.run(im, field, run);
  progress.done();
  stop_if_interrupted();
  mesh = im.to_node_mesh();
  vm::require_valid(mesh, "the improved mesh");
  if (!o.history.empty()) history.write(o.history);
  if (!common.quiet) {
    const auto [min_q, mean_q] = vm::quality_summary(im);
    std::fprintf(stderr, "improve: %d iterations of %s in %.3f s; min q %.3f -> %.3f, mean q %.3f -> %.3f\n", done,
                 o.pipeline.c_str(), total, first_min, min_q, first_mean, mean_q);
  }
}

} // namespace vmcli
