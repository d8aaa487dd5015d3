// End-to-end benchmark of one input, grid and thread count per run (so peak
// memory is measured per configuration): load and sample the input, create the
// initial mesh (paper sect. 4.1), then 50 iterations of the paper's pipeline
// (smooth, project, clamp, flip; sect. 4.2-4.3) with the crossing guard.
//
//   bench_mesh INPUT GRID THREADS [--no-guard] [--iterations N] [--voxels-per-cell F]
//              [--check-crossings-every N]
//   bench_mesh --header
//
// INPUT is anything vm::load_input reads (scene JSON, label volume, labelled
// point cloud); GRID sets the cells per axis (0 keeps the input's grid);
// --no-guard commits moves without the crossing guard, to measure its cost.
// --iterations N runs N instead of 50 (the largest cases; columns for iterations
// not reached show "–"); --voxels-per-cell F meshes a label volume on a grid of
// about F voxels per cell (voronoimesh mesh --voxels-per-cell).
// Prints one Markdown table row (--header: the table's header and separator
// lines, so scripts and tests never restate the columns). Create is the best
// of up to 5 runs within about a second; everything else is measured once.
// The last column hashes the final mesh, so rows for 1 and 2 threads show
// whether the output is identical.

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/improve/pipeline.hpp"

#include <sys/resource.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

constexpr int kIterations = 50;     // the targets are for 20 and 50 iterations
constexpr int kEarlyIterations = 20;

constexpr const char* kHeader =
    "| scene | grid | threads | phases | tets visited | triangles | load s | sampling s | create ms | ms/it. | "
    "smooth ms | project ms | clamp+commit ms | flip ms | 20 it. s | 50 it. s | peak RSS MiB | "
    "min q 20 | mean q 20 | min q 50 | mean q 50 | hash |";

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// FNV-1a over the bytes of a trivially copyable array.
template <class T> void hash_bytes(uint64_t& h, const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  for (size_t i = 0; i < v.size() * sizeof(T); ++i) h = (h ^ p[i]) * 1099511628211ull;
}

/// Hash of the node positions (their bits), triangles and phase pairs.
uint32_t mesh_hash(const vm::NodeMesh& m) {
  uint64_t h = 14695981039346656037ull;
  hash_bytes(h, m.points);
  hash_bytes(h, m.triangles);
  hash_bytes(h, m.pairs);
  return uint32_t(h ^ (h >> 32));
}

std::string grid_text(const std::array<int, 3>& c) {
  if (c[0] == c[1] && c[1] == c[2]) return std::to_string(c[0]) + "^3";
  return std::to_string(c[0]) + "x" + std::to_string(c[1]) + "x" + std::to_string(c[2]);
}

/// Quality and time after one iteration of the run, as the observer sees it.
struct Progress {
  double seconds = 0;   ///< all iterations so far
  double min_q = 0, mean_q = 0;
};

/// What the command line asks for beyond INPUT GRID THREADS.
struct Options {
  bool guard = true;
  int check_crossings_every = 1; ///< vm::RunOptions::check_crossings_every
  int iterations = kIterations; ///< fewer for the largest cases: the 50-iteration columns stay empty
  vm::InputOptions input;       ///< --voxels-per-cell for label volumes
};

/// A time or quality column, or "–" when the run stopped before that iteration.
std::string cell(bool reached, double value, const char* format) {
  if (!reached) return "–";
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

int run(const std::string& path, int grid, int threads, const Options& o) {
  const bool guard = o.guard;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  auto t0 = std::chrono::steady_clock::now();
  vm::Scene scene = vm::load_input(path, o.input);
  const double load = seconds_since(t0);
  if (grid > 0) scene.grid.cells = {grid, grid, grid};

  vm::CreateParams params;
  vm::CreateStats stats;
  vm::NodeMesh initial;
  double sampling = 0, create = 0;
  {
    // As the CLI does: create samples the field itself, holding values near interfaces only.
    const vm::GridSpec lattice_grid = vm::grid_for_lattice(scene.grid, params.lattice);
    double spent = 0;
    for (int r = 0; r < 5 && spent < 1.0; ++r) {
      stats = vm::create_initial_mesh(*scene.field, lattice_grid, 4, params, initial);
      sampling = r == 0 ? stats.sampling_seconds : std::min(sampling, stats.sampling_seconds);
      create = r == 0 ? stats.seconds : std::min(create, stats.seconds);
      spent += stats.sampling_seconds + stats.seconds;
    }
  }
  const size_t triangles = initial.num_triangles();
  vm::InterfaceMesh mesh = vm::InterfaceMesh::from_node_mesh(initial);
  initial = {};

  const vm::Pipeline pipeline = vm::Pipeline::parse(vm::kDefaultPipeline, vm::builtin_registry());
  std::vector<double> per_pass(pipeline.steps().size(), 0.0);
  Progress now, early;
  vm::RunOptions options;
  options.iterations = o.iterations;
  options.guard_crossings = guard;
  options.check_crossings_every = o.check_crossings_every;
  options.observer = [&](const vm::IterationReport& r, const vm::InterfaceMesh&) {
    now.seconds += r.seconds;
    now.min_q = r.min_quality, now.mean_q = r.mean_quality;
    for (size_t i = 0; i < r.pass_seconds.size(); ++i) per_pass[i] += r.pass_seconds[i];
    if (r.iteration == kEarlyIterations) early = now;
  };
  pipeline.run(mesh, scene.field.get(), options);

  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const std::string name = std::filesystem::path(path).stem().string() + (guard ? "" : ", no guard");
  std::printf("| %s | %s | %d | %d | %llu | %zu | %.2f | %.2f | %.1f | %.2f |", name.c_str(),
              grid_text(scene.grid.cells).c_str(), threads, scene.field->num_phases(),
              (unsigned long long)stats.tets_visited, triangles, load, sampling, create * 1e3,
              now.seconds / o.iterations * 1e3);
  for (double p : per_pass) std::printf(" %.2f |", p / o.iterations * 1e3);
  const bool early_reached = o.iterations >= kEarlyIterations, all_reached = o.iterations >= kIterations;
  std::printf(" %s | %s | %.0f | %s | %s | %s | %s | %08x |\n", cell(early_reached, early.seconds, "%.3f").c_str(),
              cell(all_reached, now.seconds, "%.3f").c_str(), usage.ru_maxrss / 1024.0,
              cell(early_reached, early.min_q, "%.3f").c_str(), cell(early_reached, early.mean_q, "%.3f").c_str(),
              cell(all_reached, now.min_q, "%.3f").c_str(), cell(all_reached, now.mean_q, "%.3f").c_str(),
              mesh_hash(mesh.to_node_mesh()));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--header") == 0) {
    std::string separator = "|";
    for (size_t i = 1; kHeader[i]; ++i)
      if (kHeader[i] == '|') separator += "---|";
    std::printf("%s\n%s\n", kHeader, separator.c_str());
    return 0;
  }
  const char* const usage =
      "usage: bench_mesh INPUT GRID THREADS [--no-guard] [--iterations N] [--voxels-per-cell F]\n"
      "                  [--check-crossings-every N]\n"
      "       bench_mesh --header\n";
  if (argc < 4) {
    std::fputs(usage, stderr);
    return 2;
  }
  Options o;
  for (int i = 4; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--no-guard") o.guard = false;
    else if (flag == "--iterations" && i + 1 < argc) o.iterations = std::atoi(argv[++i]);
    else if (flag == "--voxels-per-cell" && i + 1 < argc) o.input.voxels_per_cell = std::atof(argv[++i]);
    else if (flag == "--check-crossings-every" && i + 1 < argc) o.check_crossings_every = std::atoi(argv[++i]);
    else {
      std::fputs(usage, stderr);
      return 2;
    }
  }
  const int grid = std::atoi(argv[2]), threads = std::atoi(argv[3]);
  if (grid < 0 || threads < 1 || o.iterations < 1) {
    std::fprintf(stderr, "bench_mesh: GRID must be 0 or more, THREADS and N 1 or more\n");
    return 2;
  }
  try {
    return run(argv[1], grid, threads, o);
  } catch (const vm::Error& e) {
    std::fprintf(stderr, "bench_mesh: %s\n", e.what());
    return 1;
  }
}
