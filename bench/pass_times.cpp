// Where an improvement run's time goes, iteration by iteration and pass by
// pass, on any input and with the pipeline `voronoimesh mesh` would take for it
// (a scene's remesh first, a label volume's coarser remesh, ...): what
// bench_mesh, which times the paper's pipeline on the bench table's cases,
// cannot show.
//
//   pass_times INPUT [--grid N] [--threads T] [--iterations N] [--pipeline P] [--no-guard]
//              [--voxels-per-cell F] [--voxel-faithful] [--close] [--stop-when-converged | --all-iterations]
//
// Reads INPUT and creates its mesh as `voronoimesh mesh` does, then prints a
// Markdown table: one row per iteration (triangles after it, its seconds, each
// pass's seconds, min and mean q) and a row of the sums. The commit of moves
// and its crossing guard are charged to clamp, as in bench_mesh.

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr const char* kUsage =
    "usage: pass_times INPUT [--grid N] [--threads T] [--iterations N] [--pipeline P] [--no-guard]\n"
    "                  [--voxels-per-cell F] [--voxel-faithful] [--close] [--stop-when-converged | --all-iterations]\n";

/// Prints each iteration's row as it ends, and keeps the sums.
class PassTimes : public vm::RunObserver {
public:
  void iteration(const vm::IterationReport& r, const vm::InterfaceMesh& mesh) override {
    if (r.iteration == 0) return; // the initial mesh's summary
    std::printf("| %d | %zu | %.3f |", r.iteration, mesh.num_triangles(), r.seconds);
    sums_.resize(std::max(sums_.size(), r.pass_seconds.size()), 0.0);
    for (size_t p = 0; p < r.pass_seconds.size(); ++p) {
      std::printf(" %.3f |", r.pass_seconds[p]);
      sums_[p] += r.pass_seconds[p];
    }
    std::printf(" %.3f | %.4f |\n", r.min_quality, r.mean_quality);
    total_ += r.seconds;
    std::fflush(stdout);
  }
  void print_sums() const {
    std::printf("| all | | %.3f |", total_);
    for (double s : sums_) std::printf(" %.3f |", s);
    std::printf(" | |\n");
  }

private:
  std::vector<double> sums_;
  double total_ = 0;
};

/// The integer after option `name`, or exit 2 with the usage.
int positive(const char* name, const char* text) {
  char* end = nullptr;
  const long value = text ? std::strtol(text, &end, 10) : 0;
  if (!text || *end != '\0' || value < 1 || value > 1 << 20) {
    std::fprintf(stderr, "pass_times: %s needs a positive integer, got '%s'\n%s", name, text ? text : "", kUsage);
    std::exit(2);
  }
  return int(value);
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const std::string input = argv[1];
  vm::MeshOptions options;
  vm::InputOptions input_options; // a label volume's, as voronoimesh's options of the same names
  int threads = 0;
  std::string pipeline;
  for (int a = 2; a < argc; ++a) {
    const std::string arg = argv[a];
    const char* value = a + 1 < argc ? argv[a + 1] : nullptr;
    if (arg == "--grid") {
      const int n = positive("--grid", value);
      options.grid = std::array<int, 3>{n, n, n}, ++a;
    } else if (arg == "--threads") {
      threads = positive("--threads", value), ++a;
    } else if (arg == "--iterations") {
      options.iterations = positive("--iterations", value), ++a;
    } else if (arg == "--pipeline") {
      if (!value) {
        std::fprintf(stderr, "pass_times: --pipeline needs a pipeline, e.g. smooth,project,clamp,flip\n%s", kUsage);
        return 2;
      }
      pipeline = value, ++a;
    } else if (arg == "--stop-when-converged" || arg == "--all-iterations") {
      options.stop_when_converged = arg == "--stop-when-converged";
    } else if (arg == "--no-guard") {
      options.guard_crossings = false;
    } else if (arg == "--voxel-faithful") {
      input_options.voxel_faithful = true;
    } else if (arg == "--close") {
      options.close = true;
    } else if (arg == "--voxels-per-cell") {
      char* end = nullptr;
      const double f = value ? std::strtod(value, &end) : 0;
      if (!value || *end != '\0' || !(f >= 1 && f <= 64)) {
        std::fprintf(stderr, "pass_times: --voxels-per-cell needs a number in [1, 64], got '%s'\n%s",
                     value ? value : "", kUsage);
        return 2;
      }
      input_options.voxels_per_cell = f, ++a;
    } else {
      std::fprintf(stderr, "pass_times: unknown option '%s'\n%s", arg.c_str(), kUsage);
      return 2;
    }
  }
  // One limit for the whole run: create_mesh() and improve_mesh() would take
  // MeshOptions::threads, but reading and building the phase functions would not.
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  try {
    const vm::Scene scene = vm::read_input(input, input_options);
    options.pipeline = pipeline;
    options = vm::options_for_scene(options, scene);
    vm::NodeMesh mesh = vm::create_mesh(scene, options);
    std::printf("%s: %zu triangles created; %s%d iterations of %s%s\n\n", input.c_str(), mesh.num_triangles(),
                *options.stop_when_converged ? "until converged, at most " : "", options.iterations,
                options.pipeline.c_str(), options.guard_crossings ? "" : " without the guard");
    const vm::Pipeline parsed = vm::Pipeline::parse(options.pipeline, vm::builtin_registry());
    std::string header = "| iteration | triangles | s |", rule = "|---|---|---|";
    for (const auto& step : parsed.steps()) header += " " + step.info.name + " s |", rule += "---|";
    std::printf("%s min q | mean q |\n%s---|---|\n", header.c_str(), rule.c_str());
    PassTimes times;
    vm::improve_mesh(mesh, scene.field, options, &times);
    times.print_sums();
  } catch (const vm::Error& e) {
    std::fprintf(stderr, "pass_times: %s\n", e.what());
    return 1;
  }
  return 0;
}
