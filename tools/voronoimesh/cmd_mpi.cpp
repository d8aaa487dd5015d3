/// @file cmd_mpi.cpp
/// `voronoimesh mesh --mpi` and `create --mpi`: every rank runs this; the
/// library's distributed run (vm::mpi::run_job()) agrees on failures, so no
/// rank waits for one that gave up, and every rank exits with the same code.

#include "commands.hpp"
#include "report.hpp"

#include "voronoimesh/mpi/distributed.hpp"

#include <algorithm>
#include <cstdio>

namespace vmcli {

namespace {

/// Report with the distributed run's own summaries.
class DistributedReport : public vm::mpi::RunObserver {
public:
  DistributedReport(bool quiet, int iterations, const std::string& output)
      : report_(quiet, output), quiet_(quiet), iterations_(iterations) {}

  void stage(vm::Stage stage, const std::string& what) override { report_.stage(stage, what); }
  void input_read(const std::string& path, const vm::Scene& scene, double seconds) override {
    report_.input_read(path, scene, seconds);
  }
  void iteration(const vm::IterationReport& r, const vm::InterfaceMesh& mesh) override { report_.iteration(r, mesh); }
  void improved(const vm::ImproveReport& r) override { report_.improved(r); }
  void written(const std::vector<std::string>& mesh_files, const std::vector<std::string>& phase_files) override {
    report_.written(mesh_files, phase_files);
  }
  void note(const std::string& line) override { report_.note(line); }
  bool stop_requested() override { return report_.stop_requested(); }

  void created_part(const vm::mpi::MeshPart& part, const vm::mpi::DistributedStats& s) override {
    if (quiet_) return;
    const auto [least, most] = std::minmax_element(s.interface_tets.begin(), s.interface_tets.end());
    uint64_t total = 0;
    for (uint64_t t : s.interface_tets) total += t;
    const double mean = double(total) / double(s.interface_tets.size());
    char line[400];
    std::snprintf(line, sizeof line,
                  "create (mpi, %zu ranks): %lld vertices, %lld triangles; create %.3f s (slowest rank); rank 0: "
                  "%.3f s, %.0f%% in MPI; interface tetrahedra per rank %llu..%llu (max/mean %.2f)",
                  s.interface_tets.size(), (long long)part.global_nodes, (long long)part.global_triangles,
                  s.create.seconds, s.seconds, s.seconds > 0 ? 100 * s.mpi_seconds / s.seconds : 0.0,
                  (unsigned long long)*least, (unsigned long long)*most, mean > 0 ? double(*most) / mean : 1.0);
    report_.say(line);
  }
  void improved_parts(int iterations, const std::string& pipeline, const vm::mpi::DistributedStats& s) override {
    char line[320];
    std::snprintf(line, sizeof line, "improve (mpi): %d iterations of %s; rank 0: %.3f s, %.0f%% in MPI%s", iterations,
                  pipeline.c_str(), s.seconds, s.seconds > 0 ? 100 * s.mpi_seconds / s.seconds : 0.0,
                  iterations < iterations_ ? kConvergedRemark : "");
    report_.say(line);
  }

private:
  Report report_;
  bool quiet_;
  int iterations_; ///< asked for: the most
};

} // namespace

int mesh_with_mpi(const MeshCommandOptions& o) {
  MPI_Init(nullptr, nullptr);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const bool quiet = o.common.quiet || rank != 0;
  const int code = run_guarded(
      [&] {
        vm::PassRegistry registry;
        vm::MeshJob job;
        vm::mpi::run_collectively(MPI_COMM_WORLD, [&] {
          registry = pass_registry(o.improve.plugins, quiet);
          job = creating_job(o, registry);
        });
        DistributedReport report(quiet, o.improve.iterations, o.output.path);
        vm::mpi::run_job(MPI_COMM_WORLD, job, &report);
        return kOk;
      },
      rank == 0);
  MPI_Finalize();
  return code;
}

} // namespace vmcli
