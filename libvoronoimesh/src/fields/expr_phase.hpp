#pragma once
/// @file expr_phase.hpp
/// A phase given by a formula in x, y, z, evaluated with muparser.

#include "fields/phase_function.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vm::detail {

/// A formula muparser refused; the message names the formula and the reason.
class ExprError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// What an expression phase is made of.
struct ExprSpec {
  std::string value;                 ///< phi(x, y, z)
  std::vector<std::string> gradient; ///< empty, or the three components of grad phi
  /// Named numbers the formulas may use besides x, y, z (and "pi").
  std::vector<std::pair<std::string, double>> constants;
  /// Central-difference step used when `gradient` is empty.
  double step = 1e-6;
};

/// phi(x) = a muparser formula. A mu::Parser keeps its evaluation stack inside
/// itself and reads x, y, z from variables bound by address, so one parser cannot
/// serve two threads; each thread that evaluates gets its own compiled copy,
/// created on first use and owned by this object (no global cache to go stale).
class ExprPhase final : public PhaseFunction {
public:
  /// Compiles every formula once to report mistakes now rather than mid-sampling.
  /// Throws ExprError naming the formula ("expr" or "gradient[i]") and the problem.
  explicit ExprPhase(ExprSpec spec);
  ~ExprPhase() override;
  ExprPhase(const ExprPhase&) = delete;
  ExprPhase& operator=(const ExprPhase&) = delete;

  double value(const Vec3& x) const override;
  /// The "gradient" formulas if given, else central differences of step `spec.step`.
  Vec3 gradient(const Vec3& x) const override;

private:
  struct Evaluator;
  std::unique_ptr<Evaluator> make_evaluator() const;

  ExprSpec spec_;
  mutable tbb::enumerable_thread_specific<std::unique_ptr<Evaluator>> evaluators_;
};

} // namespace vm::detail
