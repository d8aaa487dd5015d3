#include "fields/bcc_fit.hpp"

#include "core/parallel.hpp"

#include <array>
#include <atomic>

namespace vm::detail {

std::vector<int64_t> voxels_bcc_cannot_hold(const PhaseVoxels& v) {
  const auto& n = v.size;
  const std::array<int64_t, 3> stride{1, n[0], n[0] * n[1]};
  // Integer counts: the same totals whichever thread adds first. Such voxels are rare, so the atomics rarely meet.
  std::vector<std::atomic<int64_t>> count(v.labels.size());
  parallel_for_each_index(size_t(n[2]), [&](size_t k) {
    for (int64_t j = 0; j < n[1]; ++j)
      for (int64_t i = 0; i < n[0]; ++i) {
        const std::array<int64_t, 3> at{i, j, int64_t(k)};
        const int odd = int(i & 1) + int(j & 1) + int(k & 1);
        if (odd == 0 || odd == 3) continue; // a lattice node
        // The axis whose parity is the odd one out: along it lies the edge.
        size_t axis = 0;
        while (int(at[axis] & 1) != (odd == 1 ? 1 : 0)) ++axis;
        const int64_t here = i + stride[1] * j + stride[2] * int64_t(k);
        const int16_t own = v.phase[size_t(here)];
        const int64_t lo = at[axis] > 0 ? here - stride[axis] : here, hi = at[axis] + 1 < n[axis] ? here + stride[axis] : here;
        const int16_t a = v.phase[size_t(lo)], b = v.phase[size_t(hi)];
        if (own >= 0 && a == b && a != own) count[size_t(own)].fetch_add(1, std::memory_order_relaxed);
      }
  }, 1);
  std::vector<int64_t> total(count.size());
  for (size_t p = 0; p < count.size(); ++p) total[p] = count[p].load();
  return total;
}

} // namespace vm::detail
