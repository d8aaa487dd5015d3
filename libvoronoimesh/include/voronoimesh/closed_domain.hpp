#pragma once
/// @file closed_domain.hpp
/// Closed domains (`CreateParams::close`): the box faces are surfaces between
/// each phase and one extra phase, "exterior" (outside the box), so every phase is a closed volume.
/// Not in the paper.

#include "voronoimesh/field.hpp"
#include "voronoimesh/node_mesh.hpp"
#include "voronoimesh/types.hpp"

#include <memory>
#include <string>

namespace vm {

/// Name of the phase outside the box of a closed mesh ("outside" is a common
/// name of a scene's own background phase).
inline const std::string kOutsidePhaseName = "exterior";

/// `field` with one more phase, id field->num_phases(), that wins exactly
/// outside `box`: phi_out(x) = max_i phi_i(x) + sd(x), sd the signed distance to
/// the box (positive outside). So phi_out ties the winning phase on the box and
/// loses inside it, and the improvement passes treat the box faces like any
/// other surface: projection onto (a, outside) lands on the box plane, the
/// surface normal there is the box normal, and where an interface meets the box
/// its nodes form a triple curve. Its label is one more than the last phase's.
std::shared_ptr<const PhaseField> with_outside_phase(std::shared_ptr<const PhaseField> field, const Box& box);

/// True when `mesh` is a closed mesh of a field with `field_phases` phases: its
/// phase `field_phases` is named kOutsidePhaseName.
bool is_closed_mesh(const NodeMesh& mesh, int field_phases);

} // namespace vm
