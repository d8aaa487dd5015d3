// python/src/observer.cpp: see observer.hpp.

#include "observer.hpp"

#include <cstdio>

namespace py = pybind11;

namespace vmpy {

namespace {

const char* stage_name(vm::Stage s) {
  switch (s) {
  case vm::Stage::read: return "read";
  case vm::Stage::sample: return "sample";
  case vm::Stage::create: return "create";
  case vm::Stage::improve: return "improve";
  default: return "write";
  }
}

} // namespace

Observer::Observer(py::object progress) : progress_(std::move(progress)) {}

Observer::~Observer() {
  py::gil_scoped_acquire held; // the callback and a held error are Python objects
  progress_ = py::object();
  error_.reset();
}

void Observer::call(const char* stage, const std::string& message) {
  py::gil_scoped_acquire held;
  if (error_ || !progress_ || progress_.is_none()) return;
  try {
    progress_(stage, message);
  } catch (py::error_already_set& e) {
    error_.emplace(std::move(e)); // raised once the run has stopped
  }
}

void Observer::stage(vm::Stage stage, const std::string& what) { call(stage_name(stage), what); }

void Observer::created(const vm::CreateReport& r) {
  call("create", std::to_string(r.nodes) + " vertices, " + std::to_string(r.triangles) + " triangles");
}

void Observer::iteration(const vm::IterationReport& r, const vm::InterfaceMesh&) {
  if (r.iteration == 0) return;
  char line[128];
  std::snprintf(line, sizeof line, "iteration %d of %d: min q %.3f, mean q %.3f", r.iteration, r.last_iteration,
                r.min_quality, r.mean_quality);
  call("improve", line);
}

void Observer::note(const std::string& line) { call("note", line); }

bool Observer::stop_requested() {
  py::gil_scoped_acquire held;
  if (!error_ && PyErr_CheckSignals() != 0) error_.emplace(); // fetches the KeyboardInterrupt
  return error_.has_value();
}

void Observer::rethrow() {
  if (!error_) return;
  py::error_already_set e = std::move(*error_);
  error_.reset();
  throw e;
}

} // namespace vmpy
