#pragma once
/// @file phase_reader.hpp
/// Builds a phase function from one entry of a scene's "phases" list
/// (format: docs/scenes.md).

#include "core/json_object.hpp"
#include "fields/grid_phases.hpp"
#include "fields/phase_function.hpp"

#include <memory>

namespace vm::detail {

/// What a phase may need beyond its own keys.
struct PhaseContext {
  Box domain;             ///< the scene's domain: sets the central-difference step of expressions
  const GridFiles& grids; ///< the files of the scene's "grid" phases, already read
};

/// The phase function `phase` describes, by its "kind". Throws InvalidInput on
/// any mistake, including keys the kind does not know ("name" and "kind" are
/// always allowed).
std::unique_ptr<const PhaseFunction> read_phase(const JsonObject& phase, const PhaseContext& context);

} // namespace vm::detail
