#pragma once
/// @file improve/field_checks.hpp
/// What the passes do when a phase function gives them a value or gradient that
/// is not finite (a formula dividing by zero somewhere, a plugin's field): no
/// move is made from it, the node is flagged, and after the parallel loop
/// refuse_not_finite() throws for the lowest flagged node, so the message does
/// not depend on the threads.

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// Throws InvalidInput naming the phase (PhaseField::describe_phase()), the
/// point and the value or gradient that is not finite, for the lowest node with
/// flagged[n] set; returns when none is.
void refuse_not_finite(const InterfaceMesh& mesh, const PhaseField& field, const std::vector<uint8_t>& flagged);

/// Throws InvalidInput unless `field` has phase `top`, the largest of a mesh's
/// phases (those of its triangles' `pairs`, or of `mesh`'s nodes): the passes
/// would evaluate a phase it lacks out of bounds. A closed mesh's phase outside
/// the box comes with with_outside_phase() (phases_of_mesh()); a mesh made from
/// another input has other phases.
void require_phases(const PhaseField& field, std::span<const PhasePair> pairs);
void require_phases(const PhaseField& field, const InterfaceMesh& mesh);

} // namespace vm::detail
