#pragma once
/// @file fields/node_sampling.hpp
/// Sampling a phase field at one grid node: what every store of node samples
/// (SampledField, create's NodeValues reading the field directly) does per node,
/// so that they all hold the same values.

#include "voronoimesh/core/types.hpp"
#include "voronoimesh/fields/phase_field.hpp"

#include <cstdint>
#include <span>

namespace vm::detail {

/// Throws InvalidInput unless `k`, the phases kept per node, is in [1, 16].
void check_phases_per_node(int k);

/// Samples `field` at node (i, j, k) of `grid`: the ids.size() largest phases
/// into `ids` and `vals` (PhaseField::top_values) and the node's floor value
/// into `floor` (top_k.hpp, floor_below). Returns false, leaving `floor`
/// unset, when a value is NaN or infinite.
bool sample_node(const PhaseField& field, const GridSpec& grid, int64_t i, int64_t j, int64_t k,
                 std::span<int32_t> ids, std::span<double> vals, double& floor);

/// Throws the InvalidInput for the first value of `field` that is NaN or
/// infinite at grid node `n` (a node index of `grid`), naming the phase and the
/// point. Evaluating again is cheaper than carrying the phase out of a parallel
/// loop, and happens once.
[[noreturn]] void throw_not_finite(const PhaseField& field, const GridSpec& grid, int64_t n);

} // namespace vm::detail
