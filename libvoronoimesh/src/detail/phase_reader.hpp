#pragma once
/// @file phase_reader.hpp
/// Builds a phase function from one entry of a scene's "phases" list
/// (format: docs/scenes.md).

#include "detail/json_object.hpp"
#include "detail/phase_function.hpp"

#include <memory>

namespace vm::detail {

/// The phase function `phase` describes, by its "kind". `domain` sets the
/// central-difference step of expressions. Throws InvalidInput on any mistake,
/// including keys the kind does not know ("name" and "kind" are always allowed).
std::unique_ptr<const PhaseFunction> read_phase(const JsonObject& phase, const Box& domain);

} // namespace vm::detail
