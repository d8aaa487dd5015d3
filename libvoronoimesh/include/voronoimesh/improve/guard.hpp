#pragma once
/// @file improve/guard.hpp
/// Committing node moves without letting surfaces cross.
///
/// Clamping (Alg. 3) keeps each triangle from inverting within its own fan, but
/// it cannot see a *different* surface, nor a distant part of its own: where a
/// phase is thinner than an edge (clusters of quadruple points, triple curves
/// meeting at shallow angles) or an interface is rough at the grid scale (point
/// clouds), projection and smoothing can push a triangle through another one.
/// The guard undoes exactly the moves that would do that (not in the paper).

#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstddef>
#include <functional>
#include <vector>

namespace vm {

/// What commit_without_crossings() did.
struct GuardReport {
  size_t undone_nodes = 0; ///< nodes left where they were
  int rounds = 0;          ///< intersection checks made
};

/// How the ranks of a distributed run agree on the moves to undo
/// (commit_without_crossings()): called once per round with the nodes this
/// rank would put back, it replaces them with those of every rank (the ones in
/// this window) and returns whether any rank put a node back.
using AgreeOnUndone = std::function<bool(std::vector<int32_t>& undone)>;

/// Moves every node by delta[n], then finds the triangle pairs that intersect
/// improperly (exactly, check/intersections.hpp) and have a moved node, puts the moved
/// nodes of both triangles back exactly where they were, and repeats until no
/// such pair is left. Pairs among unmoved triangles are not looked at, so
/// crossings the mesh already had are neither counted nor cured; a mesh free of
/// them stays free. Undoing moves never inverts a triangle that clamping made
/// safe: any subset of clamped moves is safe (eq. 5's factor 1/2). Deterministic
/// for any thread count.
/// The moves that turn any triangle's normal by 90 degrees or more, or shrink it
/// to what validate() calls zero area, are undone too: clamping rules that out,
/// but not in round-off for triangles a millionth of the mesh's size. With
/// `field`, so are the moves that turn a triangle with a corner on a junction
/// against the direction from its first phase into its second
/// (grad phi_second - grad phi_first at its centroid, where that is clear):
/// clamping cannot see that, and near close quadruple points such triangles
/// could stand across their surface for a few iterations.
///
/// In a distributed run each rank passes its window of the mesh (moves of every
/// node in it, exact) and `agree` (AgreeOnUndone), so every rank undoes the same
/// moves and stops at the same round.
/// @param mesh  the mesh whose nodes move (in a distributed run, this rank's window)
/// @param delta the move of every node, one entry per node; set to the moves actually made
/// @param field the phase functions, to also undo moves that turn a junction triangle against its phase
///              pair; null: not checked
/// @param agree in a distributed run, how the ranks agree on the nodes put back; empty in one process
/// @return the nodes left where they were and the intersection checks made
GuardReport commit_without_crossings(InterfaceMesh& mesh, std::vector<Vec3>& delta,
                                     const PhaseField* field = nullptr, const AgreeOnUndone& agree = {});

} // namespace vm
