/// @file run/meshing.cpp
/// The run path: read, create, improve, write (run/meshing.hpp).

#include "voronoimesh/run/meshing.hpp"

#include "core/clock.hpp"
#include "core/memory.hpp"
#include "core/staged_outputs.hpp"
#include "core/text.hpp"
#include "fields/voxel_grid.hpp"
#include "improve/node_merge.hpp"
#include "run/run_job.hpp"
#include "voronoimesh/check/history.hpp"
#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/io/ply.hpp"
#include "io/writers.hpp"
#include "voronoimesh/io/write_mesh.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cstdio>

namespace vm {

void RunObserver::stage(Stage, const std::string&) {}
void RunObserver::input_read(const std::string&, const Scene&, double) {}
void RunObserver::created(const CreateReport&) {}
void RunObserver::iteration(const IterationReport&, const InterfaceMesh&) {}
void RunObserver::improved(const ImproveReport&) {}
void RunObserver::written(const std::vector<std::string>&, const std::vector<std::string>&) {}
void RunObserver::note(const std::string&) {}
bool RunObserver::stop_requested() { return false; }

namespace {

using detail::cat;

void require_field(const Scene& scene) {
  if (!scene.field) throw InvalidInput("scene: no phase field");
}

void begin(RunObserver* observer, Stage stage, const std::string& what) {
  if (observer) observer->stage(stage, what);
}

/// Throws Cancelled if the observer asks to stop.
void stop_if_asked(RunObserver* observer) {
  if (observer && observer->stop_requested()) throw Cancelled();
}

/// One flag per phase id below `phases`: some triangle of `mesh` bounds it.
std::vector<uint8_t> bounded_phases(const NodeMesh& mesh, size_t phases) {
  std::vector<uint8_t> bounded(phases, 0);
  for (const PhasePair& p : mesh.pairs)
    for (int32_t phase : p)
      if (size_t(phase) < bounded.size()) bounded[size_t(phase)] = 1;
  return bounded;
}

/// The phases of `scene` that no triangle of `mesh` bounds.
std::vector<int32_t> lost_phases(const NodeMesh& mesh, const Scene& scene) {
  const std::vector<uint8_t> bounded = bounded_phases(mesh, size_t(scene.field->num_phases()));
  std::vector<int32_t> lost;
  for (size_t p = 0; p < bounded.size(); ++p)
    if (!bounded[p]) lost.push_back(int32_t(p));
  return lost;
}

/// "label L", and " ('name')" after it when the phase's name says more than
/// its label does.
std::string labelled(int32_t label, const std::string& name) {
  if (name.empty() || name == cat("label", label)) return cat("label ", label);
  return cat("label ", label, " (", detail::quote(name), ")");
}

/// One line naming a lost phase, with its size for a label volume.
std::string lost_phase_line(const Scene& scene, int32_t p) {
  const PhaseField& f = *scene.field;
  if (size_t(p) < scene.phase_voxels.size()) {
    const int64_t voxels = scene.phase_voxels[size_t(p)];
    // Smoothing can outweigh a thin region at its own voxel centres; where it
    // still leads there, by less than the snapping threshold, snapping removes it.
    // --voxel-faithful makes it lead there; a voxel the bcc lattice has no node
    // at, between two of another label, needs cube6 as well.
    const int32_t around = size_t(p) < scene.phase_around.size() ? scene.phase_around[size_t(p)] : -1;
    const std::string merged = around < 0 ? std::string() : cat(", merged into label ", f.phase_label(around));
    return cat(labelled(f.phase_label(p), f.phase_name(p)), ": ", voxels, voxels == 1 ? " voxel" : " voxels",
               ", no surface in the mesh", merged,
               ": thinner than the grid resolves (--voxel-faithful, with --lattice cube6 "
               "if need be, or --smoothing 0.5, --snap 0.1, --signed-distance may keep it)");
  }
  return cat("phase ", detail::quote(f.phase_name(p)),
             ": no surface in the mesh: smaller or thinner than the grid resolves (a finer --grid may keep it)");
}

/// Drops the vertices of `mesh` that no triangle uses (another tool's edits can
/// leave them; they hold no surface and fail validation), numbering the others
/// in order, with a note naming `what` holds them.
void drop_vertices_of_no_triangle(NodeMesh& mesh, const std::string& what, RunObserver* observer) {
  if (mesh.triangles.empty()) return; // nothing to mesh: the caller says so
  const size_t vertices = mesh.points.size();
  std::vector<int32_t> kept;
  detail::drop_unused_nodes(mesh, kept);
  if (observer && mesh.points.size() < vertices)
    observer->note(cat(what, ": ", vertices - mesh.points.size(), " of its ", vertices,
                       " vertices belong to no triangle: dropped, the others numbered in order"));
}

/// improve_mesh(), recording every iteration in `history` if given.
int improve(NodeMesh& mesh, std::shared_ptr<const PhaseField> field, const MeshOptions& o, RunObserver* observer,
            QualityHistory* history) {
  detail::check_options(o);
  drop_vertices_of_no_triangle(mesh, "the mesh", observer);
  const auto limit = detail::thread_limit(o);
  const Pipeline pipeline = detail::parse_pipeline(o);
  // A closed mesh has one more phase, outside the box; the passes need its function too.
  const auto phases = field ? phases_of_mesh(mesh, std::move(field)) : nullptr;
  if (pipeline.needs_field() && !phases)
    throw InvalidOption("pipeline", "'" + pipeline_for(o, nullptr) + "' needs the phase functions, and the mesh has none");
  begin(observer, Stage::improve, "improving...");
  InterfaceMesh im = InterfaceMesh::from_node_mesh(mesh);
  RunOptions run;
  run.iterations = o.iterations;
  run.stop_when_converged = o.stop_when_converged.value_or(false);
  run.guard_crossings = o.guard_crossings;
  run.check_crossings_every = history ? 1 : o.check_crossings_every;
  if (observer) run.stop_requested = [observer] { return observer->stop_requested(); };
  ImproveReport report;
  report.pipeline = pipeline_for(o, nullptr);
  run.observer = [&](const IterationReport& r, const InterfaceMesh& current) {
    if (r.iteration == 0) report.initial_min_quality = r.min_quality, report.initial_mean_quality = r.mean_quality;
    report.min_quality = r.min_quality;
    report.mean_quality = r.mean_quality;
    report.seconds += r.seconds;
    if (history) history->record(r.iteration, current.to_node_mesh());
    if (observer) observer->iteration(r, current);
  };
  int32_t top_phase = -1;
  for (const PhasePair& p : mesh.pairs) top_phase = std::max({top_phase, p[0], p[1]});
  const auto phase_count = size_t(top_phase + 1);
  const std::vector<uint8_t> bounded_before = bounded_phases(mesh, phase_count);
  report.iterations = pipeline.run(im, phases.get(), run);
  stop_if_asked(observer);
  report.converged = report.iterations < o.iterations;
  mesh = im.to_node_mesh();
  if (o.validate) require_valid(mesh, "the improved mesh");
  // Collapses can take a phase's last triangles: never silently.
  const std::vector<uint8_t> bounded_after = bounded_phases(mesh, phase_count);
  for (size_t p = 0; p < phase_count; ++p)
    if (bounded_before[p] && !bounded_after[p] && observer)
      observer->note(cat(labelled(mesh.label_of(int32_t(p)), p < mesh.phase_names.size() ? mesh.phase_names[p] : ""),
                         ": no surface left after improvement (collapses took its last triangles; a finer grid, or "
                         "a --pipeline without remesh, may keep it)"));
  if (observer) observer->improved(report);
  return report.iterations;
}

/// Writes the outputs among `staged`, the history too if given, and renames them
/// all into place unless the observer asks to stop meanwhile (then none is).
void write_staged(detail::StagedOutputs& staged, const NodeMesh& mesh, const RunOutputs& outputs,
                  const QualityHistory* history, RunObserver* observer) {
  stop_if_asked(observer); // a run stopped before the end writes nothing
  begin(observer, Stage::write, "writing...");
  io::WriteOptions options;
  options.ascii = outputs.ascii;
  std::vector<std::string> mesh_files, phase_files;
  if (!outputs.mesh.empty()) mesh_files = io::detail::write_mesh(staged, mesh, outputs.mesh, options);
  if (!outputs.per_phase.empty())
    phase_files = io::detail::write_per_phase_stl(staged, mesh, outputs.per_phase, options);
  if (history) {
    const std::string text = history->text_for(outputs.history);
    staged.write(outputs.history, [&](std::ostream& f) { f << text; });
  }
  stop_if_asked(observer); // stopped while writing: the temporaries go, nothing appears
  staged.commit();
  if (observer) observer->written(mesh_files, phase_files);
}

/// The mesh at `path` (a PLY written by voronoimesh), which must be valid: an
/// input's fault, not the library's, when it is not; but vertices no triangle
/// uses are dropped with a note, not refused.
NodeMesh read_mesh(const std::string& path, RunObserver* observer) {
  begin(observer, Stage::read, "reading " + path + "...");
  NodeMesh mesh = io::read_ply(path);
  drop_vertices_of_no_triangle(mesh, path, observer);
  const ValidationReport report = validate(mesh);
  if (!report.ok())
    throw InvalidInput(located(path, cat("not a valid interface mesh (", report.problem_count,
                                         " problems), first: ", report.problems.front())));
  return mesh;
}

/// Refuses a mesh read from `path` whose triangles cross: the crossing guard
/// undoes any edit that would make a crossing, it cannot take one away, so
/// improving such a mesh would hand back one that still crosses as if it were
/// sound (`flip` on a mesh with a node dragged through a surface did, with exit 0).
void refuse_crossing_input(const NodeMesh& mesh, const std::string& path) {
  const IntersectionReport crossings = find_self_intersections(mesh, 1);
  if (crossings.ok()) return;
  const auto [t, s] = crossings.pairs.front();
  throw InvalidInput(located(path, cat(crossings.count, crossings.count == 1 ? " pair" : " pairs",
                                       " of triangles cross (the first: triangles ", t, " and ", s,
                                       "): improvement keeps a mesh free of crossings but cannot untangle one "
                                       "(`smooth --no-crossing-guard` improves it anyway, without that guarantee)")));
}

} // namespace

void check_field_matches(const NodeMesh& mesh, const std::string& mesh_path, const Scene& scene,
                         const std::string& input) {
  const auto field = phases_of_mesh(mesh, scene.field);
  const int phases = field->num_phases();
  int top = -1;
  for (const auto& p : mesh.pairs) top = std::max(top, p[1]);
  if (top >= phases)
    throw InvalidInput(located(input, cat("has ", scene.field->num_phases(), " phases, but ", mesh_path,
                                          " uses phase ", top)));
  for (int p = 0; p < std::min(phases, int(mesh.phase_names.size())); ++p)
    if (!mesh.phase_names[size_t(p)].empty() && mesh.phase_names[size_t(p)] != field->phase_name(p))
      throw InvalidInput(located(input, cat("its phase ", p, " is ", detail::quote(field->phase_name(p)), ", but ",
                                            mesh_path, " calls phase ", p, " ",
                                            detail::quote(mesh.phase_names[size_t(p)]),
                                            ": give the input the mesh was made from")));
  for (int p = 0; p <= top; ++p) {
    const int32_t label = mesh.label_of(p);
    if (label != field->phase_label(p))
      throw InvalidInput(located(input, cat("its phase ", p, " has the label ", field->phase_label(p), ", but ",
                                            mesh_path, " gives it ", label, ": give the input the mesh was made from")));
  }
  const Box& box = scene.grid.domain;
  const double tol = 1e-6 * (box.max - box.min).norm();
  const std::string same_options = ": give the input the mesh was made from, read with the same options "
                                   "(--voxel-size, --world)";
  for (const Vec3& p : mesh.points)
    if (((box.min.array() - tol) > p.array()).any() || (p.array() > (box.max.array() + tol)).any())
      throw InvalidInput(located(input, "its domain does not contain the nodes of " + mesh_path + same_options));
  // A closed mesh's box is the domain it was meshed in: the input read another
  // way (another --voxel-size) would measure the mesh against another box.
  const auto corners = [](const Box& b) {
    return cat("(", b.min.x(), ", ", b.min.y(), ", ", b.min.z(), ") to (", b.max.x(), ", ", b.max.y(), ", ",
               b.max.z(), ")");
  };
  const bool same_box = (mesh.domain.min - box.min).cwiseAbs().maxCoeff() <= tol &&
                        (mesh.domain.max - box.max).cwiseAbs().maxCoeff() <= tol;
  if (mesh.outside_phase >= 0 && !same_box)
    throw InvalidInput(located(input, cat("its domain ", corners(box), " is not the box of the closed mesh ", mesh_path,
                                          ", ", corners(mesh.domain), same_options)));
}

MeshOffsets offsets_from_input(const NodeMesh& mesh, const std::string& mesh_path, const Scene& scene,
                               const std::string& input) {
  check_field_matches(mesh, mesh_path, scene, input);
  const bool own = mesh.grid_spacing > 0;
  return {interface_offsets(mesh, *phases_of_mesh(mesh, scene.field)), own ? mesh.grid_spacing : scene.grid.h(), own};
}

std::string voxel_centres_not_located(const NodeMesh& mesh, const Scene& scene) {
  if (scene.phase_voxels.empty() || mesh.outside_phase >= 0) return {};
  return "voxel centres not located: the mesh is not closed (mesh it with --close; in Python, close=True)";
}

std::optional<LabelAgreement> label_agreement_from_input(const NodeMesh& mesh, const Scene& scene,
                                                         const std::string& input, const InputOptions& options) {
  if (scene.phase_voxels.empty() || mesh.outside_phase < 0) return std::nullopt;
  const io::Volume v = read_placed_volume(input, options);
  return label_agreement(mesh, {v.origin, v.spacing, v.size}, v.labels);
}

Scene read_input(const std::string& path, const InputOptions& options, RunObserver* observer) {
  if (path.empty()) {
    refuse_options_that_do_not_apply(options, false, false, "a scene", "the built-in demo");
    return demo_scene();
  }
  begin(observer, Stage::read, "reading " + path + "...");
  const auto start = std::chrono::steady_clock::now();
  Scene scene = load_input(path, options);
  if (observer) observer->input_read(path, scene, detail::seconds_since(start));
  for (const std::string& line : scene.notes)
    if (observer) observer->note(line);
  return scene;
}

GridSpec create_grid(const Scene& scene, const MeshOptions& o) {
  require_field(scene);
  detail::check_options(o);
  if (o.close) outside_phase_label(*scene.field); // refused before any sampling
  GridSpec grid = scene.grid;
  if (o.grid) grid.cells = *o.grid;
  grid = grid_for_lattice(grid, lattice_for(o, scene));
  detail::require_resolvable(grid, "the grid"); // whatever the input: a scene's domain, --grid
  return grid;
}

Lattice lattice_for(const MeshOptions& o, const Scene& scene) {
  if (o.lattice) return *o.lattice;
  return scene.needs_every_grid_node && !o.grid ? Lattice::cube6 : Lattice::bcc;
}

CreateParams create_params(const Scene& scene, const MeshOptions& o) {
  CreateParams params;
  params.lattice = lattice_for(o, scene);
  params.snap = o.snap;
  params.close = o.close;
  return params;
}

NodeMesh create_mesh(const Scene& scene, const MeshOptions& o, RunObserver* observer) {
  const GridSpec grid = create_grid(scene, o);
  const auto limit = detail::thread_limit(o);
  const CreateParams params = create_params(scene, o);
  const std::string too_big =
      detail::beyond_memory(double(estimate_create_memory(grid, params.lattice)),
                            cat("a ", grid.cells[0], "x", grid.cells[1], "x", grid.cells[2], " grid"));
  if (!too_big.empty()) throw InvalidOption("grid", too_big);

  CreateReport report;
  report.grid = grid;
  report.lattice = params.lattice;
  // The bcc lattice reads a quarter of the grid's nodes: only those are sampled.
  const SampledNodes sampled = params.lattice == Lattice::bcc ? SampledNodes::bcc : SampledNodes::all;
  begin(observer, Stage::sample, cat("sampling ", SampledField::count_nodes(grid, sampled), " grid nodes..."));
  NodeMesh mesh;
  report.stats = create_initial_mesh(*scene.field, grid, o.top_k, params, mesh,
                                     [&] { begin(observer, Stage::create, "creating the mesh..."); });
  report.sampling_seconds = report.stats.sampling_seconds;
  name_phases(mesh, *phases_of_mesh(mesh, scene.field));
  if (o.validate && !report.stats.validated) require_valid(mesh, "the created mesh");
  report.nodes = mesh.num_nodes();
  report.triangles = mesh.num_triangles();
  report.lost_phases = lost_phases(mesh, scene);
  if (observer) observer->created(report);
  for (int32_t p : report.lost_phases)
    if (observer) observer->note(lost_phase_line(scene, p));
  stop_if_asked(observer); // create itself runs to its end; nothing after it does
  return mesh;
}

int improve_mesh(NodeMesh& mesh, std::shared_ptr<const PhaseField> field, const MeshOptions& o,
                 RunObserver* observer) {
  return improve(mesh, std::move(field), o, observer, nullptr);
}

std::string pipeline_for(const MeshOptions& options, const Scene* scene) {
  if (!options.pipeline.empty()) return options.pipeline;
  if (options.size > 0) {
    auto text = [](double x) { // the shortest text that reads back as the same double
      std::array<char, 32> digits{};
      return std::string(digits.data(), std::to_chars(digits.data(), digits.data() + digits.size(), x).ptr);
    };
    std::string remesh = "remesh:length=" + text(options.size);
    // The pass takes its tolerance and shortest edge as multiples of the length.
    if (options.tolerance > 0) remesh += ":tolerance=" + text(options.tolerance / options.size);
    if (options.min_size > 0) remesh += ":min_size=" + text(options.min_size / options.size);
    return remesh + "," + kPassesAfterRemesh;
  }
  if (!scene) return kDefaultPipeline;
  return scene->voxel_grid ? kLabelVolumePipeline : kScenePipeline;
}

namespace detail {

bool stops_when_converged(const MeshOptions& options, const Scene& scene) {
  return options.stop_when_converged.value_or(options.pipeline.empty() && options.size == 0 && scene.voxel_grid);
}

} // namespace detail

MeshOptions options_for_scene(MeshOptions options, const Scene& scene) {
  options.stop_when_converged = detail::stops_when_converged(options, scene);
  options.pipeline = pipeline_for(options, &scene);
  options.size = options.tolerance = options.min_size = 0;
  return options;
}

NodeMesh mesh_scene(const Scene& scene, const MeshOptions& options, RunObserver* observer) {
  NodeMesh mesh = create_mesh(scene, options, observer);
  improve_mesh(mesh, scene.field, options_for_scene(options, scene), observer);
  return mesh;
}

void write_outputs(const NodeMesh& mesh, const RunOutputs& outputs, RunObserver* observer) {
  detail::StagedOutputs staged;
  write_staged(staged, mesh, outputs, nullptr, observer);
}

NodeMesh run_job(const MeshJob& job, RunObserver* observer) {
  check_job(job);
  const auto limit = detail::thread_limit(job.options);
  const InputOptions input = detail::input_options_for(job.input_options, job.options);
  NodeMesh mesh;
  std::shared_ptr<const PhaseField> field;
  MeshJob resolved = job;
  if (job.mesh.empty()) {
    const Scene scene = read_input(job.input, input, observer);
    mesh = create_mesh(scene, job.options, observer);
    if (mesh.num_triangles() == 0)
      throw InvalidInput(located(job.input.empty() ? "the built-in demo" : job.input,
                                 "meshes to nothing: no two phases meet between the grid's nodes (a finer grid, or "
                                 "less smoothing of labels, may resolve them)"));
    field = scene.field;
    resolved.options = options_for_scene(job.options, scene);
  } else {
    mesh = read_mesh(job.mesh, observer);
    if (job.options.guard_crossings) refuse_crossing_input(mesh, job.mesh);
    if (!job.input.empty()) {
      const Scene scene = read_input(job.input, input, observer);
      check_field_matches(mesh, job.mesh, scene, job.input);
      field = scene.field;
    }
  }
  detail::finish_job(mesh, field, resolved, observer);
  return mesh;
}

namespace detail {

std::string sliver_note(const NodeMesh& mesh) {
  constexpr double kSliver = MeshStats::kSliverQuality;
  size_t slivers = 0;
  for (const auto& t : mesh.triangles)
    slivers += triangle_quality(mesh.points[size_t(t[0])], mesh.points[size_t(t[1])], mesh.points[size_t(t[2])]) < kSliver;
  const std::vector<WorstTriangle> worst = worst_triangles(mesh, slivers);
  if (worst.empty()) return {};
  const auto at_corners =
      std::count_if(worst.begin(), worst.end(), [](const WorstTriangle& w) { return w.corner_node >= 0; });
  char worst_q[32];
  std::snprintf(worst_q, sizeof worst_q, "%.2g", worst.front().quality);
  const std::string corners =
      at_corners == 0 ? std::string("none fills its surface's whole corner at a junction point")
                      : cat(at_corners, " of them fill their surface's whole corner at a junction point: while "
                                        "the point and its curves stay where they are, no remeshing does better");
  return cat(slivers, slivers == 1 ? " triangle is a sliver" : " triangles are slivers", " (q below ", kSliver,
             ", the worst ", worst_q, "); ", corners, "; `voronoimesh stats --worst ", slivers, "` lists them");
}

void finish_job(NodeMesh& mesh, std::shared_ptr<const PhaseField> field, const MeshJob& job, RunObserver* observer) {
  // With no iterations and no history there is nothing to improve.
  QualityHistory history;
  const bool recording = !job.outputs.history.empty();
  if (job.options.iterations > 0 || recording)
    improve(mesh, std::move(field), job.options, observer, recording ? &history : nullptr);
  // A fold keeps its triangles' quality, so nothing else would show it.
  if (const size_t folds = observer ? count_folds(mesh) : 0)
    observer->note(cat(folds, folds == 1 ? " surface edge folds" : " surface edges fold",
                       ": the surface turns back across each by more than ", int(MeshStats::kFoldDeg),
                       " degrees, two of its sheets laid onto each other (where a layer or rim is thinner than the "
                       "edges, or a surface meets the box at a glancing angle); `voronoimesh stats --folds N` lists where"));
  if (observer)
    if (const std::string note = sliver_note(mesh); !note.empty()) observer->note(note);
  // No output may replace an input of the run.
  StagedOutputs staged({job.input, job.mesh});
  write_staged(staged, mesh, job.outputs, recording ? &history : nullptr, observer);
}

} // namespace detail

} // namespace vm
