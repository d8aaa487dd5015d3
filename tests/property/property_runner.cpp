// The long tier of the property tests: runs cases [first, first + count) of a
// seed through check_case() (case_checks.hpp), one thread per process (run
// several processes for parallelism: scripts/property_tests.sh), and prints a
// line per failing case with the command that reproduces it.
//
//   property_runner [--seed S] [--first A] [--count N] [--iterations K]
//                   [--threads-every M] [--progress P] [--remesh SPEC] [--voxel-faithful]
//                   [--check-crossings-every N]
//   property_runner --seed S --case I --verbose     one case, with its scene

#include "case_checks.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

namespace {

using namespace vm::test;

struct Args {
  uint64_t seed = 1, first = 0, count = 100;
  int iterations = 3;
  uint64_t threads_every = 16; ///< 0: never compare thread counts
  uint64_t progress = 0;       ///< print a progress line every this many cases (0: never)
  bool verbose = false;
  std::string remesh; ///< a remesh pass spec run first in every iteration; empty: none
  bool voxel_faithful = false; ///< only the label cases, read voxel-faithful (random_case())
  uint64_t check_every = 1;    ///< CheckOptions::check_crossings_every
  bool whole = false;          ///< CheckOptions::whole
};

[[noreturn]] void usage(const char* problem) {
  std::fprintf(stderr, "property_runner: %s\nusage: property_runner [--seed S] [--first A] [--count N] "
                       "[--case I] [--iterations K] [--threads-every M] [--progress P] [--remesh SPEC] [--voxel-faithful]\n"
                       "       [--check-crossings-every N] [--whole] [--verbose]\n", problem);
  std::exit(2);
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--verbose") {
      a.verbose = true;
      continue;
    }
    if (arg == "--voxel-faithful") {
      a.voxel_faithful = true;
      continue;
    }
    if (arg == "--whole") {
      a.whole = true;
      continue;
    }
    if (arg == "--remesh" && i + 1 < argc) {
      a.remesh = argv[++i];
      continue;
    }
    if (i + 1 >= argc) usage(("missing value after " + arg).c_str());
    char* end = nullptr;
    const unsigned long long v = std::strtoull(argv[++i], &end, 10);
    if (*end != '\0' || argv[i][0] == '-') usage(("bad value for " + arg).c_str());
    if (arg == "--seed") a.seed = v;
    else if (arg == "--first") a.first = v;
    else if (arg == "--count") a.count = v;
    else if (arg == "--case") a.first = v, a.count = 1;
    else if (arg == "--iterations") a.iterations = int(v);
    else if (arg == "--threads-every") a.threads_every = v;
    else if (arg == "--progress") a.progress = v;
    else if (arg == "--check-crossings-every") a.check_every = v >= 1 ? v : (usage("--check-crossings-every: 1 or more"), 1);
    else usage(("unknown option " + arg).c_str());
  }
  return a;
}

} // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  uint64_t checked = 0, failed = 0, against_field = 0, against_triangles = 0, folds = 0;
  uint64_t windowed_cases = 0, windows_run_again = 0; // with --check-crossings-every
  std::string variant = a.voxel_faithful ? " --voxel-faithful" : "";
  if (a.check_every > 1) variant += " --check-crossings-every " + std::to_string(a.check_every);
  if (a.whole) variant += " --whole";
  if (a.check_every > 1 || a.whole) variant += " --iterations " + std::to_string(a.iterations);
  for (uint64_t index = a.first; index < a.first + a.count; ++index) {
    if (a.voxel_faithful && SceneKind(index % kSceneKinds) != SceneKind::labels) continue;
    ++checked;
    RandomCase c;
    try {
      c = random_case(a.seed, index, a.voxel_faithful);
    } catch (const std::exception& e) { // a generator bug: report it like a failing case
      ++failed;
      std::printf("FAIL seed %llu case %llu: the generator threw: %s\n", (unsigned long long)a.seed,
                  (unsigned long long)index, e.what());
      continue;
    }
    CheckOptions o;
    o.iterations = a.iterations;
    o.compare_threads = a.threads_every > 0 && index % a.threads_every == 0;
    o.remesh = a.remesh;
    o.check_crossings_every = int(a.check_every);
    o.whole = a.whole;
    if (a.verbose) {
      std::printf("%s\n", c.description().c_str());
      if (!c.scene_json.empty()) std::printf("scene:\n%s\n", c.scene_json.c_str());
    }
    const CaseResult r = check_case(c, o);
    against_field += r.against_field > 0;
    against_triangles += r.against_field;
    folds += r.folds;
    windowed_cases += r.windows_run_again > 0;
    windows_run_again += r.windows_run_again;
    if (a.verbose) std::printf("%zu triangles created\n", r.triangles);
    if (!r.ok()) {
      ++failed;
      std::printf("FAIL seed %llu case %llu (%s): %s\n  reproduce: property_runner --seed %llu --case %llu%s --verbose\n",
                  (unsigned long long)a.seed, (unsigned long long)index, scene_kind_name(c.kind),
                  r.failures.front().c_str(), (unsigned long long)a.seed, (unsigned long long)index, variant.c_str());
    }
    if (a.progress > 0 && (index - a.first + 1) % a.progress == 0) {
      std::fprintf(stderr, "progress %llu %llu\n", (unsigned long long)(index - a.first + 1),
                   (unsigned long long)failed);
    }
    std::fflush(stdout);
  }
  std::printf("checked %llu cases, %llu failed, %llu with %llu triangles against their pair's direction, "
              "%llu surface edges folding",
              (unsigned long long)checked, (unsigned long long)failed, (unsigned long long)against_field,
              (unsigned long long)against_triangles, (unsigned long long)folds);
  if (a.check_every > 1)
    std::printf(", %llu windows run again in %llu cases", (unsigned long long)windows_run_again,
                (unsigned long long)windowed_cases);
  std::printf("\n");
  return failed ? 1 : 0;
}
