#pragma once
/// @file improve/crossing_windows.hpp
/// Windows of iterations whose crossings are looked for together, at the
/// window's end (RunOptions::check_crossings_every): when to open one, what it
/// keeps to run its iterations again, checked, and putting that back when the
/// check at its end finds a crossing. For Pipeline::run, whose loop state
/// (RunState) a window keeps with the mesh.

#include "improve/convergence.hpp"

#include "voronoimesh/improve/guard.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <algorithm>
#include <optional>

namespace vm::detail {

/// What Pipeline::run carries from one iteration to the next besides the mesh.
struct RunState {
  Convergence convergence;
  double worst_now = 0; ///< min q of the mesh now, the next iteration's quality floor
  int done = 0;         ///< iterations done
};

class CrossingWindows {
public:
  /// Windows of `every` iterations (1 or less: none, every iteration checked).
  explicit CrossingWindows(int every) : length_(std::max(1, every)) {}

  /// Before iteration `it`: opens a window there, keeping `mesh` and `state`,
  /// once enough checked iterations in a row found no crossing (kQuietIterations,
  /// twice as many after each window that ended crossed); tells the guard
  /// whether this iteration's crossings are deferred.
  void before(int it, const InterfaceMesh& mesh, const RunState& state, CrossingGuard& guard) {
    if (length_ > 1 && !open_ && quiet_ >= quiet_needed_) open_.emplace(Start{it, mesh, state});
    guard.defer_crossings(open_.has_value());
    crossed_before_ = guard.checks_that_crossed();
  }

  /// The iteration running now is in an open window.
  bool is_open() const { return open_.has_value(); }

  /// After iteration `it`, run until `last`: counts it among the quiet checked
  /// iterations if it was checked and its guard found no crossing; returns
  /// whether it ends the open window.
  bool after(int it, int last, const CrossingGuard& guard) {
    if (!open_) {
      quiet_ = guard.checks_that_crossed() == crossed_before_ ? quiet_ + 1 : 0;
      return false;
    }
    return it - open_->iteration + 1 == length_ || it >= last;
  }

  /// Ends the open window. When its check found a `crossing`, the mesh and
  /// `state` go back to the window's start and `it` to the iteration before it,
  /// so that the loop runs its iterations again, checked.
  void close(bool crossing, int& it, InterfaceMesh& mesh, RunState& state, CrossingGuard& guard) {
    if (crossing) {
      quiet_ = 0;
      quiet_needed_ *= 2;
      it = open_->iteration - 1;
      mesh = std::move(open_->mesh);
      guard.forget_meshes(); // its index follows the mesh the window left
      state = open_->state;
    }
    open_.reset();
    guard.defer_crossings(false);
  }

private:
  /// The first window opens after this many iterations in a row in which the
  /// guard, checking each, found no crossing; after each window that ends
  /// crossed, twice as many: on meshes where crossings keep coming (label
  /// volumes' thin structures), windows would mostly be run twice.
  static constexpr int kQuietIterations = 2;
  struct Start {
    int iteration; ///< the window's first
    InterfaceMesh mesh;
    RunState state;
  };
  int length_;
  std::optional<Start> open_;
  int quiet_ = 0;
  int quiet_needed_ = kQuietIterations;
  size_t crossed_before_ = 0; ///< the guard's checks_that_crossed() before this iteration
};

} // namespace vm::detail
