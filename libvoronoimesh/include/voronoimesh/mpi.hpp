#pragma once
/// @file mpi.hpp
/// Distributed create with MPI (paper sect. 4.4), in the separate library
/// voronoimesh_mpi (built with -DVM_MPI=ON; the core library needs no MPI).
///
/// The lattice's slabs (one per layer of lattice blocks along z) are shared out
/// among the ranks in contiguous ranges, so that each rank gets a similar
/// number of interface tetrahedra; each tetrahedron belongs to the rank owning
/// its slab. A rank samples only its block of grid layers, receives the few
/// layers around its slabs from the ranks that hold them, and creates the
/// triangles of its own tetrahedra. Ranks agree on shared vertices through
/// their exact keys (lattice element and barycentric weights), not by a
/// tolerance, and repair ties exactly as one process would: the mesh the ranks
/// make together is the one create_mesh() makes, node for node and triangle for
/// triangle, in the same order.
///
/// Every call is collective over its communicator. A rank that fails (bad
/// input in its block, out of memory, any exception) makes every rank throw:
/// the same error class on all, with the message "rank R of N: <problem>".
///
/// Memory: before sampling its block and again before receiving its window of
/// layers, each rank estimates what it will hold (samples, lattice node values,
/// its part of the mesh) and refuses with InvalidInput if that exceeds its share
/// of its node: the node's available memory (MemAvailable) divided by the ranks
/// of the communicator on that node, or the environment variable
/// VORONOIMESH_NODE_MEMORY (bytes, or with K, M, G or T) instead of MemAvailable,
/// e.g. for a batch system's limit below the node's memory.

#include "voronoimesh/meshing.hpp"
#include "voronoimesh/node_mesh.hpp"
#include "voronoimesh/pipeline.hpp"
#include "voronoimesh/sampled_field.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vm::mpi {

/// One rank's part of a distributed mesh: the triangles it owns and every
/// vertex they use. After create_part() those are the triangles of the
/// tetrahedra it owns; a vertex on the boundary between two ranks' slabs is in
/// both parts, with the same global id, owned by the lower rank, which made it
/// first. After improve_part() a vertex belongs to the rank whose band of z it
/// lies in, and a triangle to the owner of its corner with the lowest id.
struct MeshPart {
  std::vector<Vec3> points;                      ///< vertices, local ids
  std::vector<std::array<int32_t, 3>> triangles; ///< local vertex ids, oriented as in NodeMesh
  std::vector<PhasePair> pairs;                  ///< phase pair of each triangle
  std::vector<int64_t> global_ids;               ///< each vertex's id in the assembled mesh
  std::vector<int32_t> owners;                   ///< the rank owning each vertex
  std::vector<int64_t> triangle_ids;             ///< each triangle's index in the assembled mesh, ascending
  int64_t global_nodes = 0, global_triangles = 0; ///< of the whole mesh
  std::array<int, 2> slabs{0, -1}; ///< the slabs (tetrahedra) this rank owns
  Box domain;
  std::vector<std::string> phase_names; ///< as NodeMesh::phase_names
  std::vector<int32_t> phase_labels;    ///< as NodeMesh::phase_labels
};

/// What a distributed create did; the same on every rank except where noted.
struct DistributedStats {
  CreateStats create;     ///< summed over ranks; seconds: the slowest rank's create
  double seconds = 0;     ///< this rank's wall time of the whole call, sampling included
  double mpi_seconds = 0; ///< of which inside MPI calls (waiting included)
  uint64_t bytes_sent = 0;  ///< this rank's bytes sent to other ranks
  uint64_t collectives = 0; ///< collective MPI calls this rank made (failure agreements included)
  /// improve_part(): this rank's window and own triangles, summed over the iterations.
  uint64_t window_triangles = 0, own_triangles = 0;
  /// improve_part(): iterations run again on wider windows, their moves having
  /// outgrown the guess the windows were built for (the same on every rank).
  int wider_windows = 0;
  std::vector<uint64_t> interface_tets; ///< per rank: tetrahedra with more than one winning phase at their nodes
  std::vector<std::array<int, 2>> slabs; ///< per rank: the slabs it owns
};

/// Creates the initial mesh of `scene` (as create_mesh() with the same options)
/// on every rank of `comm` together; returns this rank's part. Each rank
/// samples an equal share of the grid layers, then the slabs are balanced by
/// interface tetrahedra (counted from the winning phase at each node). Throws
/// as create_mesh(), InvalidInput when there are more ranks than slabs (half
/// the grid cells along z for bcc) and when a rank's work exceeds its share of
/// its node's memory (above).
MeshPart create_part(MPI_Comm comm, const Scene& scene, const MeshOptions& options = {},
                     DistributedStats* stats = nullptr);

/// The same for data already distributed: `block` is this rank's block of the
/// samples (SampledField::sample() or from_samples() of some grid layers), the
/// ranks' blocks cover the grid's layers once, in rank order. The grid must suit
/// the lattice (grid_for_lattice()). Phase names and labels are left empty.
/// Throws TopologyError if the mesh fails validation after the repair rounds,
/// InvalidInput when a rank's window exceeds its share of its node's memory.
MeshPart create_part(MPI_Comm comm, const SampledField& block, const CreateParams& params,
                     DistributedStats* stats = nullptr);

/// Runs `iterations` of `pipeline` on the distributed mesh (paper sect. 4.4),
/// updating every rank's part: the mesh the ranks end with is the one
/// Pipeline::run() makes in one process (with RunOptions::guard_crossings as
/// given), vertex for vertex (positions bit for bit) and triangle for triangle,
/// once assemble() has closed the gaps collapses leave in the ids. The ranks
/// split space into bands of z balanced by vertices; vertices belong to the
/// band they lie in and migrate as they move, triangles to the owner of their
/// lowest corner. The built-in passes smooth, project, clamp and flip (with its
/// collapses) are distributed, and the crossing guard; any other pass is
/// refused with InvalidInput (distributes() says beforehand). `field` is
/// evaluated around each rank's band, so every rank needs it there (a
/// closed-form scene's field everywhere; a sampled field whole, for now).
void improve_part(MPI_Comm comm, MeshPart& part, const PhaseField& field, const Pipeline& pipeline, int iterations,
                  bool guard_crossings = true, DistributedStats* stats = nullptr);

/// True when improve_part() can run every pass of `pipeline`.
bool distributes(const Pipeline& pipeline);

/// The whole mesh on rank 0 (empty on the others): the mesh create_mesh()
/// makes. Throws InvalidInput when it has more than 2^31 nodes or triangles.
NodeMesh assemble(MPI_Comm comm, const MeshPart& part);

/// Runs `local`, work of this rank alone (reading input, writing a file on
/// rank 0), and agrees on its outcome: if it threw on any rank, every rank
/// throws that error as the distributed calls do. Between distributed calls,
/// so that a rank failing on its own never leaves the others waiting.
void run_collectively(MPI_Comm comm, const std::function<void()>& local);

/// Writes `path` (.pvtu), an index of one piece per rank, and the pieces
/// beside it, <stem>_<rank>.vtu (each the rank's part as io::write_mesh()
/// writes a .vtu; a piece's junction_order counts its own triangles). Throws IoError if a
/// file cannot be written, InvalidInput if `path` does not end in .pvtu.
void write_pvtu(MPI_Comm comm, const MeshPart& part, const std::string& path);

} // namespace vm::mpi
