#pragma once
/// @file report.hpp
/// How the tool tells the user what a run does (a vm::RunObserver): on a
/// terminal, a status line overwritten stage by stage and iteration by
/// iteration; unless quiet, one summary line per stage on stderr. Ctrl-C
/// (interrupt.hpp) asks the run to stop.

#include "voronoimesh/run/meshing.hpp"

#include <string>

namespace vmcli {

/// What the improve line ends with when a run stopped once its quality converged.
inline constexpr const char* kConvergedRemark = "; quality converged (--all-iterations runs every one)";

class Report : public vm::RunObserver {
public:
  /// `quiet`: print no summaries (errors are the caller's); `output`: the -o
  /// path, to name the files written beside it; `tell_input`: a line on the
  /// input read. The status line counts to the run's last iteration as the
  /// run knows it (vm::IterationReport::last_iteration).
  Report(bool quiet, std::string output, bool tell_input = true);

  void stage(vm::Stage stage, const std::string& what) override;
  void input_read(const std::string& path, const vm::Scene& scene, double seconds) override;
  void created(const vm::CreateReport& report) override;
  void iteration(const vm::IterationReport& report, const vm::InterfaceMesh& mesh) override;
  void improved(const vm::ImproveReport& report) override;
  void written(const std::vector<std::string>& mesh_files, const std::vector<std::string>& phase_files) override;
  void note(const std::string& line) override;
  bool stop_requested() override;

  /// Prints `line` unless quiet, after clearing the status line.
  void say(const std::string& line);

private:
  void status(const std::string& text);

  bool quiet_, terminal_, tell_input_;
  std::string output_;
};

} // namespace vmcli
