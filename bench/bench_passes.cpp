// Google Benchmark of every stage and pass on fixed meshes, to see which one a
// change speeds up: sampling a scene, create (paper sect. 4.1), smoothing
// (Alg. 4), projection (eq. 4), clamping (Alg. 3), the guarded commit
// (improve/guard.hpp), flipping (Alg. 5), the quality summary and a whole iteration.
// Scenes: the seven-phase scene at grid 44 (~16k triangles, the paper's Fig. 8
// size) and the four spheres at grid 128 (~70k triangles); the argument is the
// thread count.
//
//   bench_passes [--benchmark_filter=REGEX] [other Google Benchmark options]
//
// The passes work on the mesh after kWarmIterations iterations, the state most
// iterations of a run see (the first ones flip and move far more). Passes that
// change the mesh get a fresh copy every iteration, made outside the timing.

#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/improve/clamp.hpp"
#include "voronoimesh/improve/flip.hpp"
#include "voronoimesh/improve/guard.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/project.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <memory>
#include <string>
#include <vector>

namespace {

constexpr int kWarmIterations = 5;

struct SceneCase {
  const char* file; // in examples/
  int grid;
};
constexpr SceneCase kVoronoi7{"voronoi7.json", 44};
constexpr SceneCase kFourSpheres{"four_spheres.json", 128};

/// A scene on its grid, its samples, and a mesh part way through improvement
/// with the pending displacement of its next iteration before and after clamping.
struct Fixture {
  vm::Scene scene;
  vm::GridSpec grid;
  vm::SampledField samples;
  vm::InterfaceMesh mesh;
  std::vector<vm::Vec3> unclamped, clamped;
};

std::unique_ptr<Fixture> make_fixture(const SceneCase& c) {
  auto f = std::make_unique<Fixture>();
  f->scene = vm::load_input(std::string(VM_EXAMPLES_DIR) + "/" + c.file);
  f->scene.grid.cells = {c.grid, c.grid, c.grid};
  f->grid = vm::grid_for_lattice(f->scene.grid, vm::Lattice::bcc);
  f->samples = vm::SampledField::sample(*f->scene.field, f->grid);
  vm::NodeMesh initial;
  vm::create_initial_mesh(f->samples, {}, initial);
  f->mesh = vm::InterfaceMesh::from_node_mesh(initial);
  vm::RunOptions warm;
  warm.iterations = kWarmIterations;
  vm::Pipeline::parse(vm::kDefaultPipeline, vm::builtin_registry()).run(f->mesh, f->scene.field.get(), warm);
  f->unclamped.assign(f->mesh.num_nodes(), vm::Vec3::Zero());
  vm::add_smoothing_forces(f->mesh, *f->scene.field, {}, f->unclamped);
  vm::add_projection(f->mesh, *f->scene.field, {}, f->unclamped);
  f->clamped = f->unclamped;
  vm::clamp_displacements(f->mesh, {}, f->clamped);
  return f;
}

/// The fixture of a scene, built on first use (a benchmark filter builds only
/// the ones it needs).
const Fixture& fixture(const SceneCase& c) {
  static std::unique_ptr<Fixture> voronoi7, four_spheres;
  auto& slot = &c == &kVoronoi7 ? voronoi7 : four_spheres;
  if (!slot) slot = make_fixture(c);
  return *slot;
}

tbb::global_control thread_limit(const benchmark::State& state) {
  return tbb::global_control(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
}

void BM_sample(benchmark::State& state, const SceneCase* c) {
  const Fixture& f = fixture(*c);
  const auto limit = thread_limit(state);
  for (auto _ : state) benchmark::DoNotOptimize(vm::SampledField::sample(*f.scene.field, f.grid));
}

void BM_create(benchmark::State& state, const SceneCase* c) {
  const Fixture& f = fixture(*c);
  const auto limit = thread_limit(state);
  vm::NodeMesh out;
  for (auto _ : state) benchmark::DoNotOptimize(vm::create_initial_mesh(f.samples, {}, out));
  state.counters["triangles"] = double(out.num_triangles());
}

/// Times add(mesh, field, delta), a pass that adds to the displacement buffer
/// (it only grows across iterations, which costs the same).
template <class AddMoves> void time_moves(benchmark::State& state, const Fixture& f, AddMoves add) {
  const auto limit = thread_limit(state);
  std::vector<vm::Vec3> delta(f.mesh.num_nodes(), vm::Vec3::Zero());
  for (auto _ : state) {
    add(f.mesh, *f.scene.field, delta);
    benchmark::DoNotOptimize(delta.data());
  }
}

/// Times change(mesh) on a fresh copy of the fixture's mesh every iteration;
/// making and freeing the copy are not timed.
template <class Change> void time_on_copy(benchmark::State& state, const Fixture& f, Change change) {
  const auto limit = thread_limit(state);
  for (auto _ : state) {
    state.PauseTiming();
    vm::InterfaceMesh mesh = f.mesh;
    state.ResumeTiming();
    change(mesh);
    state.PauseTiming();
    mesh = {};
    state.ResumeTiming();
  }
}

void BM_smooth(benchmark::State& state, const SceneCase* c) {
  time_moves(state, fixture(*c), [](const vm::InterfaceMesh& m, const vm::PhaseField& field, std::vector<vm::Vec3>& d) {
    vm::add_smoothing_forces(m, field, {}, d);
  });
}

void BM_project(benchmark::State& state, const SceneCase* c) {
  time_moves(state, fixture(*c), [](const vm::InterfaceMesh& m, const vm::PhaseField& field, std::vector<vm::Vec3>& d) {
    vm::add_projection(m, field, {}, d);
  });
}

void BM_clamp(benchmark::State& state, const SceneCase* c) {
  const Fixture& f = fixture(*c);
  const auto limit = thread_limit(state);
  std::vector<vm::Vec3> delta;
  for (auto _ : state) {
    state.PauseTiming();
    delta = f.unclamped;
    state.ResumeTiming();
    vm::clamp_displacements(f.mesh, {}, delta);
    benchmark::DoNotOptimize(delta.data());
  }
}

/// The pipeline's commit: moves through the crossing guard, with the phase
/// functions for the junction-orientation check (as PassContext::commit()).
/// Copying the displacement is timed too: it is tiny next to the guard.
void BM_guarded_commit(benchmark::State& state, const SceneCase* c) {
  const Fixture& f = fixture(*c);
  time_on_copy(state, f, [&](vm::InterfaceMesh& mesh) {
    std::vector<vm::Vec3> delta = f.clamped;
    benchmark::DoNotOptimize(vm::commit_without_crossings(mesh, delta, f.scene.field.get()));
  });
}

/// The commit without the guard (--no-guard), for the guard's cost.
void BM_unguarded_commit(benchmark::State& state, const SceneCase* c) {
  const Fixture& f = fixture(*c);
  time_on_copy(state, f, [&](vm::InterfaceMesh& mesh) { mesh.move_nodes(f.clamped); });
}

void BM_flip(benchmark::State& state, const SceneCase* c) {
  const Fixture& f = fixture(*c);
  vm::FlipParams params;
  params.field = f.scene.field.get();
  size_t flips = 0;
  time_on_copy(state, f, [&](vm::InterfaceMesh& mesh) { flips = vm::flip_edges(mesh, params).flips; });
  state.counters["flips"] = double(flips);
}

void BM_quality_summary(benchmark::State& state, const SceneCase* c) {
  const Fixture& f = fixture(*c);
  const auto limit = thread_limit(state);
  for (auto _ : state) benchmark::DoNotOptimize(vm::quality_summary(f.mesh));
}

/// One iteration of the default pipeline with the guard, as bench_mesh runs it
/// (two quality summaries included: before and after, for the observer).
void BM_iteration(benchmark::State& state, const SceneCase* c) {
  const Fixture& f = fixture(*c);
  const vm::Pipeline pipeline = vm::Pipeline::parse(vm::kDefaultPipeline, vm::builtin_registry());
  vm::RunOptions once;
  once.iterations = 1;
  time_on_copy(state, f, [&](vm::InterfaceMesh& mesh) { pipeline.run(mesh, f.scene.field.get(), once); });
}

#define VM_BENCH(fn)                                                                                           \
  BENCHMARK_CAPTURE(fn, voronoi7_44, &kVoronoi7)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime(); \
  BENCHMARK_CAPTURE(fn, four_spheres_128, &kFourSpheres)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()

VM_BENCH(BM_sample);
VM_BENCH(BM_create);
VM_BENCH(BM_smooth);
VM_BENCH(BM_project);
VM_BENCH(BM_clamp);
VM_BENCH(BM_guarded_commit);
VM_BENCH(BM_unguarded_commit);
VM_BENCH(BM_flip);
VM_BENCH(BM_quality_summary);
VM_BENCH(BM_iteration);

} // namespace

BENCHMARK_MAIN();
