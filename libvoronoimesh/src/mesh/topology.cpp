#include "mesh/topology.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

namespace vm::detail {

NodeTriangles node_triangles(size_t num_nodes, std::span<const std::array<int32_t, 3>> tris,
                             const std::vector<char>* usable) {
  NodeTriangles nt;
  nt.off.assign(num_nodes + 1, 0);
  auto use = [&](size_t t) { return usable == nullptr || (*usable)[t] != 0; };
  for (size_t t = 0; t < tris.size(); ++t)
    if (use(t))
      for (int32_t n : tris[t]) ++nt.off[size_t(n) + 1];
  for (size_t n = 0; n < num_nodes; ++n) nt.off[n + 1] += nt.off[n];
  nt.tri.resize(size_t(nt.off[num_nodes]));
  std::vector<int32_t> fill(nt.off.begin(), nt.off.end() - 1);
  // Ascending t per node falls out of filling in triangle order.
  for (size_t t = 0; t < tris.size(); ++t)
    if (use(t))
      for (int32_t n : tris[t]) nt.tri[size_t(fill[size_t(n)]++)] = int32_t(t);
  return nt;
}

namespace {

/// Nodes go in blocks of this many to the parallel table builds, each block's
/// rows built on their own and laid end to end in node order afterwards, so a
/// table is the same as one pass over the nodes would make.
constexpr size_t kNodesPerBlock = 4096;

/// Calls build(first, last, out) for each block of nodes [first, last), in
/// parallel, and returns the blocks' outputs in node order.
template <class Block, class Build> std::vector<Block> build_by_blocks(size_t num_nodes, const Build& build) {
  std::vector<Block> blocks((num_nodes + kNodesPerBlock - 1) / kNodesPerBlock);
  parallel_for_each_index(
      blocks.size(),
      [&](size_t b) { build(b * kNodesPerBlock, std::min(num_nodes, (b + 1) * kNodesPerBlock), blocks[b]); }, 1);
  return blocks;
}

/// Where each block's rows and items start in the whole table (block sizes summed).
template <class Block, class Rows, class Items>
std::pair<std::vector<size_t>, std::vector<size_t>> block_starts(const std::vector<Block>& blocks, Rows rows,
                                                                 Items items) {
  std::vector<size_t> row(blocks.size() + 1, 0), item(blocks.size() + 1, 0);
  for (size_t b = 0; b < blocks.size(); ++b) {
    row[b + 1] = row[b] + rows(blocks[b]);
    item[b + 1] = item[b] + items(blocks[b]);
  }
  return {row, item};
}

} // namespace

EdgeTable edge_table(const Triangles& tris, const NodeTriangles& nt) {
  const size_t num_nodes = nt.off.size() - 1;
  struct Block {
    std::vector<std::array<int32_t, 2>> nodes;
    std::vector<int32_t> ends, he, first; // ends: where each edge's halfedges end in `he`
  };
  const auto blocks = build_by_blocks<Block>(num_nodes, [&](size_t lo, size_t hi, Block& out) {
    EdgesAt local;
    for (size_t a = lo; a < hi; ++a) {
      out.first.push_back(int32_t(out.nodes.size()));
      local.gather(int32_t(a), tris, nt);
      const auto base = int32_t(out.he.size());
      for (size_t i = 0; i < local.size(); ++i) {
        out.nodes.push_back({int32_t(a), local.other(i)});
        out.ends.push_back(base + local.halfedges_end(i));
      }
      out.he.insert(out.he.end(), local.halfedges().begin(), local.halfedges().end());
    }
  });
  // Named vectors, not a structured binding: the lambdas below capture them,
  // which Debian 12's clang 14 (the fuzz build) cannot do for bindings.
  std::vector<size_t> edge_start, he_start;
  std::tie(edge_start, he_start) = block_starts(
      blocks, [](const Block& b) { return b.nodes.size(); }, [](const Block& b) { return b.he.size(); });
  EdgeTable et;
  et.nodes.resize(edge_start.back());
  et.he.resize(he_start.back());
  et.off.resize(et.nodes.size() + 1);
  et.off[0] = 0;
  et.first.resize(num_nodes + 1);
  et.first[num_nodes] = int32_t(et.nodes.size());
  parallel_for_each_index(
      blocks.size(),
      [&](size_t b) {
        const Block& block = blocks[b];
        std::copy(block.nodes.begin(), block.nodes.end(), et.nodes.begin() + ptrdiff_t(edge_start[b]));
        std::copy(block.he.begin(), block.he.end(), et.he.begin() + ptrdiff_t(he_start[b]));
        for (size_t i = 0; i < block.ends.size(); ++i)
          et.off[edge_start[b] + i + 1] = int32_t(he_start[b]) + block.ends[i];
        for (size_t i = 0; i < block.first.size(); ++i)
          et.first[b * kNodesPerBlock + i] = int32_t(edge_start[b]) + block.first[i];
      },
      1);
  return et;
}

void EdgesAt::gather(int32_t a, const Triangles& tris, const NodeTriangles& nt) {
  // (b, halfedge) packed in one integer that sorts the same, as it sorts faster.
  auto key = [](int32_t b, int32_t h) { return uint64_t(uint32_t(b)) << 32 | uint32_t(h); };
  local_.clear();
  // Each halfedge is gathered once, at its smaller endpoint.
  for (int32_t t : nt.of(size_t(a))) {
    const auto& tri = tris[size_t(t)];
    for (int k = 0; k < 3; ++k) {
      const int32_t from = tri[size_t(k)], to = tri[size_t((k + 1) % 3)];
      const int32_t other = from == a ? to : to == a ? from : -1;
      if (other > a) local_.push_back(key(other, 3 * t + k));
    }
  }
  std::sort(local_.begin(), local_.end());
  other_.clear();
  off_.clear();
  he_.clear();
  for (size_t i = 0; i < local_.size(); ++i) {
    const auto b = int32_t(local_[i] >> 32);
    if (i == 0 || b != other_.back()) {
      other_.push_back(b);
      off_.push_back(int32_t(i));
    }
    he_.push_back(int32_t(uint32_t(local_[i])));
  }
  off_.push_back(int32_t(he_.size()));
}

int64_t EdgeTable::find(int32_t a, int32_t b) const {
  if (a > b) std::swap(a, b);
  if (a < 0 || size_t(a) + 1 >= first.size()) return -1;
  auto lo = nodes.begin() + first[size_t(a)], hi = nodes.begin() + first[size_t(a) + 1];
  auto it = std::lower_bound(lo, hi, b, [](const std::array<int32_t, 2>& e, int32_t v) { return e[1] < v; });
  return it != hi && (*it)[1] == b ? int64_t(it - nodes.begin()) : -1;
}

NodePhases node_phases(const NodeTriangles& nt, const std::vector<PhasePair>& pairs) {
  const size_t num_nodes = nt.off.size() - 1;
  struct Block {
    std::vector<int32_t> ends, phase; // ends: where each node's phases end in `phase`
  };
  const auto blocks = build_by_blocks<Block>(num_nodes, [&](size_t lo, size_t hi, Block& out) {
    std::vector<int32_t> local;
    for (size_t n = lo; n < hi; ++n) {
      local.clear();
      for (int32_t t : nt.of(n)) {
        local.push_back(pairs[size_t(t)][0]);
        local.push_back(pairs[size_t(t)][1]);
      }
      std::sort(local.begin(), local.end());
      local.erase(std::unique(local.begin(), local.end()), local.end());
      out.phase.insert(out.phase.end(), local.begin(), local.end());
      out.ends.push_back(int32_t(out.phase.size()));
    }
  });
  std::vector<size_t> node_start, phase_start; // named, as edge_table()'s (clang 14)
  std::tie(node_start, phase_start) = block_starts(
      blocks, [](const Block& b) { return b.ends.size(); }, [](const Block& b) { return b.phase.size(); });
  NodePhases np;
  np.off.resize(num_nodes + 1);
  np.off[0] = 0;
  np.phase.resize(phase_start.back());
  parallel_for_each_index(
      blocks.size(),
      [&](size_t b) {
        const Block& block = blocks[b];
        std::copy(block.phase.begin(), block.phase.end(), np.phase.begin() + ptrdiff_t(phase_start[b]));
        for (size_t i = 0; i < block.ends.size(); ++i)
          np.off[node_start[b] + i + 1] = int32_t(phase_start[b]) + block.ends[i];
      },
      1);
  return np;
}

} // namespace vm::detail
