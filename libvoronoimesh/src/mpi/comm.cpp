#include "mpi/comm.hpp"

#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <new>
#include <numeric>

namespace vm::mpi::detail {

namespace {

/// Adds the wall time of its scope to a counter: wraps every MPI call.
class Timed {
public:
  explicit Timed(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~Timed() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;

private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

/// What a failed rank tells the others: the class of its exception.
enum Kind : int { kFine = 0, kInvalidInput, kIoError, kTopology, kOutOfMemory, kError, kOther };

/// Allocates inside a collective, where a rank can no longer tell the others
/// it failed: out of memory there ends the job.
template <class Buffer> void allocate(Buffer& buffer, size_t size, MPI_Comm comm) {
  try {
    buffer.resize(size);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "voronoimesh: out of memory receiving %zu bytes from the other ranks; ending the job\n", size);
    MPI_Abort(comm, 5);
  }
}

} // namespace

Comm::Comm(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

int Comm::count(size_t bytes) const {
  if (bytes > size_t(INT_MAX)) {
    std::fprintf(stderr, "voronoimesh: rank %d: a message of %zu bytes is beyond MPI's 2 GiB; use more ranks\n", rank_,
                 bytes);
    MPI_Abort(comm_, 5);
  }
  return int(bytes);
}

void Comm::check_in() { agree(kFine, ""); }

void Comm::agree(int kind, const std::string& message) {
  const int mine = kind == kFine ? size_ : rank_;
  int lowest = size_;
  {
    Timed t(mpi_seconds_);
    ++collectives_;
    MPI_Allreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, comm_);
  }
  if (lowest == size_) return;
  std::vector<char> text(message.begin(), message.end());
  int header[2] = {kind, int(text.size())};
  {
    Timed t(mpi_seconds_);
    MPI_Bcast(header, 2, MPI_INT, lowest, comm_);
    text.resize(size_t(header[1]));
    MPI_Bcast(text.data(), header[1], MPI_CHAR, lowest, comm_);
  }
  throw_agreed(lowest, header[0], std::string(text.begin(), text.end()));
}

void Comm::throw_agreed(int failed_rank, int kind, const std::string& message) {
  agreed_failure_ = true;
  const std::string what = "rank " + std::to_string(failed_rank) + " of " + std::to_string(size_) + ": " + message;
  switch (kind) {
  case kInvalidInput: throw InvalidInput(what);
  case kIoError: throw IoError(what);
  case kTopology: throw TopologyError(what);
  default: throw Error(what);
  }
}

void Comm::fail(std::exception_ptr error) {
  if (agreed_failure_) std::rethrow_exception(error);
  int kind = kOther;
  std::string message;
  try {
    std::rethrow_exception(error);
  } catch (const InvalidInput& e) {
    kind = kInvalidInput, message = e.what();
  } catch (const IoError& e) {
    kind = kIoError, message = e.what();
  } catch (const TopologyError& e) {
    kind = kTopology, message = e.what();
  } catch (const Error& e) {
    kind = kError, message = e.what();
  } catch (const std::bad_alloc&) {
    kind = kOutOfMemory, message = "out of memory";
  } catch (const std::exception& e) {
    kind = kOther, message = std::string("internal error: ") + e.what();
  } catch (...) {
    kind = kOther, message = "internal error: unknown exception";
  }
  agree(kind, message);
  throw_agreed(rank_, kind, message); // not reached: agree() throws when any rank failed
}

template <class T> T Comm::all_reduce(T value, MPI_Datatype type, MPI_Op op) {
  check_in();
  T result{};
  Timed t(mpi_seconds_);
  ++collectives_;
  MPI_Allreduce(&value, &result, 1, type, op, comm_);
  return result;
}

int Comm::ranks_on_node() {
  check_in();
  Timed t(mpi_seconds_);
  MPI_Comm node;
  MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  int ranks = 1;
  MPI_Comm_size(node, &ranks);
  MPI_Comm_free(&node);
  return ranks;
}

uint64_t Comm::sum(uint64_t value) { return all_reduce(value, MPI_UINT64_T, MPI_SUM); }
double Comm::min(double value) { return all_reduce(value, MPI_DOUBLE, MPI_MIN); }
double Comm::max(double value) { return all_reduce(value, MPI_DOUBLE, MPI_MAX); }

uint64_t Comm::exclusive_sum(uint64_t value) {
  check_in();
  uint64_t below = 0;
  Timed t(mpi_seconds_);
  ++collectives_;
  MPI_Exscan(&value, &below, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return rank_ == 0 ? 0 : below; // MPI leaves rank 0's result undefined
}

std::vector<char> Comm::all_gather_bytes(std::span<const char> bytes) {
  check_in();
  Timed t(mpi_seconds_);
  const int mine = count(bytes.size());
  std::vector<int> counts(static_cast<size_t>(size_)), offsets(static_cast<size_t>(size_));
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  std::exclusive_scan(counts.begin(), counts.end(), offsets.begin(), 0);
  std::vector<char> all;
  allocate(all, size_t(offsets.back()) + size_t(counts.back()), comm_);
  MPI_Allgatherv(bytes.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, comm_);
  collectives_ += 2;
  bytes_sent_ += bytes.size() * size_t(size_ - 1);
  return all;
}

std::vector<char> Comm::gather_bytes(std::span<const char> bytes) {
  check_in();
  Timed t(mpi_seconds_);
  const int mine = count(bytes.size());
  std::vector<int> counts(static_cast<size_t>(size_)), offsets(static_cast<size_t>(size_));
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  std::vector<char> all;
  if (rank_ == 0) {
    size_t total = 0;
    for (int c : counts) total += size_t(c);
    count(total);
    std::exclusive_scan(counts.begin(), counts.end(), offsets.begin(), 0);
    allocate(all, total, comm_);
  }
  MPI_Gatherv(bytes.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, 0, comm_);
  collectives_ += 2;
  if (rank_ != 0) bytes_sent_ += bytes.size();
  return all;
}

void Comm::all_to_all_in_place(const char* send, std::span<const int> send_count, std::span<const int> send_at,
                               char* recv, std::span<const int> recv_count, std::span<const int> recv_at,
                               size_t unit_bytes) {
  check_in();
  Timed t(mpi_seconds_);
  MPI_Datatype unit;
  MPI_Type_contiguous(count(unit_bytes), MPI_BYTE, &unit);
  MPI_Type_commit(&unit);
  MPI_Alltoallv(send, send_count.data(), send_at.data(), unit, recv, recv_count.data(), recv_at.data(), unit, comm_);
  ++collectives_;
  for (int q = 0; q < size_; ++q)
    if (q != rank_) bytes_sent_ += size_t(send_count[size_t(q)]) * unit_bytes;
  MPI_Type_free(&unit);
}

std::vector<std::vector<char>> Comm::all_to_all(const std::vector<std::vector<char>>& send) {
  check_in();
  Timed t(mpi_seconds_);
  std::vector<int> send_counts(static_cast<size_t>(size_)), send_offsets(static_cast<size_t>(size_)), recv_counts(static_cast<size_t>(size_)),
      recv_offsets(static_cast<size_t>(size_));
  std::vector<char> out;
  size_t total = 0;
  for (int q = 0; q < size_; ++q) {
    send_counts[size_t(q)] = count(send[size_t(q)].size());
    total += send[size_t(q)].size();
  }
  allocate(out, total, comm_);
  for (int q = 0, at = 0; q < size_; at += send_counts[size_t(q)], ++q) {
    send_offsets[size_t(q)] = at;
    std::copy(send[size_t(q)].begin(), send[size_t(q)].end(), out.begin() + at); // not memcpy: empty vectors hold null
  }
  count(total);
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm_);
  size_t received = 0;
  for (int c : recv_counts) received += size_t(c);
  count(received);
  std::exclusive_scan(recv_counts.begin(), recv_counts.end(), recv_offsets.begin(), 0);
  std::vector<char> in;
  allocate(in, received, comm_);
  MPI_Alltoallv(out.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, in.data(), recv_counts.data(),
                recv_offsets.data(), MPI_BYTE, comm_);
  collectives_ += 2;
  bytes_sent_ += total - send[size_t(rank_)].size();
  std::vector<std::vector<char>> by_rank(static_cast<size_t>(size_));
  for (int q = 0; q < size_; ++q) {
    allocate(by_rank[size_t(q)], size_t(recv_counts[size_t(q)]), comm_);
    std::copy_n(in.begin() + recv_offsets[size_t(q)], recv_counts[size_t(q)], by_rank[size_t(q)].begin());
  }
  return by_rank;
}

} // namespace vm::mpi::detail
