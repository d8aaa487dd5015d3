#pragma once
/// @file report.hpp
/// How the tool tells the user what a run does (a vm::RunObserver): on a
/// terminal, a status line overwritten stage by stage and iteration by
/// iteration; unless quiet, one summary line per stage on stderr. Ctrl-C
/// (interrupt.hpp) asks the run to stop.

#include "voronoimesh/run/meshing.hpp"

#include <string>

namespace vmcli {

class Report : public vm::RunObserver {
public:
  /// `quiet`: print no summaries (errors are the caller's); `iterations`: how
  /// many the status line counts to; `output`: the -o path, to name the files
  /// written beside it; `tell_input`: a line on the input read.
  Report(bool quiet, int iterations, std::string output, bool tell_input = true);

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
  int iterations_;
  std::string output_;
};

} // namespace vmcli
