#pragma once
// python/src/observer.hpp: a run watched from Python: progress lines to a
// callback, Ctrl-C (or an exception in the callback) stops the run at its next
// check, and the Python error is raised once the library has unwound.

#include <voronoimesh/voronoimesh.hpp>

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

namespace vmpy {

class Observer : public vm::RunObserver {
public:
  /// `progress`: None, or a callable taking (stage, message); iterations are
  /// "k of n", n the run's last as it knows it (vm::IterationReport::last_iteration).
  explicit Observer(pybind11::object progress);
  ~Observer() override;

  void stage(vm::Stage stage, const std::string& what) override;
  void created(const vm::CreateReport& report) override;
  void iteration(const vm::IterationReport& report, const vm::InterfaceMesh& mesh) override;
  void note(const std::string& line) override;
  /// Holds the GIL for a moment: a pending signal (Ctrl-C) stops the run.
  bool stop_requested() override;

  /// Raises the Python error that stopped the run (KeyboardInterrupt, or what
  /// the callback raised), if any.
  void rethrow();

private:
  void call(const char* stage, const std::string& message);

  pybind11::object progress_;
  std::optional<pybind11::error_already_set> error_;
};

} // namespace vmpy
