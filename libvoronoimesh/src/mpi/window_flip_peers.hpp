#pragma once
/// @file mpi/window_flip_peers.hpp
/// The flip rounds' agreement across ranks (improve/flip_peers.hpp) for a
/// rank's window of distributed improvement.
///
/// A candidate edge belongs to the owner of its lower node. Its owner decides
/// it as one process would: taken unless a better candidate sharing a node is
/// taken. That chains from candidate to better candidate, across the cuts too,
/// so the ranks decide in sub-rounds: each decides what it can, sends what it
/// decided to the windows that hold those candidates, and goes on until no
/// rank has an undecided candidate of its own. Every rank then flips every
/// taken candidate of its window, so the windows stay the mesh one process has
/// around each band.

#include "improve/flip_peers.hpp"
#include "mpi/window.hpp"

namespace vm::mpi::detail {

class WindowFlipPeers : public vm::detail::FlipPeers {
public:
  /// `own`: the window's vertices this rank owns; `reach`: how far from a band
  /// the windows reach (decisions go to every window that may hold them).
  WindowFlipPeers(Comm& comm, const Window& window, const std::vector<uint8_t>& own, const Bands& bands, double reach)
      : comm_(comm), window_(window), own_(own), bands_(bands), reach_(reach) {}

  bool any(bool mine) override { return comm_.sum(mine ? 1 : 0) > 0; }
  void choose(const std::vector<vm::detail::FlipCandidate>& found, std::vector<uint8_t>& take) override;
  bool answers_for(const std::array<int32_t, 3>& triangle) override {
    return own_[size_t(std::min({triangle[0], triangle[1], triangle[2]}))]; // local order is id order
  }
  bool agree_on_culprits(std::vector<std::array<int32_t, 2>>& culprits) override;
  bool agree_on_flips(std::vector<vm::detail::FlipInstance>& flips) override;

private:
  Comm& comm_;
  const Window& window_;
  const std::vector<uint8_t>& own_;
  const Bands& bands_;
  double reach_;
};

} // namespace vm::mpi::detail
