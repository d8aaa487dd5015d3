#pragma once
/// @file improve/tangential.hpp
/// The part of a move that keeps a node on what it lies on: its surface or
/// curve (the phase functions' gradient differences there) and its box faces.

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

namespace vm::detail {

/// Removes from `move` its components across node n's constraints at x: the
/// normals grad phi_0 - grad phi_i of its phases (at most two, which fix a
/// curve) and the axes of its box faces. False when a gradient is not finite.
bool keep_tangential(const InterfaceMesh& mesh, const PhaseField& field, int32_t n, const Vec3& x, Vec3& move);

} // namespace vm::detail
