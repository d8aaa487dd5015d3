#pragma once
/// @file phase_function.hpp
/// One closed-form phase function, and the PhaseField made of a list of them.

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/core/types.hpp"
#include "voronoimesh/fields/phase_field.hpp"

#include <memory>
#include <string>
#include <vector>

namespace vm::detail {

/// phi(x) of a single phase. Implementations must be safe to call from several
/// threads at once, since CompositeField forwards to them.
class PhaseFunction {
public:
  virtual ~PhaseFunction() = default;
  virtual double value(const Vec3& x) const = 0;
  virtual Vec3 gradient(const Vec3& x) const = 0;
};

/// A PhaseField whose phases are independent PhaseFunctions (the scene kinds).
class CompositeField final : public PhaseField {
public:
  /// `source` names where the phases are given (the scene's file) in messages.
  explicit CompositeField(std::string source) : source_(std::move(source)) {}
  void add(std::string name, std::unique_ptr<const PhaseFunction> phase);

  int num_phases() const override { return int(phases_.size()); }
  std::string phase_name(int i) const override { return names_.at(size_t(i)); }
  /// "<source>: phase <name>".
  std::string describe_phase(int i) const override { return located(source_, "phase " + phase_name(i)); }
  void values(const Vec3& x, std::span<double> out) const override;
  double value(int i, const Vec3& x) const override { return phases_[size_t(i)]->value(x); }
  Vec3 gradient(int i, const Vec3& x) const override { return phases_[size_t(i)]->gradient(x); }

private:
  std::string source_;
  std::vector<std::string> names_;
  std::vector<std::unique_ptr<const PhaseFunction>> phases_;
};

} // namespace vm::detail
