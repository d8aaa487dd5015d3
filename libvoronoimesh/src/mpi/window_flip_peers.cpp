/// @file mpi/window_flip_peers.cpp
/// Sub-rounds of the distributed flip choice, and the agreed culprits
/// (flip_peers.hpp).

#include "mpi/window_flip_peers.hpp"

#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <map>

namespace vm::mpi::detail {

namespace {

enum Status : int8_t { kUndecided = 0, kTaken = 1, kLost = 2 };

/// A candidate's decision as sent: the edge by its nodes' ids.
struct Decision {
  int64_t i, j;
  int8_t status;
};

} // namespace

void WindowFlipPeers::choose(const std::vector<vm::detail::FlipCandidate>& found, std::vector<uint8_t>& take) {
  const size_t n = found.size();
  std::vector<int8_t> status(n, kUndecided);
  // Candidates at each node, in priority order (found is best first).
  std::map<int32_t, std::vector<size_t>> at_node;
  for (size_t c = 0; c < n; ++c)
    for (int32_t v : found[c].nodes) at_node[v].push_back(c);
  std::map<std::pair<int64_t, int64_t>, size_t> by_edge;
  for (size_t c = 0; c < n; ++c)
    by_edge[{window_.vertex_ids[size_t(found[c].nodes[0])], window_.vertex_ids[size_t(found[c].nodes[1])]}] = c;
  auto mine = [&](size_t c) { return own_[size_t(found[c].nodes[0])] != 0; };

  while (true) {
    // Best first, so each candidate sees its betters' latest status.
    std::vector<Decision> decided;
    for (size_t c = 0; c < n; ++c) {
      if (status[c] != kUndecided) continue;
      bool better_taken = false, better_open = false;
      for (int32_t v : found[c].nodes)
        for (size_t b : at_node[v]) {
          if (b >= c) break;
          better_taken = better_taken || status[b] == kTaken;
          better_open = better_open || status[b] == kUndecided;
        }
      // Lost is sure whoever owns it; taken only for this rank's own candidates,
      // whose betters are all in this window.
      if (better_taken) status[c] = kLost;
      else if (!better_open && mine(c)) status[c] = kTaken;
      if (status[c] != kUndecided && mine(c))
        decided.push_back({window_.vertex_ids[size_t(found[c].nodes[0])],
                           window_.vertex_ids[size_t(found[c].nodes[1])], status[c]});
    }
    // The decisions go to every window that may hold those candidates.
    const std::vector<Decision> received = exchange(comm_, decided, [&](const Decision& d, int r) {
      return r != comm_.rank() && bands_.near(r, window_.mesh.points[size_t(window_.local(d.i))].z(), reach_);
    });
    for (const Decision& d : received) {
      const auto it = by_edge.find({d.i, d.j});
      if (it == by_edge.end()) continue; // a candidate this window cannot judge
      int8_t& s = status[it->second];
      if (s != kUndecided && s != d.status)
        throw Error("mpi: internal error: ranks disagree on a flip (please report this with the input)");
      s = d.status;
    }
    uint64_t open = 0;
    for (size_t c = 0; c < n; ++c) open += mine(c) && status[c] == kUndecided;
    if (comm_.sum(open) == 0) break;
  }
  for (size_t c = 0; c < n; ++c) take[c] = status[c] == kTaken;
}

bool WindowFlipPeers::agree_on_culprits(std::vector<std::array<int32_t, 2>>& culprits) {
  std::vector<std::array<int64_t, 2>> ids;
  for (const auto& [a, b] : culprits) ids.push_back({window_.vertex_ids[size_t(a)], window_.vertex_ids[size_t(b)]});
  std::vector<std::array<int64_t, 2>> all = comm_.all_gather(std::span<const std::array<int64_t, 2>>(ids));
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  culprits.clear();
  for (const auto& [a, b] : all) {
    const int32_t la = window_.local(a), lb = window_.local(b);
    if (la >= 0 && lb >= 0) culprits.push_back({la, lb});
  }
  return !all.empty();
}

bool WindowFlipPeers::agree_on_flips(std::vector<vm::detail::FlipInstance>& flips) {
  std::vector<std::array<int64_t, 3>> ids;
  for (const auto& f : flips)
    ids.push_back({window_.vertex_ids[size_t(f.edge[0])], window_.vertex_ids[size_t(f.edge[1])], f.earlier});
  std::vector<std::array<int64_t, 3>> all = comm_.all_gather(std::span<const std::array<int64_t, 3>>(ids));
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  flips.clear();
  for (const auto& [a, b, earlier] : all) {
    const int32_t la = window_.local(a), lb = window_.local(b);
    if (la >= 0 && lb >= 0) flips.push_back({{la, lb}, int32_t(earlier)});
  }
  return !all.empty();
}

} // namespace vm::mpi::detail
