#pragma once
/// @file improve/part_agreement.hpp
/// How the built-in passes agree across the parts of a distributed mesh. In a
/// distributed run (mpi/improve_part.cpp) each rank runs the pipeline on its
/// window of the mesh; where one process would look at the whole mesh, the
/// passes ask the run's PartAgreement (PassContext::parts), so every rank makes
/// the moves and flips one process makes around its own nodes. One process has
/// none, and the passes take their one-process paths. A pass that can work so
/// says PassInfo::distributed; the distributed run refuses any other.

#include "improve/collapse_peers.hpp"
#include "improve/flip_peers.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

class PartAgreement {
public:
  virtual ~PartAgreement() = default;

  /// The RMS edge length over the whole mesh (the smoothing's rest length, eq. 3).
  virtual double rms_edge_length(const InterfaceMesh& mesh) = 0;
  /// Before pending moves are committed: every node takes its owner's move.
  virtual void share_moves(std::vector<Vec3>& delta) = 0;
  /// The crossing guard's agreement on the moves it undoes (AgreeOnUndone, guard.hpp).
  virtual bool agree_on_undone(std::vector<int32_t>& undone) = 0;

  /// Before a pass changes the topology (moves committed): the run may find
  /// that this window cannot hold what the change looks at, and then throws
  /// to run the iteration again on wider windows.
  virtual void before_topology_change(const InterfaceMesh& mesh) = 0;
  /// The flip rounds' agreement (flip_peers.hpp).
  virtual FlipPeers& flip_peers() = 0;
  /// The collapses' agreement (collapse_peers.hpp), with the ids that order this
  /// part's nodes and triangles as the whole mesh's.
  virtual CollapsePeers& collapse_peers() = 0;
  virtual std::span<const int64_t> node_ids() const = 0;
  virtual std::span<const int64_t> triangle_ids() const = 0;
  /// After collapses rebuilt the mesh: what it kept of the old nodes and triangles.
  virtual void renumbered(const CollapseKept& kept) = 0;
};

/// flip_edges() on a part of a distributed mesh (flip.cpp): the flip rounds and
/// then the collapses, agreed through `parts`.
FlipStats flip_edges(InterfaceMesh& mesh, const FlipParams& params, PartAgreement& parts);

} // namespace vm::detail
