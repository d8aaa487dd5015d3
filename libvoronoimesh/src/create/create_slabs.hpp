#pragma once
/// @file create/create_slabs.hpp
/// create_initial_mesh() for one rank of a distributed create (mpi/): the rank
/// owns a range of slabs (the tetrahedra it meshes) and also cuts the slab on
/// each side of it, so that it holds every triangle around the vertices of its
/// own, which is what validating them needs. One process is the rank that owns
/// every slab. The repair rounds make the same repairs on every rank as one
/// process would (CreatePeers merges what the ranks found), so the ranks' parts
/// together are the mesh one process makes.

#include "create/limit_key.hpp"
#include "create/node_values.hpp"
#include "voronoimesh/create/create.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm::detail {

/// What create_slabs() needs from the other ranks at the end of each repair
/// round; in one process there are none and both are the identity.
class CreatePeers {
public:
  virtual ~CreatePeers() = default;
  /// The lattice nodes every rank found at fault, merged: sorted, no repeats.
  virtual std::vector<int64_t> merge_nodes(std::vector<int64_t> nodes) { return nodes; }
  /// The tiny loops' closings every rank found, merged: sorted, no repeats.
  virtual std::vector<LoopClosing> merge_closings(std::vector<LoopClosing> closings) { return closings; }
  /// The sum of `value` over every rank.
  virtual uint64_t sum(uint64_t value) { return value; }
};

/// Where a vertex of a part was made: bits for the slab below the owned ones,
/// the owned slabs and the slab above them; and whether a slab cut in this
/// repair round made it (its other slabs are as the last round left them).
enum VertexWhere : uint8_t { kBelowOwned = 1, kInOwned = 2, kAboveOwned = 4, kRecut = 8 };

/// What one rank's cut slabs produced, after resolving coincident triangles.
/// Vertices are numbered by first appearance over the cut slabs in order, so
/// those first made in the owned slabs come in the order one process gives them.
struct SlabsMesh {
  std::vector<Vec3> points;
  std::vector<LimitKey> keys;
  std::vector<uint8_t> where; ///< VertexWhere bits per vertex
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<PhasePair> pairs;
  size_t owned_begin = 0, owned_end = 0; ///< the triangles of the owned slabs
  /// The vertex of every limit point of the first owned slab and of the slab
  /// above the owned ones, in the order that slab's cut found them (the same on
  /// every rank that cuts it): how neighbouring ranks match shared vertices.
  std::vector<int32_t> first_owned_slab, slab_above;
};

/// Creates the part of the mesh of slabs owned[0]..owned[1] (SlabsMesh) from
/// `values`, whose window must hold the layers of the slabs from owned[0]-1 to
/// owned[1]+1 (those that exist), quantized over the range of the whole field,
/// the same on every rank; `field` is where they were read, for the repair
/// rounds to read again. Statistics count the owned slabs and the nodes of their
/// layers; the repair counts are summed over the ranks (the rounds need them),
/// the caller sums the rest. Throws InvalidInput as create_initial_mesh().
CreateStats create_slabs(const NodeSource& field, NodeValues& values, const CreateParams& params,
                         std::array<int, 2> owned, CreatePeers& peers, SlabsMesh& part);

} // namespace vm::detail
