#pragma once
/// @file improve/convergence.hpp
/// When a run whose quality stopped improving ends (RunOptions::stop_when_converged),
/// for the one-process loop (Pipeline::run) and the distributed one
/// (mpi::improve_part) alike, so that both stop after the same iteration.

#include "voronoimesh/improve/pipeline.hpp"

#include <algorithm>

namespace vm::detail {

class Convergence {
public:
  /// `min_q` and `mean_q`: the mesh's before the first iteration; iterations
  /// before `settled_from` (Pipeline::settled_from()) never count as stalled.
  Convergence(const RunOptions& options, double min_q, double mean_q, int settled_from)
      : options_(&options), best_min_(min_q), best_mean_(mean_q), settled_from_(settled_from), last_(options.iterations) {}

  /// After each iteration, its mesh's quality: an iteration from `settled_from`
  /// on that raised neither the best minimum by more than RunOptions::tolerance
  /// nor the best mean by more than RunOptions::mean_tolerance stalled; after
  /// RunOptions::patience stalled ones in a row, the next iteration is the last.
  /// (Before the passes' schedules settle, a stall says nothing: on a 2x2x2
  /// label volume the remesh calls of iterations 2 and 3 stalled, the run
  /// stopped after 4 at min q 0.562 and never polished, which gives 0.698.)
  void after(int iteration, double min_q, double mean_q) {
    const bool improved = min_q > best_min_ + options_->tolerance || mean_q > best_mean_ + options_->mean_tolerance;
    best_min_ = std::max(best_min_, min_q);
    best_mean_ = std::max(best_mean_, mean_q);
    stalled_ = improved || iteration < settled_from_ ? 0 : stalled_ + 1;
    if (options_->stop_when_converged && stalled_ >= options_->patience) last_ = std::min(last_, iteration + 1);
  }

  /// The run's last iteration, as known now (RunOptions::iterations until it converges).
  int last() const { return last_; }

private:
  const RunOptions* options_; // a pointer: the pipeline copies the state to run iterations again
  double best_min_, best_mean_;
  int settled_from_;
  int stalled_ = 0;
  int last_;
};

} // namespace vm::detail
