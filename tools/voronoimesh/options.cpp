/// @file options.cpp
/// The options the subcommands share, and their translation into a vm::MeshJob.

#include "commands.hpp"

#include "voronoimesh/core/errors.hpp"

#include <charconv>

namespace vmcli {

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

void add_create_options(CLI::App* cmd, CreateOptions& o) {
  cmd->add_option("--grid", o.grid, "Grid cells per axis, N or NX,NY,NZ (overrides the scene's \"grid\")")
      ->delimiter(',');
  cmd->add_option("--snap", o.snap,
                  "Snapping threshold in units of the grid spacing h: two phases' values closer than this at a "
                  "lattice node are made equal (paper: 0.2; a pair whose difference grows slower than 0.2 per unit "
                  "length snaps proportionally less, so no snap moves an interface more than a cell); 0 turns it off. "
                  "With --voxel-faithful it also decides which voxel centres the bcc lattice can hold (--lattice auto)")
      ->capture_default_str();
  cmd->add_option("--lattice", o.lattice,
                  "Background tetrahedra: bcc (every second grid point), cube6 (every grid point) or auto (bcc, but "
                  "with --voxel-faithful cube6 for a label volume with structures one voxel thin where bcc has no "
                  "grid point)")
      ->check(CLI::IsMember({"auto", "bcc", "cube6"}))
      ->capture_default_str();
  cmd->add_option("--top-k", o.top_k, "Phases kept per grid point (memory does not grow with the phase count)")
      ->capture_default_str();
  cmd->add_flag("--no-validate", o.skip_validation, "Skip the topological checks of the created and improved mesh");
  cmd->add_flag("--close", o.close,
                "Close the domain: the box faces become surfaces between each phase and an extra phase 'exterior', "
                "so every phase is a closed, watertight volume (for volume meshing)");
}

void add_input_options(CLI::App* cmd, InputCliOptions& o, CLI::Option* input) {
  const char* labels = "Label volumes";
  cmd->add_option("--keep-labels", o.keep,
                  "Only these labels (and the background) become phases, L,L,...: every other label's voxels become "
                  "background. A label is its value or, in a 3D Slicer segmentation, its segment's name")
      ->delimiter(',')->group(labels);
  cmd->add_option("--drop-labels", o.drop, "Labels (values or segment names) whose voxels become background, L,L,...")
      ->delimiter(',')->group(labels);
  cmd->add_option("--merge-labels", o.merge,
                  "Label groups (values or segment names) merged into their smallest label, A+B,C+D+E,...")
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
  cmd->add_flag("--voxel-faithful", o.input.voxel_faithful,
                "Keep labels one or two voxels thin: each voxel's label leads at its centre, and --lattice auto takes "
                "cube6 where bcc would lose more than 1% of a label; the grid is then the voxel grid unless "
                "--voxels-per-cell says otherwise. Off by default: on CGAL's liver (whose 2-voxel label 84 then needs "
                "cube6) it takes the voxel centres in their label from 99.870% to 99.976%, but about 5x the time, "
                "min q from 0.695 to 0.165 and folds along the rims of its one-voxel structures")
      ->group(labels);
  cmd->add_option("--band", o.input.band, "Half-width of the signed-distance band, in voxels")
      ->capture_default_str()->group(labels);
  cmd->add_option("--voxels-per-cell", o.input.voxels_per_cell,
                  "Mesh a volume on cells of about F voxels (of the smallest spacing) per axis (2: about a quarter of "
                  "the triangles of the voxel grid, in about half the time, but structures thinner than a cell merge "
                  "into their neighbours; 1: the voxel grid); --grid overrides it. Default: the voxel grid, "
                  "but for flat voxels (slices over 1.2 times thicker than their pixels) cubic cells of the voxels' "
                  "volume, as many as the voxels (bcc tetrahedra on flat cells cut the surfaces into slivers); with "
                  "--voxel-faithful the voxel grid")
      ->group(labels);
  cmd->add_option("--voxel-size", o.voxel_size,
                  "The voxel size of a volume, S or SX,SY,SZ along the file's axes, instead of the file's: for a file "
                  "that says none (a TIFF not written by ImageJ, a NRRD without spacings; the output says so) or a "
                  "wrong one")
      ->delimiter(',')
      ->group(labels);
  cmd->add_flag("--ignore-direction", o.input.ignore_direction,
                "Use the voxel axes as they are when the volume's direction matrix is oblique")
      ->group(labels);
  cmd->add_option("--world", o.world,
                  "Coordinates of a volume's mesh: 'file' (the file's own: RAS for NIfTI, LPS for MetaImage, NRRD's "
                  "'space'), 'lps' or 'ras' (converted from the frame the file states), so one segmentation saved as "
                  "NIfTI and as NRRD gives one mesh")
      ->check(CLI::IsMember({"file", "lps", "ras"}))
      ->capture_default_str()
      ->group(labels);
  if (input)
    for (CLI::Option* option : cmd->get_options([labels](const CLI::Option* o) { return o->get_group() == labels; }))
      option->needs(input);
}

void add_improve_options(CLI::App* cmd, ImproveOptions& o, int default_iterations) {
  o.iterations = default_iterations;
  cmd->add_option("--iterations", o.iterations,
                  "Iterations of the pipeline; the most where the run stops once quality converges (by default a "
                  "label volume meshed with its default pipeline; see --stop-when-converged, --all-iterations)")
      ->capture_default_str();
  cmd->add_option("--pipeline", o.pipeline,
                  std::string("Passes per iteration, e.g. smooth,project,clamp,flip:skip_quality=0.95 (see 'voronoimesh "
                              "passes'). Default: ") +
                      vm::kScenePipeline +
                      " (the remesh pass evens out the created mesh at its own edge length before the paper's "
                      "passes, which then collapse junction slivers below q 0.5; polish and floor, not in the "
                      "paper, raise the worst triangles and take back moves onto the interface that left the worst "
                      "one worse than the iteration found it); "
                      "for label volumes " +
                      vm::kLabelVolumePipeline +
                      " (their voxel grid is finer than their surfaces need: the remesh pass coarsens the mesh to "
                      "edges 1.4x the lattice's, about half the triangles); for a mesh read from a file and under "
                      "--mpi the paper's " + vm::kDefaultPipeline);
  cmd->add_option("--size,--max-size", o.size,
                  std::string("Target edge length in world units (the input's units): remesh to edges of about L "
                              "first, for any input (remesh:length=L,") +
                      vm::kPassesAfterRemesh + "); not with --pipeline (put remesh:length=L in it). With "
                                               "--tolerance, the longest edge, where surfaces are flat");
  cmd->add_option("--tolerance", o.tolerance,
                  "With --size: how far, in world units, a triangle may stand off a curved surface (like CGAL's facet "
                  "distance); edges shorten where surfaces curve, down to --min-size (remesh:tolerance)");
  cmd->add_option("--min-size", o.min_size,
                  "With --tolerance: the shortest target edge in world units, between a tenth of --size and --size "
                  "(default: half of --size)");
  add_plugin_option(cmd, o.plugins);
  auto* converged = cmd->add_flag(
      "--stop-when-converged", o.stop_when_converged,
      "Stop once quality stops improving (min q by 1e-3 and mean q by 2e-3 for 2 iterations, counted once the "
      "passes' schedules settled: from iteration 6 in the default pipelines, after the remesh calls, the flip "
      "pass's early collapses and the polish pass's start), after one more iteration run as the last; "
      "--iterations is then the most. The default for label volumes meshed with their default pipeline");
  cmd->add_flag("--all-iterations", o.all_iterations,
                "Run every one of --iterations, label volumes included (they stop when converged by default)")
      ->excludes(converged);
  auto* unguarded = cmd->add_flag(
      "--no-crossing-guard", o.unguarded,
      "Do not undo moves and flips that make two surfaces cross (faster; only safe on well-resolved scenes)");
  cmd->add_option("--check-crossings-every", o.check_crossings_every,
                  "Look for crossing surfaces once every N iterations, in the whole mesh, instead of after every move "
                  "and flip; where one is found, those iterations run again from where they began, each checked. "
                  "The output is checked either way. Faster where surfaces rarely come to cross (1M triangles of 30 "
                  "Voronoi cells, 20 iterations: a quarter faster at 5, a third at 10), not on label volumes, where crossings "
                  "keep coming (the liver is slower); the mesh is the same as with 1 "
                  "where the guard finds nothing, and may differ where a crossing came and went in between. With "
                  "--history or --mpi every iteration is checked")
      ->default_val(1)
      ->excludes(unguarded);
  cmd->add_option("--history", o.history,
                  "Write per-iteration histograms of inradius, circumradius, edge length, quality, angles and vertex "
                  "degree (paper Fig. 7) to FILE: .svg (a picture), .csv or .json");
}

namespace {

/// A label as the command line gives it: a whole integer is a value, anything
/// else a segment's name.
vm::LabelRef label_ref(const std::string& text) {
  int32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc() && end == text.data() + text.size() && !text.empty()) return value;
  return text;
}

} // namespace

vm::InputOptions input_options(const InputCliOptions& o) {
  vm::InputOptions input = o.input;
  for (const std::string& l : o.keep) input.keep_labels.push_back(label_ref(l));
  for (const std::string& l : o.drop) input.drop_labels.push_back(label_ref(l));
  for (const std::string& group : o.merge) {
    std::vector<vm::LabelRef> labels;
    size_t start = 0;
    for (size_t plus = 0; plus != std::string::npos; start = plus + 1) {
      plus = group.find('+', start);
      const std::string part = group.substr(start, plus == std::string::npos ? std::string::npos : plus - start);
      if (part.empty())
        throw vm::InvalidInput("--merge-labels: expected groups of labels (values or segment names) as A+B, got '" +
                               group + "'");
      labels.push_back(label_ref(part));
    }
    input.merge_labels.push_back(labels);
  }
  input.world = o.world == "lps" ? vm::World::lps : o.world == "ras" ? vm::World::ras : vm::World::file;
  if (o.voxel_size.size() == 1) input.voxel_size = vm::Vec3::Constant(o.voxel_size[0]);
  else if (o.voxel_size.size() == 3) input.voxel_size = vm::Vec3(o.voxel_size[0], o.voxel_size[1], o.voxel_size[2]);
  else if (!o.voxel_size.empty())
    throw vm::InvalidInput("--voxel-size: one size (S) or three (SX,SY,SZ), got " +
                           std::to_string(o.voxel_size.size()));
  input.label_function = o.signed_distance ? vm::LabelFunction::signed_distance : vm::LabelFunction::smoothed_indicator;
  return input;
}

void set_create_options(const CreateOptions& create, vm::MeshOptions& options) {
  if (!create.grid.empty()) {
    if (create.grid.size() != 1 && create.grid.size() != 3)
      throw vm::InvalidInput("--grid: give one number or three (nx,ny,nz)");
    options.grid.emplace();
    for (size_t a = 0; a < 3; ++a) (*options.grid)[a] = create.grid[create.grid.size() == 1 ? 0 : a];
  }
  options.snap = create.snap;
  if (create.lattice != "auto") options.lattice = create.lattice == "cube6" ? vm::Lattice::cube6 : vm::Lattice::bcc;
  options.top_k = create.top_k;
  options.close = create.close;
  options.validate = !create.skip_validation;
}

void set_improve_options(const ImproveOptions& improve, vm::MeshJob& job) {
  job.options.iterations = improve.iterations;
  job.options.pipeline = improve.pipeline;
  job.options.size = improve.size;
  job.options.tolerance = improve.tolerance;
  job.options.min_size = improve.min_size;
  // Neither flag: the input's default (vm::options_for_scene()).
  if (improve.stop_when_converged || improve.all_iterations)
    job.options.stop_when_converged = improve.stop_when_converged;
  job.options.guard_crossings = !improve.unguarded;
  job.options.check_crossings_every = improve.check_crossings_every;
  job.outputs.history = improve.history;
}

vm::RunOutputs run_outputs(const OutputOptions& output, const CommonOptions& common) {
  vm::RunOutputs outputs;
  outputs.mesh = output.path;
  outputs.per_phase = output.per_phase;
  outputs.ascii = common.ascii;
  return outputs;
}

vm::MeshJob creating_job(const MeshCommandOptions& o, const vm::PassRegistry& registry) {
  vm::MeshJob job;
  job.input = o.input;
  job.input_options = input_options(o.input_options);
  set_create_options(o.create, job.options);
  job.outputs = run_outputs(o.output, o.common);
  set_improve_options(o.improve, job);
  job.options.passes = &registry;
  job.options.threads = o.common.threads;
  return job;
}

} // namespace vmcli
