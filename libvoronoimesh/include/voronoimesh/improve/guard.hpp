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

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

namespace vm {

namespace detail {
class CrossingIndex; // the kept grid of triangle boxes (check/crossing_index.hpp)
}

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

/// Commits moves, and checks flips, so that no two triangles come to cross.
/// It keeps an index of the triangles' boxes between calls (check/crossing_index.hpp),
/// filing again only triangles that changed or moved far: one guard per run of
/// a pipeline makes each check cost about a scan of the mesh's boxes plus the
/// exact tests of what moved, where a fresh one sorts the whole mesh first. It
/// learns the mesh from each call anew (any moves, flips or renumbering in
/// between are seen), so it needs no notice of changes; it remembers the
/// version of the mesh it last looked at (checked_at()), so that a caller that
/// knows what it changed since may ask about that alone.
class CrossingGuard {
public:
  CrossingGuard();  ///< a guard that has seen no mesh yet
  ~CrossingGuard(); ///< frees the index
  /// Takes over another guard's index.
  CrossingGuard(CrossingGuard&&) noexcept;
  /// Takes over another guard's index.
  /// @return this guard
  CrossingGuard& operator=(CrossingGuard&&) noexcept;

  /// Moves every node by delta[n], then finds the triangle pairs that intersect
  /// improperly (exactly, check/intersections.hpp) and have a moved node, puts the
  /// corner of each pair that moved farthest (all that moved as far) back exactly
  /// where it was, and repeats until no such pair is left: the other corners may
  /// have moved where they belong (putting back every moved corner froze a flat
  /// face of the CT-like volume for a whole run). Pairs among unmoved triangles are not looked at, so
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
  /// And the moves that leave a triangle below `quality_floor` (triangle_quality()),
  /// but not (with `field`) a move that at least halves the eq. 4 step of a node
  /// whose step was over 2% of that triangle's longest edge: given the worst
  /// quality of the mesh before the moves, moving never makes the worst triangle
  /// worse except to bring a node visibly off its interface onto it. Such moves
  /// are remembered until forget_floor_exceptions(), so that they can be taken
  /// back (floor_exception_reverts()); with `floor_holds_all` none is made.
  /// A triple-curve node's move (eq. 4 takes it about a third of the way per
  /// iteration, never half) goes ahead when its step was over 2% of the
  /// triangle's longest edge, the move leaves at most 0.9 of it and the
  /// triangle at quality 0.4 or better; it is not remembered: the floor never
  /// holds a curve node visibly off its curve for a triangle above 0.4.
  ///
  /// With a `field` that keeps points (PhaseField::kept_points(): a
  /// voxel-faithful label volume's centres of voxels in thin structures), so
  /// are the moves that carry one out of its phase across a triangle.
  ///
  /// In a distributed run each rank passes its window of the mesh (moves of every
  /// node in it, exact) and `agree` (AgreeOnUndone), so every rank undoes the same
  /// moves and stops at the same round.
  /// @param mesh          the mesh whose nodes move (in a distributed run, this rank's window)
  /// @param delta         the move of every node, one entry per node; set to the moves actually made
  /// @param field         the phase functions, to also undo moves that turn a junction triangle against its
  ///                      phase pair; null: not checked
  /// @param agree         in a distributed run, how the ranks agree on the nodes put back; empty in one process
  /// @param quality_floor no moved triangle may end below this quality; 0: not checked
  /// @param floor_holds_all the floor holds for every move, even one closing in on its interface
  /// @return the nodes left where they were and the intersection checks made
  GuardReport commit(InterfaceMesh& mesh, std::vector<Vec3>& delta, const PhaseField* field = nullptr,
                     const AgreeOnUndone& agree = {}, double quality_floor = 0, bool floor_holds_all = false);

  /// The pairs of faces {f, g}, f < g, that intersect improperly and of which at
  /// least one is flagged in `involved` (one flag per face), sorted: what the
  /// flip guard asks after a batch of flips. The mesh's triangles() must be current.
  /// @param mesh     the mesh, as of its last InterfaceMesh::topology_changed()
  /// @param involved one flag per face: the faces whose crossings are wanted
  /// @return the crossing pairs of face ids
  std::vector<std::array<int32_t, 2>> crossings(const InterfaceMesh& mesh, std::span<const uint8_t> involved);

  /// crossings() where the faces flagged in `involved` are the only ones that
  /// moved or were flipped since the guard's last check of this mesh (the
  /// rounds of a commit after the first, a flip pass's repairs): it then costs
  /// time in those faces, not in the whole mesh. The same answer.
  /// @param mesh     the mesh, as of its last InterfaceMesh::topology_changed()
  /// @param involved one flag per face: the faces changed since the last check
  /// @return the crossing pairs of face ids
  std::vector<std::array<int32_t, 2>> crossings_of_changed(const InterfaceMesh& mesh,
                                                           std::span<const uint8_t> involved);

  /// Whether the guard's last look at a mesh (a check, index_for()) saw it at
  /// `version` (InterfaceMesh::version()): then, if only some faces changed
  /// since, crossings_of_changed() told of those answers for the whole mesh
  /// (the flip pass's first check after its flips).
  /// @param version a mesh's version() before the changes
  bool checked_at(uint64_t version) const { return version != 0 && version == checked_version_; }
  /// The guard's index, up to date with `mesh`, for checking a trial of edits
  /// to it (CrossingIndex::crossings_with(), as the junction-sliver collapses
  /// do); null while the guard keeps no index (then check the trial whole).
  /// @param mesh the mesh, as of its last InterfaceMesh::topology_changed()
  /// @return the index, or null
  const detail::CrossingIndex* index_for(const InterfaceMesh& mesh);

  /// Tells the guard that `mesh` was rebuilt from the mesh it last saw, keeping
  /// some of its faces and nodes (a collapse, a remesh), so that its index carries over.
  /// Without this call it would notice the change by itself and build its
  /// index anew.
  /// @param mesh     the rebuilt mesh
  /// @param old_face the old id of each face of `mesh` (each once, in any order), or -1 for a new face
  /// @param old_node the old id of each node of `mesh` (each once, in any order), or -1 for a new node
  void renumbered(const InterfaceMesh& mesh, std::span<const int32_t> old_face, std::span<const int32_t> old_node);
  /// renumbered() for an edit in place (InterfaceMesh::edit_in_place()) that
  /// removed faces and nodes and added none: told sparsely, in time of the edit.
  /// @param removed_faces the old ids of the faces that went, each once
  /// @param face_moves    the edit's moves of faces (EditMoves::faces)
  /// @param removed_nodes the old ids of the nodes that went, ascending
  /// @param node_moves    the edit's moves of nodes (EditMoves::nodes)
  void edited(std::span<const int32_t> removed_faces, std::span<const SlotMove> face_moves,
              std::span<const int32_t> removed_nodes, std::span<const SlotMove> node_moves);

  /// While on, commit() leaves out its search for crossings (every other check
  /// stays) and the passes that ask defers_crossings() check none of their
  /// flips: the pipeline then checks the whole mesh once, after some
  /// iterations, and runs them again from their start, checked, should it
  /// find a crossing (RunOptions::check_crossings_every).
  /// @param on whether to defer
  void defer_crossings(bool on) { deferred_ = on; }
  /// Forgets the meshes seen so far (the index drops; the next check builds
  /// anew): for a mesh put back to an earlier state, which renumbered() could
  /// not carry the index over to.
  void forget_meshes();
  /// Whether crossings are left to a later whole check (defer_crossings()).
  bool defers_crossings() const { return deferred_; }
  /// How many of the guard's checks so far found a crossing (commits, flips
  /// and whole checks alike): the pipeline defers crossings only where the
  /// guard has been finding none.
  size_t checks_that_crossed() const { return checks_that_crossed_; }

  /// Forgets the moves the quality floor let through (commit()).
  void forget_floor_exceptions() { excepted_.clear(); }
  /// Adds to `delta` the moves that take the nodes the quality floor let
  /// through since forget_floor_exceptions() back where they were before, for
  /// those still where it left them and at a triangle now below `quality_floor`
  /// (the others' triangles came back above it), and forgets them all: to be
  /// committed with the floor holding for every move
  /// (PassContext::take_back_floor_exceptions()).
  /// @param mesh          the mesh commit() moved them in
  /// @param quality_floor the worst quality the iteration began with
  /// @param delta         one entry per node
  void floor_exception_reverts(const InterfaceMesh& mesh, double quality_floor, std::vector<Vec3>& delta);
  /// The nodes the quality floor let through since forget_floor_exceptions()
  /// (commit()), ascending: where a floor pass follows, the flip pass leaves
  /// their triangles as they are (FlipParams::keep_triangles_at), so that it
  /// can still put them back among them.
  std::vector<int32_t> floor_exception_nodes() const;

private:
  /// A node the quality floor let through: where it was, where that left it.
  struct FloorException {
    Vec3 from, to;
  };
  std::unique_ptr<detail::CrossingIndex> index_;
  uint64_t checked_version_ = 0; ///< the version() of the mesh at the guard's last look at one (checked_at())
  bool deferred_ = false;        ///< defer_crossings()
  size_t checks_that_crossed_ = 0; ///< checks_that_crossed()
  std::unordered_map<int32_t, FloorException> excepted_; ///< by node
};

/// CrossingGuard::commit() with a guard of its own, for a single commit.
/// @param mesh  the mesh whose nodes move (in a distributed run, this rank's window)
/// @param delta the move of every node, one entry per node; set to the moves actually made
/// @param field the phase functions, to also undo moves that turn a junction triangle against its phase
///              pair; null: not checked
/// @param agree in a distributed run, how the ranks agree on the nodes put back; empty in one process
/// @return the nodes left where they were and the intersection checks made
GuardReport commit_without_crossings(InterfaceMesh& mesh, std::vector<Vec3>& delta,
                                     const PhaseField* field = nullptr, const AgreeOnUndone& agree = {});

} // namespace vm
