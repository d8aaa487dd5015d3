#pragma once
/// @file mpi/window_collapse_peers.hpp
/// The collapses' agreement across ranks (improve/collapse_peers.hpp) for a
/// rank's window of distributed improvement: each rank finds the slivers it
/// owns (by lowest corner) and checks the collapses whose target it owns; the
/// slivers and the failures are gathered, so every rank chooses the same batch
/// and drops the same collapses as one process does over the whole mesh.

#include "improve/collapse_peers.hpp"
#include "mpi/comm.hpp"

namespace vm::mpi::detail {

class WindowCollapsePeers : public vm::detail::CollapsePeers {
public:
  WindowCollapsePeers(Comm& comm, const std::vector<uint8_t>& own) : comm_(comm), own_(own) {}

  bool answers_for(int32_t n) override { return own_[size_t(n)] != 0; }
  std::vector<vm::detail::SliverCollapse> all(const std::vector<vm::detail::SliverCollapse>& mine) override;
  std::vector<int64_t> all(const std::vector<int64_t>& mine) override;
  bool any(bool mine) override { return comm_.sum(mine ? 1 : 0) > 0; }

private:
  Comm& comm_;
  const std::vector<uint8_t>& own_;
};

} // namespace vm::mpi::detail
