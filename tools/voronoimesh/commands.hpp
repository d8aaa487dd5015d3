#pragma once
/// @file commands.hpp
/// The subcommands of the voronoimesh tool and the stages they share. Each
/// subcommand runs through run_guarded(), which turns library exceptions into a
/// one-line message and the exit codes below.

#include "voronoimesh/create.hpp"
#include "voronoimesh/input.hpp"
#include "voronoimesh/node_mesh.hpp"
#include "voronoimesh/pipeline.hpp"
#include "voronoimesh/plugins.hpp"
#include "voronoimesh/scene.hpp"
#include "voronoimesh/validate.hpp" // vm::require_valid, which every command uses

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <tbb/global_control.h>
#include <vector>

namespace vmcli {

enum ExitCode : int {
  kOk = 0,
  kInvalidInput = 2, ///< bad scene, bad option value
  kIoError = 3,      ///< a file could not be read or written
  kTopology = 4,     ///< the mesh failed validation
  kInternal = 5,     ///< anything else (a bug)
  kInterrupted = 130, ///< stopped by Ctrl-C or SIGTERM (128 + SIGINT, as shells report it)
};

/// Runs `body`, printing "voronoimesh: <message>" for any exception (unless
/// not `report`) and returning the matching exit code.
int run_guarded(const std::function<int()>& body, bool report = true);

/// What INPUT (create, mesh) and --field (smooth) accept.
inline constexpr const char* kInputHelp =
    "Input: a scene (.json, docs/scenes.md); a label volume or distance grid (.nrrd, .nhdr, .nii, .nii.gz, .hdr, .mha, "
    ".mhd, .inr, .inr.gz); or a labelled point cloud (.xyz, .txt, .pts, .csv, or .ply with a vertex 'label'); see "
    "docs/inputs.md.";

/// Options every command that computes has.
struct CommonOptions {
  int threads = 0;
  bool quiet = false;
  bool ascii = false;
};
void add_common_options(CLI::App* cmd, CommonOptions& o, bool writes_mesh);
/// Fails early (IoError) if `path` cannot be written, before any long work.
void check_writable(const std::string& path);

/// Where a command writes its mesh: -o (format by extension) and --per-phase.
struct OutputOptions {
  std::string path;
  std::string per_phase; ///< directory for one closed STL per phase ("" = none)
};
/// Adds -o/--output (required) and, if `per_phase`, --per-phase DIR.
void add_output_options(CLI::App* cmd, OutputOptions& o, bool per_phase);
/// Fails early if the output format is unknown (InvalidInput) or a path cannot
/// be written (IoError), before any long work.
void check_outputs(const OutputOptions& o);
/// Writes the mesh as the options ask; says what was written unless quiet.
void write_outputs(const vm::NodeMesh& mesh, const OutputOptions& o, const CommonOptions& common);
/// Limits TBB to --threads while alive.
std::optional<tbb::global_control> thread_limit(const CommonOptions& o);

/// One status line on a terminal, overwritten stage by stage; silent otherwise.
class Progress {
public:
  explicit Progress(bool enabled);
  void stage(const std::string& what);
  void done();

private:
  bool enabled_;
};

/// Options of the create stage (create, mesh).
struct CreateOptions {
  std::vector<int> grid;
  double snap = vm::CreateParams{}.snap;
  std::string lattice = "bcc";
  int top_k = 4;
  bool skip_validation = false;
  bool close = false; ///< box faces become surfaces against an "outside" phase
};
void add_create_options(CLI::App* cmd, CreateOptions& o);
/// Samples `scene` and creates its initial mesh; prints a summary unless quiet.
vm::NodeMesh create_stage(vm::Scene scene, const CreateOptions& o, const CommonOptions& common, Progress& progress);

/// Options for inputs other than scenes (label volumes, point clouds), in their
/// own --help groups.
struct InputCliOptions {
  vm::InputOptions input;
  std::vector<std::string> merge; ///< "A+B" groups, parsed by read_input()
  bool signed_distance = false;
};
void add_input_options(CLI::App* cmd, InputCliOptions& o);
/// Reads `path` with vm::load_input (the built-in demo if empty), `top_k` phases
/// kept per voxel; unless quiet, says how long reading and the phase functions took.
vm::Scene read_input(const std::string& path, InputCliOptions o, int top_k, Progress& progress, bool quiet);

/// Adds --plugin FILE (repeatable) to `cmd`.
void add_plugin_option(CLI::App* cmd, std::vector<std::string>& files);
/// The built-in passes plus those of every plugin: `files` (--plugin; a file that
/// fails to load throws) and the plugin folders (a file that fails is named on
/// stderr with its reason, unless quiet, and skipped).
/// What happened to every plugin goes to `records` if given.
vm::PassRegistry pass_registry(const std::vector<std::string>& files, bool quiet,
                               std::vector<vm::PluginRecord>* records = nullptr);

/// Options of the improvement stage (mesh, smooth).
struct ImproveOptions {
  int iterations = 20;
  std::vector<std::string> plugins; ///< --plugin files
  std::string pipeline = vm::kDefaultPipeline;
  bool stop_when_converged = false;
  bool unguarded = false; ///< skip the crossing guard (guard.hpp)
  std::string history; ///< where to write per-iteration histograms (.csv, .json, .svg)
};
void add_improve_options(CLI::App* cmd, ImproveOptions& o, int default_iterations);
/// Checks the improvement options (pipeline against `registry`, iterations,
/// history file) before any work, so a typo fails at once rather than after a
/// long create.
void check_improve_options(const ImproveOptions& o, const vm::PassRegistry& registry);
/// Runs the pipeline (passes from `registry`) on `mesh` (validated before and
/// after); prints a progress line per iteration on a terminal and a summary
/// unless quiet.
void improve_stage(vm::NodeMesh& mesh, const vm::PhaseField* field, const ImproveOptions& o,
                   const vm::PassRegistry& registry, const CommonOptions& common, Progress& progress);

/// Everything `mesh` is told.
struct MeshCommandOptions {
  std::string input;
  OutputOptions output;
  CreateOptions create;
  InputCliOptions input_options;
  ImproveOptions improve;
  CommonOptions common;
  bool mpi = false;
};
/// `mesh --mpi` and `create --mpi` (iterations 0), under mpirun (mpi_mesh.cpp):
/// returns the exit code, the same on every rank; rank 0 prints.
int mesh_with_mpi(const MeshCommandOptions& o);

void add_create_command(CLI::App& app, int& exit_code);
void add_mesh_command(CLI::App& app, int& exit_code);
void add_smooth_commands(CLI::App& app, int& exit_code);
void add_passes_command(CLI::App& app, int& exit_code);
void add_stats_command(CLI::App& app, int& exit_code);
void add_plugins_command(CLI::App& app, int& exit_code);

} // namespace vmcli
