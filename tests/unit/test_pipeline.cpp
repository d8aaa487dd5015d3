// Tests of the pipeline (paper Algorithm 1) and the pass registry: specs parse
// against the registry, runs stop when asked or when quality stops improving
// (after one last iteration told that it is the last), and the built-in passes
// are listed with their parameters.

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/check/validate.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace vm;

using test::example_scene;
using test::initial_mesh;
using test::iterations;

TEST(Pipeline, parses_passes_and_parameters_against_the_registry) {
  const PassRegistry registry = builtin_registry();
  Pipeline p = Pipeline::parse("smooth:rest_factor=1.3, project,clamp,flip:skip_quality=0.95:max_rounds=2", registry);
  ASSERT_EQ(p.steps().size(), 4u);
  EXPECT_EQ(p.steps()[0].params.at("rest_factor"), 1.3);
  EXPECT_EQ(p.steps()[2].params.at("factor"), 0.5); // default filled in
  EXPECT_EQ(p.steps()[3].params.at("max_rounds"), 2);
  EXPECT_TRUE(p.needs_field());
  EXPECT_FALSE(Pipeline::parse("flip", registry).needs_field());
  for (const char* bad : {"smoth", "smooth:rest=1", "smooth:rest_factor=abc", "smooth:rest_factor=9",
                          "flip:max_rounds=1.5", "smooth,,flip", "", "flip:skip_quality"}) {
    try {
      Pipeline::parse(bad, registry);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("pipeline"), std::string::npos) << e.what();
    }
  }
  // Numbers are decimal, with a point: what each refusal says.
  const std::pair<const char*, const char*> said[] = {
      {"smooth:rest_factor=1e400", "smooth.rest_factor: 1e400 is out of range"},
      {"smooth:rest_factor=0x2", "smooth.rest_factor: '0x2' is not a number"}, // std::stod read hex
      {"smooth:rest_factor=inf", "'inf' is not a number"},
      {"smooth:rest_factor=1,5", "'5' is not a pass: a decimal comma?"}};
  for (const auto& [bad, message] : said) {
    try {
      Pipeline::parse(bad, registry);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(Pipeline::parse("smooth:rest_factor=+1.5", registry).steps()[0].params.at("rest_factor"), 1.5);
}

TEST(Pipeline, refuses_to_run_field_passes_without_a_field) {
  Scene scene = example_scene("four_spheres.json", 16);
  InterfaceMesh mesh = initial_mesh(scene);
  EXPECT_THROW(Pipeline::parse("smooth", builtin_registry()).run(mesh, nullptr, iterations(1)), InvalidInput);
}

// A closed mesh's phase outside the box, with the scene's field alone: refused
// by name, not read out of bounds; with_outside_phase() runs.
TEST(Pipeline, refuses_a_field_without_a_phase_of_the_mesh) {
  const Scene scene = example_scene("four_spheres.json", 12);
  CreateParams closed;
  closed.close = true;
  NodeMesh created = test::created_mesh(scene, closed);
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(created);
  const Pipeline smooth = Pipeline::parse("smooth", builtin_registry());
  try {
    smooth.run(mesh, scene.field.get(), iterations(1));
    ADD_FAILURE() << "ran with a field that lacks the mesh's outside phase";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("the mesh has phase 5, but its phase functions only 5 phases"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(smooth.run(mesh, phases_of_mesh(created, scene.field).get(), iterations(1)), 1);
}

TEST(Pipeline, stops_when_quality_stops_improving_after_one_last_iteration_told_that_it_is_the_last) {
  // A pass that writes down what each iteration is told: passes such as flip
  // end a run with work of their own (its last collapse batch) when they are
  // told that the iteration is the run's last.
  struct Told {
    int iteration, iterations;
  };
  std::vector<Told> told;
  struct Record : Pass {
    std::vector<Told>* told;
    explicit Record(std::vector<Told>* t) : told(t) {}
    void run(PassContext& c) override { told->push_back({c.iteration, c.iterations}); }
  };
  PassRegistry passes = builtin_registry();
  PassInfo record;
  record.name = "record";
  record.summary = "writes down the iteration and the run's last";
  record.make = [&told](const ParamValues&) { return std::make_unique<Record>(&told); };
  passes.add(record);
  Scene scene = example_scene("four_spheres.json", 24);
  InterfaceMesh mesh = initial_mesh(scene);
  RunOptions run = iterations(200);
  run.stop_when_converged = true;
  std::vector<std::pair<double, double>> quality; // after each iteration, the initial mesh first
  std::vector<int> last_known;                     // the run's last iteration as each report says
  run.observer = [&](const IterationReport& r, const InterfaceMesh&) {
    quality.emplace_back(r.min_quality, r.mean_quality);
    last_known.push_back(r.last_iteration);
  };
  const int done = Pipeline::parse(std::string(kDefaultPipeline) + ",record", passes).run(mesh, scene.field.get(), run);
  EXPECT_LT(done, 200);
  EXPECT_GT(done, 3);
  ASSERT_EQ(told.size(), size_t(done));
  // Every iteration but the last was told the most asked for, the last that it is the last.
  for (int it = 1; it < done; ++it) EXPECT_EQ(told[size_t(it - 1)].iterations, 200) << "iteration " << it;
  EXPECT_EQ(told.back().iteration, done);
  EXPECT_EQ(told.back().iterations, done);
  // The two iterations before the last raised neither the worst triangle by
  // more than RunOptions::tolerance nor the mean by more than mean_tolerance
  // over the best before them; the one before those did.
  ASSERT_EQ(quality.size(), size_t(done + 1));
  auto best_before = [&](int it) {
    std::pair<double, double> best{0, 0};
    for (int i = 0; i < it; ++i)
      best = {std::max(best.first, quality[size_t(i)].first), std::max(best.second, quality[size_t(i)].second)};
    return best;
  };
  auto improved = [&](int it) {
    const auto best = best_before(it);
    return quality[size_t(it)].first > best.first + run.tolerance ||
           quality[size_t(it)].second > best.second + run.mean_tolerance;
  };
  EXPECT_FALSE(improved(done - 1));
  EXPECT_FALSE(improved(done - 2));
  // Unless it came before the passes' schedules settled (the flip pass
  // collapses every sliver until iteration 5), when stalls do not count.
  const int settled = Pipeline::parse(kDefaultPipeline, passes).settled_from();
  EXPECT_EQ(settled, 6);
  EXPECT_TRUE(done - 3 < settled || improved(done - 3));
  EXPECT_GE(done - 2, settled);
  // Progress counts to the most asked for until the run knows it converged
  // (after the second iteration that stalled), then to the iteration it ends at.
  for (int it = 0; it < done - 1; ++it) EXPECT_EQ(last_known[size_t(it)], 200) << "iteration " << it;
  EXPECT_EQ(last_known[size_t(done - 1)], done);
  EXPECT_EQ(last_known[size_t(done)], done);
}

TEST(Pipeline, judges_convergence_only_once_every_pass_schedule_settled) {
  // A run whose quality never changes stops after three iterations (two
  // stalled, then the last), unless a pass's schedule still changes what it
  // does: a stall then says nothing of later iterations (on a 2x2x2 label
  // volume the remesh calls of iterations 2 and 3 stalled, and the run ended
  // before the polish pass began).
  struct Idle : Pass {
    void run(PassContext&) override {}
  };
  PassRegistry passes = builtin_registry();
  PassInfo idle;
  idle.name = "idle";
  idle.summary = "changes nothing, on a schedule";
  idle.params = {{"until", 0, 0, 100, true, "the last iteration of its schedule"}};
  idle.make = [](const ParamValues&) { return std::make_unique<Idle>(); };
  idle.scheduled_until = [](const ParamValues& p) { return int(p.at("until")); };
  passes.add(idle);
  Scene scene = example_scene("four_spheres.json", 12);
  RunOptions run = iterations(50);
  run.stop_when_converged = true;
  auto done = [&](const std::string& spec) {
    InterfaceMesh mesh = initial_mesh(scene);
    const Pipeline pipeline = Pipeline::parse(spec, passes);
    return std::pair{pipeline.run(mesh, scene.field.get(), run), pipeline.settled_from()};
  };
  EXPECT_EQ(done("idle"), std::pair(3, 1));
  EXPECT_EQ(done("idle:until=6"), std::pair(9, 7)); // 7 and 8 stall, 9 is the last
  EXPECT_EQ(done("idle:until=2,idle:until=4"), std::pair(7, 5));
  // The built-in schedules: the remesh pass's last call, the flip pass's last
  // iteration of every sliver collapsed (with collapses on), the polish pass's first.
  EXPECT_EQ(Pipeline::parse(kLabelVolumePipeline, passes).settled_from(), 6);
  EXPECT_EQ(Pipeline::parse("remesh:last=9,flip", passes).settled_from(), 10);
  EXPECT_EQ(Pipeline::parse("smooth,flip:collapse_below=0", passes).settled_from(), 1);
  EXPECT_EQ(Pipeline::parse("polish:first=3", passes).settled_from(), 3);
}

TEST(Pipeline, stops_before_the_iteration_after_a_stop_request) {
  // The CLI's Ctrl-C: asked before each iteration, the run ends cleanly there.
  Scene scene = example_scene("four_spheres.json", 16);
  InterfaceMesh mesh = initial_mesh(scene);
  RunOptions run = iterations(50);
  int seen = 0;
  run.observer = [&](const IterationReport& r, const InterfaceMesh&) { seen = r.iteration; };
  run.stop_requested = [&] { return seen >= 3; };
  const int done = Pipeline::parse(kDefaultPipeline, builtin_registry()).run(mesh, scene.field.get(), run);
  EXPECT_EQ(done, 3);
  EXPECT_EQ(seen, 3);
  EXPECT_TRUE(validate(mesh.to_node_mesh()).ok());
}

TEST(Registry, lists_the_builtin_passes_with_schemas) {
  const PassRegistry registry = builtin_registry();
  std::vector<std::string> names;
  for (const PassInfo* p : registry.all()) names.push_back(p->name);
  EXPECT_EQ(names, (std::vector<std::string>{"clamp", "flip", "floor", "polish", "project", "remesh", "smooth", "stats"}));
  EXPECT_EQ(registry.get("smooth").params.at(0).default_value, 1.2);
  PassRegistry r2 = builtin_registry();
  PassInfo dup;
  dup.name = "smooth";
  EXPECT_THROW(r2.add(dup), InvalidInput);
}

} // namespace
