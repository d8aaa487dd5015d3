#pragma once
/// @file mpi/memory.hpp
/// Refusing a rank's work before allocating it when it cannot fit in the rank's
/// share of its node's memory, as one process refuses a grid too big for its
/// machine (create_mesh()): the ranks on one node (MPI_COMM_TYPE_SHARED) share
/// what the node has available, so each counts on its fraction of it.

#include "mpi/comm.hpp"

#include <string>

namespace vm::mpi::detail {

/// Replaces a node's available memory when set: bytes, or a number with K, M,
/// G or T (powers of 1024). For jobs granted less than their nodes have (a
/// batch system's limit) and for tests.
inline constexpr const char* kNodeMemoryVariable = "VORONOIMESH_NODE_MEMORY";

/// What this rank may count on.
struct MemoryShare {
  double node_bytes = 0; ///< the node's MemAvailable, or kNodeMemoryVariable
  int node_ranks = 1;    ///< ranks of the communicator on this node
  bool from_variable = false;
  double bytes() const { return node_bytes / node_ranks; }
};

/// This rank's share. Collective (the ranks find which of them share a node);
/// throws InvalidInput for a malformed kNodeMemoryVariable.
MemoryShare memory_share(Comm& comm);

/// Throws InvalidInput "<what> needs about X GiB on this rank, its share of its
/// node's memory is Y GiB (Z GiB available, N ranks)" when `bytes` exceed the share.
void refuse_beyond_share(const MemoryShare& share, double bytes, const std::string& what);

} // namespace vm::mpi::detail
