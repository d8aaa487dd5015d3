// The one run path (run/meshing.hpp): run_job() makes what the stages make one
// by one, tells its observer every stage in order, stops when asked without
// writing anything, refuses a bad job before reading its input, and keeps a
// closed mesh closed through a file (NodeMesh::outside_phase).

#include "fixtures.hpp"
#include "improve/node_merge.hpp"
#include "scratch_dir.hpp"
#include "nrrd_file.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/array_input.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/improve/smooth.hpp"
#include "voronoimesh/io/ply.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

namespace vm {
namespace {

using RunJob = test::ScratchDir;

const std::string kFourSpheres = std::string(VM_EXAMPLES_DIR) + "/four_spheres.json";

/// Records what a run tells its observer; asks to stop after `stop_after` iterations.
struct Recorder : RunObserver {
  std::vector<Stage> stages;
  std::vector<int> iterations;
  int creates = 0, improvements = 0, inputs = 0;
  std::vector<std::string> files;
  int stop_after = -1;
  bool stop_when_writing = false; ///< ask to stop once the write stage has begun (Ctrl-C during the write)

  void stage(Stage s, const std::string&) override {
    if (stages.empty() || stages.back() != s) stages.push_back(s);
  }
  void input_read(const std::string&, const Scene&, double) override { ++inputs; }
  void created(const CreateReport& r) override {
    ++creates;
    EXPECT_GT(r.triangles, 0u);
    EXPECT_GT(r.stats.tets_cut, 0u);
  }
  void iteration(const IterationReport& r, const InterfaceMesh&) override { iterations.push_back(r.iteration); }
  void improved(const ImproveReport& r) override {
    ++improvements;
    EXPECT_EQ(r.iterations, int(iterations.size()) - 1);
    EXPECT_GE(r.mean_quality, r.initial_mean_quality);
  }
  void written(const std::vector<std::string>& mesh, const std::vector<std::string>& phases) override {
    files = mesh;
    files.insert(files.end(), phases.begin(), phases.end());
  }
  bool stop_requested() override {
    if (stop_when_writing) return !stages.empty() && stages.back() == Stage::write;
    return stop_after >= 0 && int(iterations.size()) > stop_after;
  }
};

MeshJob four_spheres_job(const std::string& output, int iterations = 3) {
  MeshJob job;
  job.input = kFourSpheres;
  job.options.grid = std::array{16, 16, 16};
  job.options.iterations = iterations;
  job.outputs.mesh = output;
  return job;
}

TEST_F(RunJob, makes_what_the_stages_make_and_tells_every_stage_in_order) {
  Recorder seen;
  const NodeMesh written = run_job(four_spheres_job(path("m.ply")), &seen);
  const std::vector<Stage> order{Stage::read, Stage::sample, Stage::create, Stage::improve, Stage::write};
  EXPECT_EQ(seen.stages, order);
  EXPECT_EQ(seen.inputs, 1);
  EXPECT_EQ(seen.creates, 1);
  EXPECT_EQ(seen.improvements, 1);
  EXPECT_EQ(seen.iterations, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(seen.files, std::vector<std::string>{path("m.ply")});

  MeshOptions o = four_spheres_job("").options;
  const Scene scene = read_input(kFourSpheres);
  NodeMesh by_stages = create_mesh(scene, o);
  o.pipeline = pipeline_for(o, &scene); // improve_mesh() sees no scene: the paper's passes by default
  improve_mesh(by_stages, scene.field, o);
  EXPECT_EQ(written.points, by_stages.points);
  EXPECT_EQ(written.triangles, by_stages.triangles);
  const NodeMesh read = io::read_ply(path("m.ply"));
  EXPECT_EQ(read.points, by_stages.points);
  EXPECT_EQ(read.triangles, by_stages.triangles);
}

TEST_F(RunJob, a_stop_request_throws_cancelled_and_writes_nothing) {
  Recorder stopper;
  stopper.stop_after = 1;
  MeshJob job = four_spheres_job(path("m.ply"), 10);
  job.outputs.history = path("h.csv");
  EXPECT_THROW(run_job(job, &stopper), Cancelled);
  EXPECT_LT(stopper.iterations.size(), 4u);
  EXPECT_TRUE(std::filesystem::is_empty(dir_)) << "a stopped run wrote a file";
}

TEST_F(RunJob, a_stop_request_while_writing_writes_nothing) {
  Recorder stopper;
  stopper.stop_when_writing = true;
  MeshJob job = four_spheres_job(path("m.stl"), 1);
  job.outputs.per_phase = path("phases");
  job.outputs.history = path("h.svg");
  EXPECT_THROW(run_job(job, &stopper), Cancelled);
  EXPECT_EQ(stopper.stages.back(), Stage::write);
  size_t files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir_)) files += e.is_regular_file();
  EXPECT_EQ(files, 0u) << "a run stopped while writing left files";
}

TEST_F(RunJob, an_output_is_never_an_input_of_the_job) {
  run_job(four_spheres_job(path("created.ply"), 0));
  MeshJob smooth;
  smooth.mesh = path("created.ply");
  smooth.input = kFourSpheres;
  smooth.options.iterations = 1;
  smooth.outputs.mesh = path("created.ply");
  EXPECT_THROW(run_job(smooth), InvalidInput);
  std::filesystem::copy_file(kFourSpheres, path("scene.json"));
  smooth.input = path("scene.json");
  smooth.outputs.mesh = path("smoothed.ply");
  smooth.outputs.history = path("scene.json");
  try {
    run_job(smooth);
    ADD_FAILURE() << "the history replaced the scene";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("is also an input of this run"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path("smoothed.ply")));
}

TEST_F(RunJob, a_bad_job_is_refused_before_its_input_is_read) {
  Recorder seen;
  MeshJob job = four_spheres_job(path("m.off"));
  EXPECT_THROW(run_job(job, &seen), InvalidInput);
  job = four_spheres_job(path("m.ply"));
  job.options.pipeline = "smooth,wiggle";
  EXPECT_THROW(run_job(job, &seen), InvalidInput);
  job = four_spheres_job(path("m.ply"));
  job.options.top_k = 0;
  EXPECT_THROW(run_job(job, &seen), InvalidOption);
  job = four_spheres_job(path("missing/m.ply"));
  EXPECT_THROW(run_job(job, &seen), IoError);
  EXPECT_EQ(seen.inputs, 0);
  EXPECT_TRUE(seen.stages.empty());
}

TEST_F(RunJob, improving_a_mesh_from_a_file_needs_its_input_only_for_passes_that_evaluate_it) {
  run_job(four_spheres_job(path("created.ply"), 0));
  MeshJob smooth;
  smooth.mesh = path("created.ply");
  smooth.options.iterations = 2;
  smooth.outputs.mesh = path("smoothed.ply");
  try {
    run_job(smooth);
    ADD_FAILURE() << "a pipeline that needs the phase functions ran without them";
  } catch (const InvalidOption& e) {
    EXPECT_EQ(e.option(), "pipeline");
  }
  smooth.input = kFourSpheres;
  EXPECT_NO_THROW(run_job(smooth));
  MeshJob flip = smooth;
  flip.input.clear();
  flip.options.pipeline = "flip";
  EXPECT_NO_THROW(run_job(flip));
}

TEST_F(RunJob, a_closed_mesh_stays_closed_through_a_file) {
  MeshJob job = four_spheres_job(path("closed.ply"), 0);
  job.options.close = true;
  const NodeMesh created = run_job(job);
  ASSERT_EQ(created.outside_phase, 5);
  EXPECT_EQ(created.phase_names.back(), kOutsidePhaseName);
  EXPECT_EQ(io::read_ply(path("closed.ply")).outside_phase, 5);
  EXPECT_EQ(InterfaceMesh::from_node_mesh(created).outside_phase(), 5);
  EXPECT_EQ(phases_of_mesh(created, read_input(kFourSpheres).field)->num_phases(), 6);
  // Improving it from the file moves box nodes only within the box.
  MeshJob smooth;
  smooth.mesh = path("closed.ply");
  smooth.input = kFourSpheres;
  smooth.options.iterations = 2;
  const NodeMesh smoothed = run_job(smooth);
  EXPECT_EQ(smoothed.outside_phase, 5);
  for (const Vec3& p : smoothed.points)
    EXPECT_TRUE((p.array() >= created.domain.min.array() - 1e-12).all() &&
                (p.array() <= created.domain.max.array() + 1e-12).all());
}

TEST_F(RunJob, a_phase_of_a_scene_named_like_the_outside_is_not_the_outside) {
  // The last phase of an open mesh is named "exterior" by its scene: its
  // triangles lie inside the box, so the file does not make the mesh closed.
  NodeMesh open = test::four_spheres(12);
  open.phase_names = {"outside", "a", "b", "c", kOutsidePhaseName};
  io::write_ply(open, path("open.ply"));
  EXPECT_EQ(io::read_ply(path("open.ply")).outside_phase, -1);
}

/// Records the pipeline each improvement ran and what it did.
struct PipelineRecorder : RunObserver {
  std::vector<std::string> pipelines;
  std::vector<ImproveReport> reports;
  size_t created_triangles = 0;
  void created(const CreateReport& r) override { created_triangles = r.triangles; }
  void improved(const ImproveReport& r) override { pipelines.push_back(r.pipeline), reports.push_back(r); }
};

/// A ball of label 5 in 24^3 voxels, x fastest: the voxel grid is finer than the ball needs.
std::vector<int32_t> ball_labels() {
  std::vector<int32_t> labels;
  for (int k = 0; k < 24; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i) labels.push_back((Vec3(i, j, k) - Vec3(11.5, 11.2, 11.7)).norm() < 8 ? 5 : 0);
  return labels;
}

/// ball_labels() written to ball.nrrd.
/// @return the file
std::string ball_volume() {
  return test::write_nrrd("ball.nrrd", "type: int\ndimension: 3\nsizes: 24 24 24\n", ball_labels());
}

TEST_F(RunJob, label_volumes_are_coarsened_by_default_scenes_evened_out_and_meshes_from_files_left_as_they_are) {
  const std::string file = ball_volume();
  MeshJob job;
  job.input = file;
  job.options.iterations = 3;
  job.outputs.mesh = path("ball.ply");
  PipelineRecorder seen;
  const NodeMesh remeshed = run_job(job, &seen);
  ASSERT_EQ(seen.pipelines, std::vector<std::string>{kLabelVolumePipeline});
  EXPECT_LT(remeshed.num_triangles(), seen.created_triangles * 3 / 4); // coarsened, not only smoothed
  // The same through the library's other doors; a pipeline given is the one run.
  GridSpec grid;
  grid.cells = {23, 23, 23};
  grid.domain.max = Vec3(23, 23, 23);
  const Scene volume = scene_from_labels(grid, ball_labels());
  EXPECT_TRUE(volume.voxel_grid);
  EXPECT_EQ(pipeline_for(MeshOptions{}, &volume), kLabelVolumePipeline);
  MeshOptions flip_only;
  flip_only.pipeline = "flip";
  EXPECT_EQ(pipeline_for(flip_only, &volume), "flip");
  const Scene spheres = read_input(kFourSpheres);
  EXPECT_FALSE(spheres.voxel_grid);
  EXPECT_EQ(pipeline_for(MeshOptions{}, &spheres), kScenePipeline);
  EXPECT_EQ(pipeline_for(MeshOptions{}, nullptr), kDefaultPipeline);
  // A mesh from a file is improved as it is, not coarsened again.
  MeshJob again;
  again.mesh = path("ball.ply");
  again.input = file;
  again.options.iterations = 1;
  PipelineRecorder improved;
  EXPECT_EQ(run_job(again, &improved).num_triangles(), remeshed.num_triangles());
  EXPECT_EQ(improved.pipelines, std::vector<std::string>{kDefaultPipeline});
  std::filesystem::remove(file);
}

TEST_F(RunJob, a_size_in_world_units_remeshes_any_input_to_it_and_a_mesh_read_back_stays_there) {
  // Four spheres in the unit cube on 24^3 cells (h = 0.042): edges of 0.06.
  MeshJob job = four_spheres_job(path("sized.ply"), 10);
  job.options.grid = std::array{24, 24, 24};
  job.options.size = 0.06;
  PipelineRecorder seen;
  const NodeMesh sized = run_job(job, &seen);
  ASSERT_EQ(seen.pipelines, std::vector<std::string>{std::string("remesh:length=0.06,") + kPassesAfterRemesh});
  const double rms = rms_edge_length(InterfaceMesh::from_node_mesh(sized));
  EXPECT_GT(rms, 0.06 * 0.85);
  EXPECT_LT(rms, 0.06 * 1.15);
  // The same size again on the mesh from the file: the target is the same, so
  // the mesh keeps about its triangles (a size relative to the mesh would
  // coarsen it once more).
  MeshJob again;
  again.mesh = path("sized.ply");
  again.input = kFourSpheres;
  again.options.iterations = 5;
  again.options.size = 0.06;
  const NodeMesh resized = run_job(again);
  EXPECT_NEAR(double(resized.num_triangles()), double(sized.num_triangles()), 0.1 * double(sized.num_triangles()));
  // Negative, or with a pipeline of one's own: refused before any work.
  job.options.size = -1;
  EXPECT_THROW(run_job(job), InvalidOption);
  job.options.size = 0.06;
  job.options.pipeline = "smooth,flip";
  EXPECT_THROW(run_job(job), InvalidOption);
}

/// Records the notes of a run and what create reported.
struct NoteRecorder : RunObserver {
  std::vector<std::string> notes;
  std::vector<int32_t> lost;
  void created(const CreateReport& r) override { lost = r.lost_phases; }
  void note(const std::string& line) override { notes.push_back(line); }
};

// A mesh file with a vertex of no triangle (another tool's edit) is improved
// without it, and a note says so; validate() would refuse it as it stands.
TEST_F(RunJob, vertices_of_no_triangle_in_a_mesh_file_are_dropped_with_a_note) {
  run_job(four_spheres_job(path("created.ply"), 0));
  NodeMesh created = io::read_ply(path("created.ply"));
  const NodeMesh original = created;
  created.points.insert(created.points.begin() + 7, Vec3(0.5, 0.5, 0.5)); // vertex 7, the others after it shifted
  for (auto& t : created.triangles)
    for (int32_t& v : t) v += v >= 7;
  ASSERT_FALSE(validate(created).ok());
  io::write_ply(created, path("stray.ply"));
  MeshJob copy;
  copy.mesh = path("stray.ply");
  copy.options.iterations = 0;
  copy.outputs.mesh = path("copied.ply");
  NoteRecorder seen;
  const NodeMesh out = run_job(copy, &seen);
  EXPECT_EQ(out.points, original.points);
  EXPECT_EQ(out.triangles, original.triangles);
  const std::string note = "stray.ply: 1 of its " + std::to_string(created.points.size()) +
                           " vertices belong to no triangle: dropped";
  EXPECT_EQ(std::count_if(seen.notes.begin(), seen.notes.end(),
                          [&](const std::string& n) { return n.find(note) != std::string::npos; }), 1);
}

// The library's improve_mesh() too: a stray node would fail the improved
// mesh's validation, blamed on the library.
TEST_F(RunJob, improve_mesh_drops_nodes_of_no_triangle_with_a_note) {
  const Scene scene = parse_scene(R"({"grid": 12, "phases": [{"kind": "constant", "value": 0},
      {"kind": "sphere", "center": [0.5, 0.5, 0.5], "radius": 0.3}]})", "ball.json");
  NodeMesh mesh = create_mesh(scene);
  const size_t nodes = mesh.points.size();
  mesh.points.push_back(Vec3(0.5, 0.5, 0.5));
  MeshOptions o;
  o.iterations = 2;
  NoteRecorder seen;
  improve_mesh(mesh, scene.field, o, &seen);
  EXPECT_EQ(mesh.points.size(), nodes);
  EXPECT_TRUE(validate(mesh).ok());
  ASSERT_EQ(seen.notes.size(), 1u);
  EXPECT_EQ(seen.notes[0].rfind("the mesh: 1 of its " + std::to_string(nodes + 1) + " vertices belong to no triangle", 0),
            0u) << seen.notes[0];
}

TEST_F(RunJob, a_phase_the_mesh_loses_is_named_with_its_size_never_dropped_silently) {
  // The 2 x 2 x 2 volume of mesher test suites: label 1 is one voxel, too small
  // for the default phase functions (--voxel-faithful keeps it: VoxelFaithful.*).
  const std::vector<int32_t> labels{0, 0, 0, 1, 2, 3, 2, 3};
  const std::string file = test::write_nrrd("two.nrrd", "type: int\ndimension: 3\nsizes: 2 2 2\n", labels);
  NoteRecorder seen;
  create_mesh(read_input(file), MeshOptions{}, &seen);
  std::filesystem::remove(file);
  EXPECT_EQ(seen.lost, std::vector<int32_t>{1});
  ASSERT_EQ(seen.notes.size(), 1u);
  EXPECT_EQ(seen.notes[0].rfind("label 1: 1 voxel, no surface in the mesh", 0), 0u) << seen.notes[0];
  // Its voxel touches label 0 across two faces and label 3 across one.
  EXPECT_NE(seen.notes[0].find("merged into label 0:"), std::string::npos) << seen.notes[0];
  // A scene's phase smaller than a cell is named too; phases the mesh keeps are not.
  const Scene scene = parse_scene(R"({"grid": 8, "phases": [{"name": "outside", "kind": "constant", "value": 0},
      {"name": "big", "kind": "sphere", "center": [0.5, 0.5, 0.5], "radius": 0.3},
      {"name": "speck", "kind": "sphere", "center": [0.11, 0.13, 0.12], "radius": 0.01}]})",
                                  "speck.json");
  NoteRecorder speck;
  create_mesh(scene, MeshOptions{}, &speck);
  EXPECT_EQ(speck.lost, std::vector<int32_t>{2});
  ASSERT_EQ(speck.notes.size(), 1u);
  EXPECT_NE(speck.notes[0].find("phase 'speck': no surface in the mesh"), std::string::npos) << speck.notes[0];
}

TEST_F(RunJob, label_volumes_stop_when_quality_stops_improving_unless_told_to_run_every_iteration) {
  const std::string file = ball_volume();
  MeshJob job;
  job.input = file;
  job.options.iterations = 40;
  PipelineRecorder converged;
  run_job(job, &converged);
  ASSERT_EQ(converged.reports.size(), 1u);
  EXPECT_TRUE(converged.reports[0].converged);
  EXPECT_LT(converged.reports[0].iterations, 40);
  job.options.stop_when_converged = false; // --all-iterations
  PipelineRecorder every;
  run_job(job, &every);
  ASSERT_EQ(every.reports.size(), 1u);
  EXPECT_FALSE(every.reports[0].converged);
  EXPECT_EQ(every.reports[0].iterations, 40);
  // Stopping is the default of a label volume's default pipeline only.
  const Scene volume = read_input(file);
  EXPECT_EQ(options_for_scene(MeshOptions{}, volume).stop_when_converged, true);
  MeshOptions given;
  given.pipeline = kLabelVolumePipeline;
  EXPECT_EQ(options_for_scene(given, volume).stop_when_converged, false);
  MeshOptions sized;
  sized.size = 2;
  const MeshOptions resolved = options_for_scene(sized, volume);
  EXPECT_EQ(resolved.stop_when_converged, false);
  EXPECT_EQ(resolved.size, 0); // taken into the pipeline
  EXPECT_EQ(options_for_scene(MeshOptions{}, read_input(kFourSpheres)).stop_when_converged, false);
  MeshOptions asked;
  asked.stop_when_converged = true;
  EXPECT_EQ(options_for_scene(asked, read_input(kFourSpheres)).stop_when_converged, true);
}

// A phase whose last triangles go during improvement is named too. No built-in
// pass was seen to do it (80 small random label volumes), so a pass made for
// the test takes a sphere standing alone in the outside phase away whole.
TEST_F(RunJob, a_phase_improvement_loses_is_named_never_dropped_silently) {
  const Scene scene = parse_scene(R"({"grid": 16, "phases": [{"name": "outside", "kind": "constant", "value": 0},
      {"name": "big", "kind": "sphere", "center": [0.35, 0.35, 0.35], "radius": 0.2},
      {"name": "apart", "kind": "sphere", "center": [0.75, 0.75, 0.75], "radius": 0.15}]})",
                                  "apart.json");
  PassRegistry passes = builtin_registry();
  PassInfo drop;
  drop.name = "drop_apart";
  drop.summary = "removes every triangle of phase 2";
  struct Drop : Pass {
    void run(PassContext& c) override {
      NodeMesh m = c.mesh.to_node_mesh(), kept = m.empty_like();
      kept.points = m.points;
      for (size_t t = 0; t < m.num_triangles(); ++t)
        if (m.pairs[t][0] != 2 && m.pairs[t][1] != 2) kept.triangles.push_back(m.triangles[t]), kept.pairs.push_back(m.pairs[t]);
      std::vector<int32_t> kept_nodes;
      detail::drop_unused_nodes(kept, kept_nodes); // the sphere's nodes, or validation fails on them
      c.mesh = InterfaceMesh::from_node_mesh(kept);
    }
  };
  drop.make = [](const ParamValues&) { return std::make_unique<Drop>(); };
  passes.add(drop);
  MeshOptions o;
  o.iterations = 1;
  NoteRecorder seen;
  NodeMesh mesh = create_mesh(scene, o, &seen);
  ASSERT_TRUE(seen.notes.empty());
  o.passes = &passes;
  o.pipeline = "smooth,drop_apart";
  improve_mesh(mesh, scene.field, o, &seen);
  ASSERT_EQ(seen.notes.size(), 1u);
  EXPECT_EQ(seen.notes[0].rfind("label 2 ('apart'): no surface left after improvement", 0), 0u) << seen.notes[0];
  o.pipeline = "smooth"; // keeps every phase: no note
  NoteRecorder quiet;
  improve_mesh(mesh, scene.field, o, &quiet);
  EXPECT_TRUE(quiet.notes.empty());
}

// What the note suggests works: a one-voxel sheet smoothed with sigma 0.7 leads
// at its voxel centres by less than snapping's 0.2 cells, so create snaps it
// away; with --snap 0.1 it is a phase of the mesh.
TEST_F(RunJob, folds_are_reported_in_a_note_as_their_quality_cannot_show_them) {
  // A tetrahedron flattened to its apex 0.05 over its base, of good triangles
  // (q 0.3-0.5): its base edges fold. Nothing else about it is wrong.
  test::Builder flat;
  test::add_tetrahedron(flat, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 0.05)}, 1, 0);
  io::write_ply(flat.mesh, path("flat.ply"));
  MeshJob job;
  job.mesh = path("flat.ply");
  job.options.iterations = 0;
  job.outputs.mesh = path("out.ply");
  NoteRecorder recorder;
  run_job(job, &recorder);
  ASSERT_EQ(recorder.notes.size(), 1u);
  EXPECT_EQ(recorder.notes[0].rfind("3 surface edges fold: the surface turns back across each by more than 150 degrees",
                                    0),
            0u)
      << recorder.notes[0];
  // A resolved mesh says nothing of folds.
  NoteRecorder resolved;
  run_job(four_spheres_job(path("spheres.ply")), &resolved);
  for (const std::string& note : resolved.notes) EXPECT_EQ(note.find("fold"), std::string::npos) << note;
}

TEST_F(RunJob, a_thin_sheet_snapping_removes_is_kept_with_the_snap_the_note_suggests) {
  constexpr int n = 24;
  std::vector<uint8_t> labels;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) labels.push_back(i == 12 && j >= 6 && j < 18 && k >= 6 && k < 18 ? 2 : 0);
  const std::string file = test::write_nrrd("sheet.nrrd", "type: uchar\ndimension: 3\nsizes: 24 24 24\n", labels);
  InputOptions smoothing;
  smoothing.smoothing = 0.7;
  const Scene scene = read_input(file, smoothing);
  std::filesystem::remove(file);
  NoteRecorder snapped, kept;
  create_mesh(scene, MeshOptions{}, &snapped);
  ASSERT_FALSE(snapped.notes.empty());
  EXPECT_NE(snapped.notes.back().find("--snap 0.1"), std::string::npos) << snapped.notes.back();
  MeshOptions finer;
  finer.snap = 0.1;
  const NodeMesh mesh = create_mesh(scene, finer, &kept);
  EXPECT_TRUE(kept.lost.empty());
  EXPECT_TRUE(validate(mesh).ok());
}

} // namespace
} // namespace vm
