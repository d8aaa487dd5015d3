#pragma once
/// @file fields/outside_phase.hpp
/// The phase function of the outside of a closed domain (`CreateParams::close`):
/// the box faces are surfaces between each phase and one extra phase, "exterior"
/// (outside the box), so every phase is a closed volume. Not in the paper.

#include "voronoimesh/core/types.hpp"
#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <memory>

namespace vm {

/// `field` with one more phase, id field->num_phases(), named kOutsidePhaseName,
/// that wins exactly outside `box`: phi_out(x) = max_i phi_i(x) + sd(x), sd the
/// signed distance to the box (positive outside). So phi_out ties the winning
/// phase on the box and loses inside it, and the improvement passes treat the box
/// faces like any other surface: projection onto (a, outside) lands on the box
/// plane, the surface normal there is the box normal, and where an interface
/// meets the box its nodes form a triple curve. Its label is
/// outside_phase_label().
/// @param field the phase functions of the phases inside the box
/// @param box   the domain box
/// @return `field` with the outside phase added as its last phase
/// @throws InvalidOption as outside_phase_label()
std::shared_ptr<const PhaseField> with_outside_phase(std::shared_ptr<const PhaseField> field, const Box& box);

/// The label of the outside phase that with_outside_phase() adds to `field`:
/// one more than the largest of its phases' labels, so that the outside phase,
/// the last, also has the largest label (files list phases by label, and a
/// mesh read back finds the outside phase last).
/// @param field the phase functions of the phases inside the box
/// @return the outside phase's label
/// @throws InvalidOption ("close") where a phase has label 2147483647: no
///         32-bit label is left above it
int32_t outside_phase_label(const PhaseField& field);

/// The phase functions of every phase of `mesh`, made from `field`: `field`
/// itself, or for a closed mesh (NodeMesh::outside_phase) `field` with the
/// outside phase of the mesh's box (with_outside_phase()).
/// @param mesh  a mesh created from `field`, closed or not
/// @param field the phase functions the mesh was created from
/// @return the phase functions of every phase of `mesh`
std::shared_ptr<const PhaseField> phases_of_mesh(const NodeMesh& mesh, std::shared_ptr<const PhaseField> field);

} // namespace vm
