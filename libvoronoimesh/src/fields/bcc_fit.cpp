#include "fields/bcc_fit.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <array>
#include <atomic>

namespace vm::detail {

namespace {

/// Whether the phase `own` leads at the midpoint of the lattice edge between
/// grid nodes `lo` and `hi` by more than `margin`, the values interpolated
/// linearly as create does.
bool leads_between(const PhaseField& field, int32_t own, const Vec3& lo, const Vec3& hi, double margin) {
  constexpr size_t kMostIds = 16; // InputOptions::top_k's largest
  std::array<int32_t, 2 * kMostIds> ids{};
  std::array<double, 2 * kMostIds> values{};
  const size_t k = std::min<size_t>(kMostIds, size_t(field.num_phases()));
  field.top_values(lo, std::span(ids).first(k), std::span(values).first(k));
  field.top_values(hi, std::span(ids).subspan(k, k), std::span(values).subspan(k, k));
  const double mine = field.value(own, lo) + field.value(own, hi);
  for (size_t i = 0; i < 2 * k; ++i)
    if (ids[i] != own && field.value(ids[i], lo) + field.value(ids[i], hi) + 2 * margin >= mine) return false;
  return true;
}

} // namespace

std::vector<int64_t> voxels_bcc_cannot_hold(const PhaseVoxels& v, const PhaseField& field, double margin) {
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
        const bool first = at[axis] == 0, last = at[axis] + 1 == n[axis];
        constexpr int16_t kBeyond = -2; // no voxel: beyond the volume
        const int16_t a = first ? kBeyond : v.phase[size_t(here - stride[axis])];
        const int16_t b = last ? kBeyond : v.phase[size_t(here + stride[axis])];
        if (own < 0 || a == own || b == own) continue;
        const Vec3 centre = v.origin + v.spacing.cwiseProduct(Vec3(double(i), double(j), double(k)));
        Vec3 step = Vec3::Zero();
        step[int(axis)] = v.spacing[int(axis)];
        // Past the last voxel of an odd number of cells the grid has one node
        // more, where the field holds the last voxel's values: the edge's far
        // end is that node, not the voxel itself (which held every such voxel,
        // and a one-voxel sheet in the last layer was lost without a word).
        // Past any other end of the volume the edge leaves the grid. Inside it,
        // two neighbours of one other label outvote the voxel whatever the values.
        const bool may_lead = first || last ? last && (n[axis] - 1) % 2 == 1 : a != b;
        if (!may_lead || !leads_between(field, own, centre - step, centre + step, margin))
          count[size_t(own)].fetch_add(1, std::memory_order_relaxed);
      }
  }, 1);
  std::vector<int64_t> total(count.size());
  for (size_t p = 0; p < count.size(); ++p) total[p] = count[p].load();
  return total;
}

} // namespace vm::detail
