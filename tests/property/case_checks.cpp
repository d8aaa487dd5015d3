#include "case_checks.hpp"

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/registry.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include "mesh_checks.hpp"

#include <tbb/global_control.h>

#include <exception>
#include <optional>

namespace vm::test {

namespace {

/// The checks that hold for every mesh at every stage: valid, no crossings, no
/// node outside the domain box. Appends a failure naming `stage` and returns
/// false when one fails.
bool valid_unintersected_and_inside(const NodeMesh& m, const std::string& stage, CaseResult& r) {
  const ValidationReport report = validate(m);
  if (!report.ok()) {
    r.failures.push_back(stage + ": validate: " + std::to_string(report.problem_count) + " problems, first: " +
                         report.problems.front());
    return false;
  }
  const IntersectionReport crossings = find_self_intersections(m, 1);
  if (!crossings.ok()) {
    r.failures.push_back(stage + ": " + std::to_string(crossings.count) + " intersecting triangle pairs, first: " +
                         std::to_string(crossings.pairs[0][0]) + " and " + std::to_string(crossings.pairs[0][1]));
    return false;
  }
  if (const size_t outside = nodes_outside_the_domain(m); outside > 0) {
    r.failures.push_back(stage + ": " + std::to_string(outside) + " nodes outside the domain box");
    return false;
  }
  return true;
}

void check_stages(const RandomCase& c, const CheckOptions& o, CaseResult& r) {
  MeshOptions options = c.options;
  options.validate = false; // validated here, to report rather than throw
  options.threads = 1;
  NodeMesh created = create_mesh(c.scene, options);
  r.triangles = created.num_triangles();
  if (!valid_unintersected_and_inside(created, "create", r)) return;

  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const PassRegistry registry = builtin_registry();
  const Pipeline moving = Pipeline::parse("smooth,project,clamp", registry);
  const Pipeline flips = Pipeline::parse("flip", registry);
  const std::optional<Pipeline> remesh =
      o.remesh.empty() ? std::nullopt : std::optional<Pipeline>(Pipeline::parse(o.remesh, registry));
  // A closed mesh has the extra phase outside the box; the passes need its function too.
  const auto field = phases_of_mesh(created, c.scene.field);
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(created);
  RunOptions once;
  once.iterations = 1;
  for (int it = 1; it <= o.iterations; ++it) {
    const std::string stage = "iteration " + std::to_string(it);
    if (remesh) {
      // A fresh pass each iteration: it remeshes the mesh as it is, so a size
      // over 1 coarsens it every time (a stress test, not a normal run).
      remesh->run(mesh, field.get(), once);
      if (!valid_unintersected_and_inside(mesh.to_node_mesh(), stage + " after remeshing", r)) return;
    }
    const std::vector<Vec3> before = face_normals(mesh);
    moving.run(mesh, field.get(), once);
    if (const size_t turned = turned_faces(before, face_normals(mesh)); turned > 0) {
      r.failures.push_back(stage + " after moving: " + std::to_string(turned) + " triangles turned by 90 degrees or more");
      return;
    }
    if (!valid_unintersected_and_inside(mesh.to_node_mesh(), stage + " after moving", r)) return;
    flips.run(mesh, field.get(), once);
    const NodeMesh m = mesh.to_node_mesh();
    if (!valid_unintersected_and_inside(m, stage + " after flipping", r)) return;
    if (it == o.iterations && c.closed_form) r.against_field = inverted_triangles(m, *field);
    if (it == o.iterations) r.folds = count_folds(m);
  }
}

/// Checks the mesh of a whole run after every iteration whose crossings were
/// looked for (CheckOptions::whole), and counts the windows of unchecked
/// crossings that ran again.
struct IterationChecks : RunObserver {
  CaseResult* result = nullptr; ///< null: count windows only
  size_t run_again = 0;
  void iteration(const IterationReport& report, const InterfaceMesh& mesh) override {
    run_again += report.runs_again;
    if (!result || !result->ok() || report.crossings_deferred) return;
    valid_unintersected_and_inside(mesh.to_node_mesh(), "iteration " + std::to_string(report.iteration) +
                                                            " of the default pipeline", *result);
  }
};

/// The whole of mesh_scene() on `threads` threads, watched by `observer` (null for none).
NodeMesh meshed(const RandomCase& c, const CheckOptions& o, int threads, RunObserver* observer = nullptr) {
  MeshOptions options = c.options;
  options.iterations = o.iterations;
  options.threads = threads;
  options.check_crossings_every = o.check_crossings_every;
  return mesh_scene(c.scene, options, observer);
}

/// The case meshed whole on one thread (CheckOptions::whole,
/// check_crossings_every over 1), returned; the mesh checked at the end, and
/// after every checked iteration too with `whole`.
NodeMesh check_whole(const RandomCase& c, const CheckOptions& o, CaseResult& r) {
  IterationChecks checks;
  if (o.whole) checks.result = &r;
  NodeMesh m = meshed(c, o, 1, &checks);
  r.windows_run_again = checks.run_again;
  if (!r.ok()) return m;
  r.triangles = m.num_triangles();
  const std::string stage = o.whole ? "the default pipeline's mesh" : "meshed with crossings checked every " +
                                                                          std::to_string(o.check_crossings_every) +
                                                                          " iterations";
  if (!valid_unintersected_and_inside(m, stage, r)) return m;
  if (c.closed_form) r.against_field = inverted_triangles(m, *phases_of_mesh(m, c.scene.field));
  r.folds = count_folds(m);
  return m;
}

/// Requires the same mesh on 1 and 2 threads; `one_thread`, if given, is the
/// first (check_whole()'s).
void compare_threads(const RandomCase& c, const CheckOptions& o, CaseResult& r,
                     std::optional<NodeMesh> one_thread) {
  const NodeMesh one = one_thread ? std::move(*one_thread) : meshed(c, o, 1), two = meshed(c, o, 2);
  if (one.points != two.points || one.triangles != two.triangles || one.pairs != two.pairs)
    r.failures.push_back("1 and 2 threads give different meshes (" + std::to_string(one.num_triangles()) + " and " +
                         std::to_string(two.num_triangles()) + " triangles)");
}

} // namespace

CaseResult check_case(const RandomCase& c, const CheckOptions& o) {
  CaseResult r;
  try {
    std::optional<NodeMesh> whole;
    if (o.whole || o.check_crossings_every > 1) whole = check_whole(c, o, r);
    else check_stages(c, o, r);
    if (r.ok() && o.compare_threads) compare_threads(c, o, r, std::move(whole));
  } catch (const std::exception& e) {
    r.failures.push_back(std::string("threw: ") + e.what());
  }
  return r;
}

} // namespace vm::test
