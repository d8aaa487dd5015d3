#pragma once
/// @file pipeline.hpp
/// An ordered list of configured passes repeated for a number of iterations
/// (paper Algorithm 1).

#include "voronoimesh/registry.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vm {

/// The paper's pipeline: smoothing, projection, clamping, then flipping.
inline constexpr const char* kDefaultPipeline = "smooth,project,clamp,flip";

/// What happened in one iteration, for progress lines and stopping rules.
struct IterationReport {
  int iteration = 0;          ///< 1-based
  double min_quality = 0;
  double mean_quality = 0;
  size_t flips = 0;
  size_t undone_moves = 0;    ///< node moves the crossing guard undid
  double seconds = 0;
  std::optional<MeshStats> stats; ///< when the pipeline has a stats pass
  /// Wall time of each step, in pipeline order; committing the moves is charged
  /// to the moving pass before it.
  std::vector<double> pass_seconds;
};

/// How Pipeline::run() iterates.
struct RunOptions {
  int iterations = 20;
  /// Stop early once neither the minimum nor the mean quality has improved by
  /// more than `tolerance` for `patience` iterations in a row.
  bool stop_when_converged = false;
  double tolerance = 1e-3;
  int patience = 3;
  /// Undo any move that would make two triangles intersect (guard.hpp). Off
  /// saves the exact intersection check of every iteration.
  bool guard_crossings = true;
  /// Called after every iteration (and with iteration 0 before the first).
  std::function<void(const IterationReport&, const InterfaceMesh&)> observer;
  /// Asked before every iteration: true ends the run there, leaving the mesh as
  /// the last complete iteration made it (the CLI's Ctrl-C).
  std::function<bool()> stop_requested;
};

/// Configured passes in order, parsed from a spec string and run for some iterations.
class Pipeline {
public:
  struct Step {
    PassInfo info; ///< a copy: the pipeline does not depend on the registry afterwards
    ParamValues params;
  };

  /// Parses "name,name:key=value:key=value,..." against `registry`. Throws
  /// InvalidInput naming the bad pass or parameter.
  static Pipeline parse(const std::string& spec, const PassRegistry& registry);

  /// The configured passes, in order.
  const std::vector<Step>& steps() const { return steps_; }
  /// True when some pass evaluates the phase functions (run() then needs a field).
  bool needs_field() const;
  /// "smooth(rest_factor=1.2), project(...), ..." with every parameter.
  std::string describe() const;

  /// Runs the pipeline on `mesh`. Throws InvalidInput if a pass needs the phase
  /// functions and `field` is null. Returns the number of iterations done.
  int run(InterfaceMesh& mesh, const PhaseField* field, const RunOptions& options) const;

private:
  std::vector<Step> steps_;
};

/// Minimum and mean triangle quality, summed in a fixed order.
std::pair<double, double> quality_summary(const InterfaceMesh& mesh);

} // namespace vm
