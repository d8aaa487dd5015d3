/// @file mpi/window_collapse_peers.cpp
/// Gathering slivers and failed nodes over the ranks (collapse_peers.hpp).

#include "mpi/window_collapse_peers.hpp"

#include <algorithm>
#include <cstring>

namespace vm::mpi::detail {

namespace {

/// A sliver's fixed part as sent; its claims follow it.
struct SliverHead {
  double quality;
  int64_t triangle, a, b, claims;
  double to[3];
};

} // namespace

std::vector<vm::detail::SliverCollapse> WindowCollapsePeers::all(const std::vector<vm::detail::SliverCollapse>& mine) {
  std::vector<char> bytes;
  auto put = [&](const void* p, size_t n) { bytes.insert(bytes.end(), static_cast<const char*>(p), static_cast<const char*>(p) + n); };
  for (const auto& s : mine) {
    const SliverHead head{s.quality, s.triangle, s.a, s.b, int64_t(s.claims.size()), {s.to.x(), s.to.y(), s.to.z()}};
    put(&head, sizeof head);
    put(s.claims.data(), s.claims.size() * sizeof(int64_t));
  }
  const std::vector<char> everyone = comm_.all_gather(std::span<const char>(bytes));
  std::vector<vm::detail::SliverCollapse> out;
  for (size_t at = 0; at < everyone.size();) {
    SliverHead head;
    std::memcpy(&head, everyone.data() + at, sizeof head);
    at += sizeof head;
    vm::detail::SliverCollapse s{head.quality, head.triangle, head.a, head.b, std::vector<int64_t>(size_t(head.claims)),
                                 Vec3(head.to[0], head.to[1], head.to[2])};
    if (!s.claims.empty()) // an empty vector's data() may be null, which memcpy may not be given
      std::memcpy(s.claims.data(), everyone.data() + at, s.claims.size() * sizeof(int64_t));
    at += s.claims.size() * sizeof(int64_t);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<int64_t> WindowCollapsePeers::all(const std::vector<int64_t>& mine) {
  std::vector<int64_t> everyone = comm_.all_gather(std::span<const int64_t>(mine));
  std::sort(everyone.begin(), everyone.end());
  everyone.erase(std::unique(everyone.begin(), everyone.end()), everyone.end());
  return everyone;
}

} // namespace vm::mpi::detail
