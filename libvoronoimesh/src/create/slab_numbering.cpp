#include "create/slab_numbering.hpp"

#include "core/parallel.hpp"
#include "create/limit_key_index.hpp"

#include <algorithm>

namespace vm::detail {

SlabNumbering number_slabs(const TetLattice& lattice, std::span<const std::vector<LimitKey>* const> slab_keys,
                           int first) {
  const size_t n = slab_keys.size();
  std::vector<LimitKeyIndex> index(n);
  detail::parallel_for(size_t(0), n, [&](size_t i) {
    const std::vector<LimitKey>& keys = *slab_keys[i];
    index[i].reserve(keys.size());
    for (size_t k = 0; k < keys.size(); ++k) index[i].add(keys[k], int32_t(k));
  });
  // Per key: -1 if it first appears in its own slab, else (slab << 32 | key) of where it does.
  std::vector<std::vector<int64_t>> earlier(n);
  std::vector<int32_t> fresh(n + 1, 0);
  detail::parallel_for(size_t(0), n, [&](size_t i) {
    const std::vector<LimitKey>& keys = *slab_keys[i];
    earlier[i].assign(keys.size(), -1);
    for (size_t k = 0; k < keys.size(); ++k) {
      const LimitKey& key = keys[k];
      int lowest = first; // the first slab whose tetrahedra use every node of the key
      for (int c = 0; c < key.count; ++c) lowest = std::max(lowest, lattice.slabs_of_node(key.nodes[size_t(c)])[0]);
      for (size_t j = size_t(lowest - first); j < i; ++j)
        if (const int32_t at = index[j].find(key, *slab_keys[j]); at >= 0) {
          earlier[i][k] = int64_t(j) << 32 | int64_t(at);
          break;
        }
      fresh[i + 1] += earlier[i][k] < 0;
    }
  });
  for (size_t i = 0; i < n; ++i) fresh[i + 1] += fresh[i];
  SlabNumbering out;
  out.global.resize(n);
  // The new keys first, in order within each slab; then the others, from the slab where they are new.
  detail::parallel_for(size_t(0), n, [&](size_t i) {
    std::vector<int32_t>& ids = out.global[i];
    ids.resize(earlier[i].size());
    int32_t next = fresh[i];
    for (size_t k = 0; k < ids.size(); ++k)
      if (earlier[i][k] < 0) ids[k] = next++;
  });
  detail::parallel_for(size_t(0), n, [&](size_t i) {
    for (size_t k = 0; k < earlier[i].size(); ++k)
      if (const int64_t at = earlier[i][k]; at >= 0)
        out.global[i][k] = out.global[size_t(at >> 32)][size_t(uint32_t(at))];
  });
  out.fresh = std::move(fresh);
  return out;
}

} // namespace vm::detail
