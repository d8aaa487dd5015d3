#include "fields/phase_function.hpp"

#include <cassert>

namespace vm::detail {

void CompositeField::add(std::string name, std::unique_ptr<const PhaseFunction> phase) {
  names_.push_back(std::move(name));
  phases_.push_back(std::move(phase));
}

void CompositeField::values(const Vec3& x, std::span<double> out) const {
  assert(out.size() == phases_.size());
  for (size_t i = 0; i < phases_.size(); ++i) out[i] = phases_[i]->value(x);
}

} // namespace vm::detail
