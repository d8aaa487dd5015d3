#pragma once
/// @file commands.hpp
/// The subcommands of the voronoimesh tool and the options they share. A
/// subcommand only translates its options into a vm::MeshJob and runs it
/// through the library's one run path (run/meshing.hpp); run_guarded() turns
/// what the library throws into a one-line message and the exit codes below.

#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/plugin/plugins.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace vmcli {

enum ExitCode : int {
  kOk = 0,
  kInvalidInput = 2,  ///< bad scene, bad option value
  kIoError = 3,       ///< a file could not be read or written
  kTopology = 4,      ///< the mesh failed validation
  kInternal = 5,      ///< anything else (a bug)
  kPlugin = 6,        ///< a plugin's pass failed or broke the plugin ABI's rules
  kInterrupted = 130, ///< stopped by Ctrl-C or SIGTERM (128 + SIGINT, as shells report it)
};

/// Runs `body`, printing "voronoimesh: <message>" for any exception (unless
/// not `report`) and returning the matching exit code. A library option
/// (vm::InvalidOption) is named as the command line names it: "--top-k".
int run_guarded(const std::function<int()>& body, bool report = true);

/// What INPUT (create, mesh) and --field (smooth) accept.
inline constexpr const char* kInputHelp =
    "Input: a scene (.json, docs/scenes.md); a label volume or distance grid (.nrrd, .nhdr, .nii, .nii.gz, .hdr, .mha, "
    ".mhd, .inr, .inr.gz, .dream3d, or a TIFF stack: .tif, .tiff); or a labelled point cloud (.xyz, .txt, .pts, .csv, or .ply with a vertex 'label'); see "
    "docs/inputs.md.";

/// Options every command that computes has.
struct CommonOptions {
  int threads = 0;
  bool quiet = false;
  bool ascii = false;
};
/// Adds --threads, -q/--quiet and, if `writes_mesh`, --ascii to `cmd`.
void add_common_options(CLI::App* cmd, CommonOptions& o, bool writes_mesh);

/// Where a command writes its mesh: -o (format by extension) and --per-phase.
struct OutputOptions {
  std::string path;
  std::string per_phase; ///< directory for one closed STL per phase ("" = none)
};
/// Adds -o/--output (required) and, if `per_phase`, --per-phase DIR to `cmd`.
void add_output_options(CLI::App* cmd, OutputOptions& o, bool per_phase);

/// Options of the create stage (create, mesh).
struct CreateOptions {
  std::vector<int> grid; ///< one number or three
  double snap = vm::MeshOptions{}.snap;
  std::string lattice = "auto";
  int top_k = vm::MeshOptions{}.top_k;
  bool skip_validation = false;
  bool close = false; ///< box faces become surfaces against an "exterior" phase
};
/// Adds --grid, --snap, --lattice, --top-k, --no-validate and --close to `cmd`.
void add_create_options(CLI::App* cmd, CreateOptions& o);

/// Options for inputs other than scenes (label volumes, point clouds), in their
/// own --help groups.
struct InputCliOptions {
  vm::InputOptions input;
  std::vector<std::string> keep, drop; ///< labels by value or segment name
  std::vector<std::string> merge;      ///< "A+B" groups
  std::string world = "file";          ///< --world
  bool signed_distance = false;
  std::vector<double> voxel_size;      ///< --voxel-size: S, or SX,SY,SZ
};
/// Adds the options of label volumes to `cmd`. Where the input is an option
/// (`--field` of stats and smooth), pass it as `input`: the label options then
/// need it, so one given without an input is refused rather than ignored.
void add_input_options(CLI::App* cmd, InputCliOptions& o, CLI::Option* input = nullptr);

/// Options of the improvement stage (mesh, smooth).
struct ImproveOptions {
  int iterations = 20;
  std::vector<std::string> plugins; ///< --plugin files
  std::string pipeline; ///< empty: the input's default (vm::pipeline_for())
  double size = 0;      ///< --size (--max-size): target edge length in world units (0: none)
  double tolerance = 0; ///< --tolerance: largest distance off a curved surface, world units (0: none)
  double min_size = 0;  ///< --min-size: shortest target edge with --tolerance (0: half of --size)
  bool stop_when_converged = false; ///< --stop-when-converged
  bool all_iterations = false;      ///< --all-iterations: never stop early, label volumes included
  bool unguarded = false; ///< skip the crossing guard (improve/guard.hpp)
  int check_crossings_every = 1; ///< MeshOptions::check_crossings_every
  std::string history;    ///< where to write per-iteration histograms (.csv, .json, .svg)
};
/// Adds --iterations (default `default_iterations`), --pipeline, --plugin,
/// --stop-when-converged, --all-iterations, --no-crossing-guard and --history to `cmd`.
void add_improve_options(CLI::App* cmd, ImproveOptions& o, int default_iterations);

/// Adds --plugin FILE (repeatable) to `cmd`.
void add_plugin_option(CLI::App* cmd, std::vector<std::string>& files);
/// The built-in passes plus those of every plugin: `files` (--plugin; a file that
/// fails to load throws) and the plugin folders (a file that fails is named on
/// stderr with its reason, unless quiet, and skipped).
/// What happened to every plugin goes to `records` if given.
vm::PassRegistry pass_registry(const std::vector<std::string>& files, bool quiet,
                               std::vector<vm::PluginRecord>* records = nullptr);

/// Everything `mesh` (and `create`, with no iterations) is told.
struct MeshCommandOptions {
  std::string input;
  std::vector<std::string> inputs; ///< as given; several (or a numbered pattern) make a sequence (sequence.hpp)
  OutputOptions output;
  CreateOptions create;
  InputCliOptions input_options;
  ImproveOptions improve;
  CommonOptions common;
  bool mpi = false;
};

/// The job the options ask for, creating a mesh from o.input; `registry` (the
/// passes the pipeline may use) must outlive the job. Throws InvalidInput for
/// options that do not parse (--grid with two numbers, a bad --merge-labels group).
vm::MeshJob creating_job(const MeshCommandOptions& o, const vm::PassRegistry& registry);
/// The parts of a job the create options set.
void set_create_options(const CreateOptions& create, vm::MeshOptions& options);
/// The parts of a job the improve options set (not the plugins: the registry does).
void set_improve_options(const ImproveOptions& improve, vm::MeshJob& job);
/// The InputOptions the label-volume options ask for.
vm::InputOptions input_options(const InputCliOptions& o);
/// The outputs -o, --per-phase and --ascii ask for.
vm::RunOutputs run_outputs(const OutputOptions& output, const CommonOptions& common);

/// `mesh --mpi` and `create --mpi` (iterations 0), under mpirun (cmd_mpi.cpp):
/// returns the exit code, the same on every rank; rank 0 prints.
int mesh_with_mpi(const MeshCommandOptions& o);

void add_create_command(CLI::App& app, int& exit_code);  ///< cmd_create.cpp
void add_mesh_command(CLI::App& app, int& exit_code);    ///< cmd_mesh.cpp
void add_smooth_command(CLI::App& app, int& exit_code);  ///< cmd_smooth.cpp (smooth, and its synonym improve)
void add_flip_command(CLI::App& app, int& exit_code);    ///< cmd_flip.cpp
void add_passes_command(CLI::App& app, int& exit_code);  ///< cmd_passes.cpp
void add_stats_command(CLI::App& app, int& exit_code);   ///< cmd_stats.cpp
void add_plugins_command(CLI::App& app, int& exit_code); ///< cmd_plugins.cpp

} // namespace vmcli
