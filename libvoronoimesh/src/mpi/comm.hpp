#pragma once
/// @file mpi/comm.hpp
/// Every MPI call of voronoimesh_mpi goes through Comm, for two reasons:
///  - failure agreement: each collective first agrees on a status word, so a
///    rank that failed (an exception between collectives) makes every rank
///    throw the same error at their next collective, naming that rank, rather
///    than leaving them waiting for it (fail());
///  - accounting: the wall time spent inside MPI (mpi_seconds()).
/// A rank that cannot even take part in the agreement (out of memory inside a
/// collective) ends the job with MPI_Abort: the last resort.

#include <mpi.h>

#include <cstdint>
#include <cstring>
#include <exception>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace vm::mpi::detail {

class Comm {
public:
  explicit Comm(MPI_Comm comm);

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Seconds spent inside MPI calls so far.
  double mpi_seconds() const { return mpi_seconds_; }
  /// Bytes this rank sent to other ranks so far, and collective calls made
  /// (agreements included): the volume and latency terms of communication.
  uint64_t bytes_sent() const { return bytes_sent_; }
  uint64_t collectives() const { return collectives_; }

  /// Agrees that every rank is well, or throws the agreed failure (see fail()).
  /// Ends every distributed call, so no rank can fail after the others returned.
  void check_in();
  /// Tells every rank that this one failed with `error` (at their next
  /// collective) and throws, as they will, the error of the lowest failed rank:
  /// of the same class (InvalidInput, IoError, TopologyError, vm::Error),
  /// "rank R of N: <message>". If the failure was already agreed (`error` is
  /// the agreed one), rethrows it.
  [[noreturn]] void fail(std::exception_ptr error);

  /// Runs `body` (this rank's part of a distributed call), then agrees: a
  /// failure on any rank, in `body` or at a collective inside it, is thrown on
  /// every rank (fail()). Returns what `body` returns.
  template <class Body> auto collectively(Body&& body) {
    try {
      if constexpr (std::is_void_v<decltype(body())>) {
        body();
        check_in();
      } else {
        auto result = body();
        check_in();
        return result;
      }
    } catch (...) {
      fail(std::current_exception());
    }
  }

  /// How many ranks of this communicator share this rank's node (memory).
  int ranks_on_node();
  uint64_t sum(uint64_t value);
  double min(double value);
  double max(double value);
  /// Sum of `value` over the ranks below this one.
  uint64_t exclusive_sum(uint64_t value);
  /// Every rank's `values`, concatenated in rank order.
  template <class T> std::vector<T> all_gather(std::span<const T> values) {
    return bytes_as<T>(all_gather_bytes(as_bytes(values)));
  }
  /// Sends send[q] to every rank q; returns what each rank sent here, by rank.
  std::vector<std::vector<char>> all_to_all(const std::vector<std::vector<char>>& send);
  /// Sends the blocks of `unit_bytes`-byte units send + send_at[q] (send_count[q]
  /// units) to every rank q and receives from each rank q recv_count[q] units
  /// into recv + recv_at[q]: for large data that is already in place (grid
  /// layers), with no copy and counts in units, so they stay far below 2^31.
  void all_to_all_in_place(const char* send, std::span<const int> send_count, std::span<const int> send_at,
                           char* recv, std::span<const int> recv_count, std::span<const int> recv_at,
                           size_t unit_bytes);
  /// Rank 0 gets every rank's `values` concatenated in rank order; the others nothing.
  template <class T> std::vector<T> gather(std::span<const T> values) {
    return bytes_as<T>(gather_bytes(as_bytes(values)));
  }

private:
  template <class T> static std::span<const char> as_bytes(std::span<const T> v) {
    return {reinterpret_cast<const char*>(v.data()), v.size_bytes()};
  }
  template <class T> static std::vector<T> bytes_as(const std::vector<char>& b) {
    std::vector<T> v(b.size() / sizeof(T));
    if (!b.empty()) std::memcpy(static_cast<void*>(v.data()), b.data(), b.size());
    return v;
  }
  std::vector<char> all_gather_bytes(std::span<const char> bytes);
  std::vector<char> gather_bytes(std::span<const char> bytes);
  /// One agreed, timed MPI_Allreduce of a single value.
  template <class T> T all_reduce(T value, MPI_Datatype type, MPI_Op op);
  /// One agreement: every rank passes its failure kind (0: none); throws the
  /// failure of the lowest failed rank, if any.
  void agree(int kind, const std::string& message);
  [[noreturn]] void throw_agreed(int failed_rank, int kind, const std::string& message);
  /// Counts in bytes as MPI wants them (int), or MPI_Abort: a message of 2 GiB
  /// or more means a decomposition far too coarse for this grid.
  int count(size_t bytes) const;

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  double mpi_seconds_ = 0;
  uint64_t bytes_sent_ = 0, collectives_ = 0;
  bool agreed_failure_ = false;
};

} // namespace vm::mpi::detail
