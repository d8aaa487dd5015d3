// bench/label_agreement.cpp: how well a mesh of a label volume keeps its labels.
// Meshes the volume as `voronoimesh mesh --close` does (a closed domain, so that
// every phase is a closed volume and every voxel centre lies in exactly one), then
// locates every voxel centre in the mesh (check/locate.hpp) and prints one
// markdown row: triangles, min/mean quality, the share of voxel centres in
// their own label's phase (all; interior ones, whose 26 neighbours share their
// label; the worst label), labels missing from the mesh, and seconds.
//
// usage: label_agreement VOLUME [--voxels-per-cell F] [--pipeline P] [--iterations N] [--threads T] [--lattice bcc|cube6]
//                        [--voxel-faithful] [--snap S]
//        label_agreement --header

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <string>

namespace {

struct Options {
  vm::InputOptions input;
  std::string pipeline = vm::kLabelVolumePipeline; ///< the CLI's default for label volumes
  int iterations = 20;
  int threads = 2;
  std::optional<vm::Lattice> lattice; ///< none: the CLI's default (vm::lattice_for())
  double snap = vm::MeshOptions{}.snap;
};

int run(const std::string& path, const Options& o) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
  const auto t0 = std::chrono::steady_clock::now();
  const vm::Scene scene = vm::load_input(path, o.input);
  if (scene.phase_voxels.empty()) {
    std::fprintf(stderr, "label_agreement: %s: needs a label volume (one integer label per voxel)\n", path.c_str());
    return 2;
  }
  // The CLI's `mesh --close` (run/meshing.hpp): a mesh made any other way
  // would be measured in place of the one users get.
  vm::MeshOptions options;
  options.close = true;
  options.lattice = o.lattice;
  options.snap = o.snap;
  options.pipeline = o.pipeline;
  options.iterations = o.iterations;
  options.threads = o.threads;
  const vm::NodeMesh m = vm::mesh_scene(scene, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const vm::LabelAgreement a = *vm::label_agreement_from_input(m, scene, path, o.input); // m is closed
  const vm::LabelAgreement::Label* worst = a.worst();
  std::string missing;
  for (int32_t label : a.lost()) missing += (missing.empty() ? "" : " ") + std::to_string(label);
  const vm::MeshStats stats = vm::compute_stats(m);
  char per_cell[32] = "default";
  if (o.input.voxels_per_cell > 0) std::snprintf(per_cell, sizeof per_cell, "%g", o.input.voxels_per_cell);
  std::printf("| %s | %s | %s | %zu | %.3f | %.3f | %.3f | %.3f | %.2f (label %d, %lld voxels) | %s | %lld | %.1f |\n",
              path.c_str(), o.pipeline.c_str(), per_cell, m.num_triangles(), stats.min_quality,
              stats.mean_quality, 100.0 * double(a.in_phase) / double(a.voxels),
              100.0 * double(a.interior_in_phase) / double(a.interior),
              worst ? 100.0 * double(worst->in_phase) / double(worst->voxels) : 100.0, worst ? worst->label : 0,
              (long long)(worst ? worst->voxels : 0),
              missing.empty() ? "none" : missing.c_str(), (long long)a.undecided, seconds);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--header") == 0) {
    std::printf("| volume | pipeline | voxels per cell | triangles (closed) | min q | mean q | voxel centres in their "
                "label %% | interior %% | worst label %% | labels lost | undecided | seconds |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    return 0;
  }
  if (argc < 2) {
    std::fputs("usage: label_agreement VOLUME [--voxels-per-cell F] [--pipeline P] [--iterations N] [--threads T]\n"
               "                       [--lattice bcc|cube6] [--voxel-faithful] [--snap S]\n"
               "       label_agreement --header\n",
               stderr);
    return 2;
  }
  Options o;
  for (int i = 2; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--voxels-per-cell" && i + 1 < argc) o.input.voxels_per_cell = std::atof(argv[++i]);
    else if (flag == "--pipeline" && i + 1 < argc) o.pipeline = argv[++i];
    else if (flag == "--iterations" && i + 1 < argc) o.iterations = std::atoi(argv[++i]);
    else if (flag == "--threads" && i + 1 < argc) o.threads = std::atoi(argv[++i]);
    else if (flag == "--voxel-faithful") o.input.voxel_faithful = true;
    else if (flag == "--snap" && i + 1 < argc) o.snap = std::atof(argv[++i]);
    else if (flag == "--lattice" && i + 1 < argc) o.lattice = std::strcmp(argv[++i], "cube6") == 0 ? vm::Lattice::cube6 : vm::Lattice::bcc;
    else {
      std::fprintf(stderr, "label_agreement: unknown option '%s'\n", flag.c_str());
      return 2;
    }
  }
  try {
    return run(argv[1], o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "label_agreement: %s\n", e.what());
    return 1;
  }
}
