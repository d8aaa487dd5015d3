#include "mpi/balance.hpp"

#include <algorithm>

namespace vm::mpi::detail {

std::array<int, 2> slabs_starting_in(const vm::detail::TetLattice& lattice, Layers block) {
  int first = 0;
  while (first < lattice.num_slabs() && lattice.layers_of_slabs(first, first)[0] < block[0]) ++first;
  int last = first - 1;
  while (last + 1 < lattice.num_slabs() && lattice.layers_of_slabs(last + 1, last + 1)[0] <= block[1]) ++last;
  return {first, last};
}

std::vector<SlabWork> slab_work(const vm::detail::TetLattice& lattice, const GridSpec& grid,
                                std::span<const int32_t> labels, Layers layers, std::array<int, 2> slabs) {
  const int64_t first_node = grid.node_index(0, 0, layers[0]);
  auto label = [&](int64_t id) {
    const auto p = lattice.grid_point(id);
    return labels[size_t(grid.node_index(p[0], p[1], p[2]) - first_node)];
  };
  std::vector<SlabWork> work;
  for (int s = slabs[0]; s <= slabs[1]; ++s) {
    SlabWork w;
    w.tets = lattice.for_each_tet(
        s,
        [&](const int64_t* nodes, int count) {
          const int32_t first = label(nodes[0]);
          for (int c = 1; c < count; ++c)
            if (label(nodes[c]) != first) return false;
          return true;
        },
        [&](const std::array<int64_t, 4>&) { ++w.interface_tets; });
    work.push_back(w);
  }
  return work;
}

std::vector<std::array<int, 2>> balance_slabs(std::span<const SlabWork> work, int ranks) {
  const int n = int(work.size());
  std::vector<uint64_t> prefix(size_t(n) + 1, 0);
  for (int s = 0; s < n; ++s) prefix[size_t(s) + 1] = prefix[size_t(s)] + work[size_t(s)].tets + kCutCost * work[size_t(s)].interface_tets;
  // Rank r ends where the running weight first reaches (r + 1) / ranks of the
  // total, keeping at least one slab for itself and for each rank after it.
  std::vector<std::array<int, 2>> ranges;
  int first = 0;
  for (int r = 0; r < ranks; ++r) {
    int last = n - 1;
    if (r + 1 < ranks) {
      const unsigned __int128 target = (unsigned __int128)prefix.back() * unsigned(r + 1) / unsigned(ranks);
      last = first;
      while (last + 1 < n && prefix[size_t(last) + 1] < target) ++last;
      last = std::min(last, n - (ranks - r));
    }
    ranges.push_back({first, last});
    first = last + 1;
  }
  return ranges;
}

} // namespace vm::mpi::detail
