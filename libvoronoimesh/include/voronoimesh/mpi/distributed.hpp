#pragma once
/// @file mpi/distributed.hpp
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

#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"
#include "voronoimesh/run/meshing.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
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
  /// Nodes of the whole mesh.
  int64_t global_nodes = 0, global_triangles = 0; ///< triangles of the whole mesh
  std::array<int, 2> slabs{0, -1}; ///< the slabs (tetrahedra) this rank owns
  Box domain;                      ///< the domain box of the whole mesh (NodeMesh::domain)
  double grid_spacing = 0;         ///< as NodeMesh::grid_spacing
  std::vector<std::string> phase_names; ///< as NodeMesh::phase_names
  std::vector<int32_t> phase_labels;    ///< as NodeMesh::phase_labels
  std::vector<std::optional<Rgb>> phase_colors; ///< as NodeMesh::phase_colors
  int32_t outside_phase = -1;           ///< as NodeMesh::outside_phase
};

/// What a distributed create did; the same on every rank except where noted.
struct DistributedStats {
  CreateStats create;     ///< summed over ranks; seconds: the slowest rank's create
  double seconds = 0;     ///< this rank's wall time of the whole call, sampling included
  double mpi_seconds = 0; ///< of which inside MPI calls (waiting included)
  uint64_t bytes_sent = 0;  ///< this rank's bytes sent to other ranks
  uint64_t collectives = 0; ///< collective MPI calls this rank made (failure agreements included)
  /// improve_part(): this rank's window triangles, summed over the iterations.
  uint64_t window_triangles = 0, own_triangles = 0; ///< improve_part(): this rank's own triangles, summed likewise
  /// improve_part(): iterations run again on wider windows, their moves having
  /// outgrown the guess the windows were built for (the same on every rank).
  int wider_windows = 0;
  /// improve_part(): the iterations it ran (fewer than asked when it stopped once quality converged).
  int iterations = 0;
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
/// @param comm    the ranks that create the mesh together; every rank calls with the same arguments
/// @param scene   the scene to mesh, the same on every rank; its field must not be null
/// @param options the options of the run, as create_mesh() takes them
/// @param stats   receives what the call did; null for none
/// @return this rank's part of the initial mesh
/// @throws InvalidInput as create_mesh(), when there are more ranks than slabs, and when a rank's work
///         exceeds its share of its node's memory, on every rank alike
/// @throws Error        anything else create_mesh() throws (InvalidOption, TopologyError), on every rank alike
MeshPart create_part(MPI_Comm comm, const Scene& scene, const MeshOptions& options = {},
                     DistributedStats* stats = nullptr);

/// The same for data already distributed: `block` is this rank's block of the
/// samples (SampledField::sample() or from_samples() of some grid layers), the
/// ranks' blocks cover the grid's layers once, in rank order. The grid must suit
/// the lattice (grid_for_lattice()). Phase names and labels are left empty.
/// @param comm   the ranks that create the mesh together
/// @param block  this rank's block of the samples, of the grid layers after the previous rank's
/// @param params the lattice, snapping threshold and whether to close the domain, the same on every rank
/// @param stats  receives what the call did; null for none
/// @return this rank's part of the initial mesh
/// @throws TopologyError if the mesh fails validation after the repair rounds
/// @throws InvalidInput  when a rank's window exceeds its share of its node's memory
MeshPart create_part(MPI_Comm comm, const SampledField& block, const CreateParams& params,
                     DistributedStats* stats = nullptr);

/// Runs `iterations` of `pipeline` on the distributed mesh (paper sect. 4.4),
/// updating every rank's part: the mesh the ranks end with is the one
/// Pipeline::run() makes in one process (with RunOptions::guard_crossings as
/// given), vertex for vertex (positions bit for bit) and triangle for triangle,
/// once assemble() has closed the gaps collapses leave in the ids. The ranks
/// split space into bands of z balanced by vertices; vertices belong to the
/// band they lie in and migrate as they move, triangles to the owner of their
/// lowest corner. Each pass runs on each rank's window of the mesh and agrees
/// with the other ranks through the run's PassContext::parts: the passes whose
/// PassInfo::distributed is set (the built-in smooth, project, clamp and flip
/// with its collapses), and the crossing guard; any other pass is refused with
/// InvalidInput (Pipeline::distributes() says beforehand). `field` is
/// evaluated around each rank's band, so every rank needs it there (a
/// closed-form scene's field everywhere; a sampled field whole, for now).
/// @param comm            the ranks that hold the parts
/// @param part            this rank's part (from create_part()), updated in place
/// @param field           the phase functions, with the outside phase for a closed mesh
///                        (with_outside_phase()); evaluated around this rank's band
/// @param pipeline        the passes to run; every pass must be distributed (Pipeline::distributes())
/// @param iterations      iterations of the pipeline; 0 or less changes nothing
/// @param guard_crossings undo moves that make surfaces cross (RunOptions::guard_crossings)
/// @param stats           receives what the call did; null for none
/// @param stop_when_converged stop once quality stops improving, by Pipeline::run()'s rule
///                        (RunOptions::stop_when_converged, with its default tolerances), after the
///                        same iteration as one process; `iterations` is then the most
/// @throws InvalidInput for a pass that does not run on parts of a distributed mesh, and when
///                      `field` lacks a phase of the mesh (a closed mesh's outside phase)
void improve_part(MPI_Comm comm, MeshPart& part, const PhaseField& field, const Pipeline& pipeline, int iterations,
                  bool guard_crossings = true, DistributedStats* stats = nullptr, bool stop_when_converged = false);

/// The whole mesh on rank 0 (empty on the others): the mesh create_mesh()
/// makes.
/// @param comm the ranks that hold the parts
/// @param part this rank's part
/// @return the whole mesh on rank 0, an empty mesh on the others
/// @throws InvalidInput when it has more than 2^31 nodes or triangles
NodeMesh assemble(MPI_Comm comm, const MeshPart& part);

/// Runs `local`, work of this rank alone (reading input, writing a file on
/// rank 0), and agrees on its outcome: if it threw on any rank, every rank
/// throws that error as the distributed calls do. Between distributed calls,
/// so that a rank failing on its own never leaves the others waiting.
/// @param comm  the ranks that agree
/// @param local the work of this rank
/// @throws Error the error `local` threw on any rank, on every rank alike ("rank R of N: <problem>")
void run_collectively(MPI_Comm comm, const std::function<void()>& local);

/// Writes `path` (.pvtu), an index of one piece per rank, and the pieces
/// beside it, `<stem>_<rank>.vtu` (each the rank's part as io::write_mesh()
/// writes a .vtu; a piece's junction_order counts its own triangles). They
/// appear together once every rank has written its own: a failure on any rank
/// leaves none of them.
/// @param comm the ranks that hold the parts
/// @param part this rank's part
/// @param path the index to write, ending in .pvtu; rank 0 writes it
/// @throws IoError      if a file cannot be written
/// @throws InvalidInput if `path` does not end in .pvtu
void write_pvtu(MPI_Comm comm, const MeshPart& part, const std::string& path);

/// The pieces write_pvtu() writes beside the index `path` for `ranks` ranks,
/// in rank order: `<folder>/<stem>_<rank>.vtu`.
/// @param path  the index, a .pvtu file
/// @param ranks the number of ranks
std::vector<std::string> pvtu_pieces(const std::string& path, int ranks);

/// Watches a distributed run_job() (mpi::run_job()): what the ranks did
/// together, on top of vm::RunObserver. Every rank has its own; rank 0's usually
/// prints and the others' stay silent.
class RunObserver : public vm::RunObserver {
public:
  /// The ranks created the initial mesh.
  /// @param part  this rank's part
  /// @param stats what the distributed create did
  virtual void created_part(const MeshPart& part, const DistributedStats& stats);
  /// The ranks improved the mesh for `iterations` of `pipeline` together.
  /// @param iterations the iterations run
  /// @param pipeline   the pipeline run, as given (MeshOptions::pipeline)
  /// @param stats      what the distributed improvement did
  virtual void improved_parts(int iterations, const std::string& pipeline, const DistributedStats& stats);
};

/// vm::run_job() over the ranks of `comm`, every rank calling it with the same
/// job: each reads the input, the ranks create the mesh together
/// (create_part()) and improve it together (improve_part()) when the pipeline
/// distributes (Pipeline::distributes()) and outputs.history is not asked, else
/// rank 0 improves the assembled mesh alone.
/// Rank 0 writes the outputs; or, when outputs.mesh ends in .pvtu, every rank
/// writes its piece beside the index (write_pvtu(); the improvement must then be
/// distributed or absent, and outputs.per_phase empty). job.mesh must be empty: a
/// distributed run creates its mesh.
/// @param comm     the ranks that run the job together
/// @param job      the job, the same on every rank; job.mesh must be empty
/// @param observer this rank's observer; null for none. Not owned.
/// @throws Error as vm::run_job(), on every rank alike; InvalidInput for a non-empty job.mesh or for
///         .pvtu pieces without a distributed improvement, InvalidOption for per-phase files with them
void run_job(MPI_Comm comm, const MeshJob& job, RunObserver* observer = nullptr);

} // namespace vm::mpi
