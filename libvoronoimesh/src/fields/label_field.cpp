#include "fields/label_field.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/huge_pages.hpp"
#include "core/parallel.hpp"
#include "core/text.hpp"
#include "fields/distance_transform.hpp"
#include "fields/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace vm::detail {

namespace {

using Index3 = std::array<int64_t, 3>;
constexpr int64_t kBrick = TopKGridField::kBrick;
/// Bricks per axis of the blocks computed as one task: large enough that the
/// halo each block reads around itself costs little, small enough to balance.
constexpr int64_t kBlockBricks = 4;

/// A box of voxels [lo, hi).
struct Box {
  Index3 lo{}, hi{};
  bool empty() const { return hi[0] <= lo[0] || hi[1] <= lo[1] || hi[2] <= lo[2]; }
  Index3 size() const { return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}; }
  int64_t count() const { const Index3 s = size(); return s[0] * s[1] * s[2]; }
  /// Grown by r[a] along each axis, clipped to `within`.
  Box grown(const Index3& r, const Box& within) const {
    Box g;
    for (size_t a = 0; a < 3; ++a)
      g.lo[a] = std::max(within.lo[a], lo[a] - r[a]), g.hi[a] = std::min(within.hi[a], hi[a] + r[a]);
    return g;
  }
  Box clipped(const Box& within) const { return grown({0, 0, 0}, within); }
  /// Calls f(i, j, k) for every voxel, x fastest.
  template <class F> void for_each(F&& f) const {
    for (int64_t k = lo[2]; k < hi[2]; ++k)
      for (int64_t j = lo[1]; j < hi[1]; ++j)
        for (int64_t i = lo[0]; i < hi[0]; ++i) f(i, j, k);
  }
};

int16_t phase_at(const PhaseVoxels& v, int64_t i, int64_t j, int64_t k) {
  return v.phase[size_t(i + v.size[0] * (j + v.size[1] * k))];
}

/// The smallest and largest phase along axis a within `r` voxels of each brick:
/// `dims` (x fastest) becomes the brick count along a; `lo(n)` and `hi(n)` give
/// the input at index n.
template <class Lo, class Hi>
void reduce_to_bricks(Lo lo, Hi hi, Index3& dims, size_t a, int64_t r, std::vector<int16_t>& out_lo,
                      std::vector<int16_t>& out_hi) {
  Index3 out = dims;
  out[a] = (dims[a] + kBrick - 1) / kBrick;
  const Index3 in_stride{1, dims[0], dims[0] * dims[1]}, out_stride{1, out[0], out[0] * out[1]};
  // Lines by x first where a is not x: neighbouring lines then share cache
  // lines (by z first, each step along y or z missed the cache: 27% of a load).
  const size_t b = a == 0 ? 1 : 0, c = 3 - a - b;
  resize_on_huge_pages(out_lo, size_t(out[0] * out[1] * out[2]));
  resize_on_huge_pages(out_hi, out_lo.size());
  parallel_for_each_index(size_t(dims[b] * dims[c]), [&](size_t line) {
    const int64_t ib = int64_t(line) % dims[b], ic = int64_t(line) / dims[b];
    const int64_t in_base = ib * in_stride[b] + ic * in_stride[c], out_base = ib * out_stride[b] + ic * out_stride[c];
    for (int64_t brick = 0; brick < out[a]; ++brick) {
      int16_t mn = std::numeric_limits<int16_t>::max(), mx = std::numeric_limits<int16_t>::min();
      for (int64_t t = std::max<int64_t>(0, brick * kBrick - r); t < std::min(dims[a], (brick + 1) * kBrick + r); ++t) {
        const int64_t n = in_base + t * in_stride[a];
        mn = std::min(mn, lo(n)), mx = std::max(mx, hi(n));
      }
      out_lo[size_t(out_base + brick * out_stride[a])] = mn, out_hi[size_t(out_base + brick * out_stride[a])] = mx;
    }
  }, 16);
  dims = out;
}

/// The voxels of a phase one voxel thin along some axis (both neighbours along
/// it of another phase or none, or beyond the volume), as linear indices,
/// ascending: islands, sheets and tubes, whose centres smoothing would
/// otherwise carry out of their phase. A sheet in the volume's first or last
/// layer counts: before, those lost their centres in improvement (small random
/// volumes, --voxel-faithful --close: 42 of 4213 centres out of their phase
/// after 20 iterations, 23 of them in a last layer; 20 and 6 with them kept).
std::vector<int64_t> thin_voxels(const PhaseVoxels& v) {
  const Index3 n = v.size;
  std::vector<std::vector<int64_t>> of_slice(static_cast<size_t>(n[2]));
  parallel_for_each_index(size_t(n[2]), [&](size_t z) {
    const auto k = int64_t(z);
    for (int64_t j = 0; j < n[1]; ++j)
      for (int64_t i = 0; i < n[0]; ++i) {
        const int64_t at = i + n[0] * (j + n[1] * k);
        const int16_t own = v.phase[size_t(at)];
        if (own < 0) continue;
        const Index3 here{i, j, k};
        bool thin = false;
        for (size_t a = 0; a < 3 && !thin; ++a) {
          const int64_t step = a == 0 ? 1 : a == 1 ? n[0] : n[0] * n[1];
          thin = (here[a] == 0 || v.phase[size_t(at - step)] != own) &&
                 (here[a] + 1 == n[a] || v.phase[size_t(at + step)] != own);
        }
        if (thin) of_slice[z].push_back(at);
      }
  }, 1); // a slice a task: under the default grain (512) a volume's slices ran as one task
  std::vector<int64_t> thin;
  for (const auto& slice : of_slice) thin.insert(thin.end(), slice.begin(), slice.end());
  return thin;
}

/// Per brick of the voxel grid (x fastest): the one phase of every voxel within
/// `reach` voxels of the brick, or -2 when they differ (the brick needs its values computed).
std::vector<int32_t> uniform_bricks(const PhaseVoxels& v, const Index3& reach) {
  Index3 dims = v.size;
  std::vector<int16_t> lo, hi, lo2, hi2;
  const auto phase = [&](int64_t n) { return v.phase[size_t(n)]; };
  reduce_to_bricks(phase, phase, dims, 0, reach[0], lo, hi);
  for (size_t a = 1; a < 3; ++a) {
    reduce_to_bricks([&](int64_t n) { return lo[size_t(n)]; }, [&](int64_t n) { return hi[size_t(n)]; }, dims, a, reach[a],
                     lo2, hi2);
    lo.swap(lo2), hi.swap(hi2);
  }
  std::vector<int32_t> uniform(lo.size());
  for (size_t b = 0; b < uniform.size(); ++b) uniform[b] = lo[b] == hi[b] ? lo[b] : -2;
  return uniform;
}

/// The phases present in `window` and the box each occupies there.
std::vector<std::pair<int16_t, Box>> phase_boxes(const PhaseVoxels& v, const Box& window) {
  std::vector<std::pair<int16_t, Box>> found;
  // Row by row along x, a run of one phase at a time: most rows are a few runs.
  for (int64_t k = window.lo[2]; k < window.hi[2]; ++k)
    for (int64_t j = window.lo[1]; j < window.hi[1]; ++j) {
      const int16_t* row = &v.phase[size_t(v.size[0] * (j + v.size[1] * k))];
      for (int64_t i = window.lo[0]; i < window.hi[0];) {
        const int16_t p = row[i];
        const int64_t first = i;
        while (i < window.hi[0] && row[i] == p) ++i;
        const Box run{{first, j, k}, {i, j + 1, k + 1}};
        auto at = std::find_if(found.begin(), found.end(), [&](const auto& f) { return f.first == p; });
        if (at == found.end()) {
          found.push_back({p, run});
          continue;
        }
        Box& b = at->second;
        for (size_t a = 0; a < 3; ++a) b.lo[a] = std::min(b.lo[a], run.lo[a]), b.hi[a] = std::max(b.hi[a], run.hi[a]);
      }
    }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return found;
}

/// Normalised Gaussian weights w[0..r] for sigma (voxels), cut at 3 sigma.
std::vector<float> gaussian(double sigma) {
  const int r = std::max(1, int(std::ceil(3 * sigma)));
  std::vector<double> w(size_t(r) + 1);
  double total = 0;
  for (int t = 0; t <= r; ++t) total += (t ? 2 : 1) * (w[size_t(t)] = std::exp(-0.5 * t * t / (sigma * sigma)));
  std::vector<float> normalised(w.size());
  for (size_t t = 0; t < w.size(); ++t) normalised[t] = float(w[t] / total);
  return normalised;
}

/// Which bricks take offers (their values are computed), by voxel.
struct DenseBricks {
  std::vector<char> dense; ///< per brick, x fastest
  Index3 nb{};             ///< bricks per axis
  bool operator()(int64_t i, int64_t j, int64_t k) const {
    return dense[size_t(i / kBrick + nb[0] * (j / kBrick + nb[1] * (k / kBrick)))];
  }
};

/// Convolves `in` (over box `from`) along axis a with the symmetric kernel w
/// into `out` (over `from` with axis a narrowed to `to`'s range). Beyond the
/// volume the edge voxel repeats (a region touching the edge stays whole
/// there); `from` must hold every voxel of the volume within reach of `to`.
void convolve_axis(const std::vector<float>& in, const Box& from, std::vector<float>& out, const Box& to, size_t a,
                   const std::vector<float>& w, const Index3& volume) {
  Box dst = from;
  dst.lo[a] = to.lo[a], dst.hi[a] = to.hi[a];
  const Index3 s = from.size(), d = dst.size();
  const int64_t r = int64_t(w.size()) - 1;
  out.assign(size_t(dst.count()), 0.f);
  // The input index along the axis of output q + t, edge voxels repeating.
  auto source = [&](int64_t q, int64_t t) { return std::clamp<int64_t>(q + t, 0, volume[a] - 1) - from.lo[a]; };
  if (a == 0) {
    // Outputs whose taps all lie inside the volume: tap by tap over the
    // whole stretch (contiguous, vectorised), each output summed in the
    // same tap order as the outputs near the volume's ends.
    const int64_t inner_lo = std::clamp(r, dst.lo[0], dst.hi[0]);
    const int64_t inner_hi = std::clamp(volume[0] - r, inner_lo, dst.hi[0]);
    for (int64_t line = 0; line < s[1] * s[2]; ++line) {
      const float* src = in.data() + line * s[0];
      float* dst_line = out.data() + line * d[0];
      auto near_end = [&](int64_t q) {
        float sum = 0;
        for (int64_t t = -r; t <= r; ++t) sum += w[size_t(std::abs(t))] * src[source(q, t)];
        dst_line[q - dst.lo[0]] = sum;
      };
      for (int64_t q = dst.lo[0]; q < inner_lo; ++q) near_end(q);
      for (int64_t t = -r; t <= r; ++t) {
        const float weight = w[size_t(std::abs(t))];
        const float* from_tap = src + (inner_lo + t - from.lo[0]);
        float* to = dst_line + (inner_lo - dst.lo[0]);
        for (int64_t x = 0; x < inner_hi - inner_lo; ++x) to[x] += weight * from_tap[x];
      }
      for (int64_t q = inner_hi; q < dst.hi[0]; ++q) near_end(q);
    }
    return;
  }
  // Along y or z: whole rows along x at a time, contiguous (vectorised).
  const int64_t row = s[0];
  const int64_t outer = a == 1 ? s[2] : 1;                     // z slices (for y), or one pass (for z)
  const int64_t rows_between = a == 1 ? 1 : s[1];              // rows from one step along the axis to the next
  const int64_t in_step = a == 1 ? s[0] : s[0] * s[1];         // values per step along the axis, input
  const int64_t out_step = a == 1 ? d[0] : d[0] * d[1];        // and output
  const int64_t in_outer = a == 1 ? s[0] * s[1] : 0, out_outer = a == 1 ? d[0] * d[1] : 0;
  for (int64_t o = 0; o < outer; ++o)
    for (int64_t q = dst.lo[a]; q < dst.hi[a]; ++q)
      for (int64_t m = 0; m < rows_between; ++m) {
        float* dst_row = out.data() + o * out_outer + (q - dst.lo[a]) * out_step + m * row;
        for (int64_t t = -r; t <= r; ++t) {
          const float weight = w[size_t(std::abs(t))];
          const float* src = in.data() + o * in_outer + source(q, t) * in_step + m * row;
          for (int64_t x = 0; x < row; ++x) dst_row[x] += weight * src[x];
        }
      }
}

/// The Gaussian-smoothed indicator of the voxels `is_in` selects, over box `to`.
template <class Pred>
void smoothed(const PhaseVoxels& v, Pred is_in, const Box& to, const std::vector<float>& w, std::vector<float>& result) {
  thread_local std::vector<float> a, b;
  const int64_t r = int64_t(w.size()) - 1;
  const Box volume{{0, 0, 0}, v.size};
  Box from = to.grown({r, r, r}, volume);
  a.resize(size_t(from.count()));
  size_t n = 0;
  from.for_each([&](int64_t i, int64_t j, int64_t k) { a[n++] = is_in(phase_at(v, i, j, k)) ? 1.f : 0.f; });
  convolve_axis(a, from, b, to, 0, w, v.size);
  from.lo[0] = to.lo[0], from.hi[0] = to.hi[0];
  convolve_axis(b, from, a, to, 1, w, v.size);
  from.lo[1] = to.lo[1], from.hi[1] = to.hi[1];
  convolve_axis(a, from, result, to, 2, w, v.size);
}

/// Offers every phase its smoothed indicator at the voxels of `block` in dense
/// bricks; with `lead` > 0, then raises each voxel's own phase to lead there by `lead`.
void offer_smoothed_indicators(const PhaseVoxels& v, const Box& block, const DenseBricks& takes, const Index3& reach,
                               const std::vector<float>& w, float scale, float lead, TopKGridField& field) {
  const Box volume{{0, 0, 0}, v.size};
  const auto phases = phase_boxes(v, block.grown(reach, volume));
  // Where some voxels are not a phase, each value is divided by the smoothed
  // weight of the voxels that are, so the phases around a gap share it.
  thread_local std::vector<float> known, buf;
  const bool gaps = !phases.empty() && phases.front().first < 0;
  if (gaps) smoothed(v, [](int16_t p) { return p >= 0; }, block, w, known);
  for (const auto& [phase, box] : phases) {
    if (phase < 0) continue;
    const Box to = box.grown(reach, volume).clipped(block);
    if (to.empty()) continue;
    smoothed(v, [p = phase](int16_t q) { return q == p; }, to, w, buf);
    const Index3 bs = block.size();
    size_t n = 0;
    // phase = phase: clang 14 (the fuzz build) cannot capture a structured binding.
    to.for_each([&, phase = phase](int64_t i, int64_t j, int64_t k) {
      float value = buf[n++];
      if (!takes(i, j, k)) return;
      if (gaps) {
        const float weight = known[size_t((i - block.lo[0]) + bs[0] * ((j - block.lo[1]) + bs[1] * (k - block.lo[2])))];
        value = weight > 0 ? value / weight : 0.f;
      }
      if (value > 0) field.offer(i, j, k, phase, value * scale);
    });
  }
  // Only nodes of dense bricks can fall behind: a uniform brick's lead is the whole scale.
  if (lead > 0)
    block.for_each([&](int64_t i, int64_t j, int64_t k) {
      const int16_t own = phase_at(v, i, j, k);
      if (own >= 0 && takes(i, j, k)) field.lead(i, j, k, own, lead, 0.f);
    });
}

/// Offers every phase its signed distance, clamped to `band`, at the voxels of `block` in dense bricks.
void offer_signed_distances(const PhaseVoxels& v, const Box& block, const DenseBricks& takes, const Index3& reach,
                            float band, TopKGridField& field) {
  const Box volume{{0, 0, 0}, v.size};
  // Half the distance between neighbouring voxel centres: the boundary lies halfway.
  const float half = float(v.spacing.minCoeff() / 2);
  const float inf = std::numeric_limits<float>::infinity();
  thread_local std::vector<float> to_inside, to_outside;
  for (const auto& [phase, box] : phase_boxes(v, block.grown(reach, volume))) {
    if (phase < 0) continue;
    const Box to = box.grown(reach, volume).clipped(block);
    if (to.empty()) continue;
    // Every voxel within reach of `to`, so distances up to the band are exact.
    const Box from = to.grown(reach, volume);
    to_inside.assign(size_t(from.count()), inf);
    to_outside.assign(size_t(from.count()), inf);
    size_t n = 0;
    // phase = phase: as in offer_smoothed_indicators.
    from.for_each([&, phase = phase](int64_t i, int64_t j, int64_t k) { (phase_at(v, i, j, k) == phase ? to_inside : to_outside)[n++] = 0.f; });
    squared_distance_transform(to_inside, from.size(), v.spacing);
    squared_distance_transform(to_outside, from.size(), v.spacing);
    const Index3 s = from.size();
    to.for_each([&, phase = phase](int64_t i, int64_t j, int64_t k) {
      if (!takes(i, j, k)) return;
      const size_t at = size_t((i - from.lo[0]) + s[0] * ((j - from.lo[1]) + s[1] * (k - from.lo[2])));
      const bool inside = phase_at(v, i, j, k) == phase;
      const float d = inside ? std::sqrt(to_outside[at]) - half : half - std::sqrt(to_inside[at]);
      const float value = std::clamp(d, -band, band);
      if (value > -band) field.offer(i, j, k, phase, value);
    });
  }
}

} // namespace

std::shared_ptr<const TopKGridField> label_field(const PhaseVoxels& v, const LabelFieldParams& p, const std::string& source) {
  const GridSpec grid = voxel_grid(v.size, v.spacing, v.origin, source, "a label volume");
  const float band = float(p.band * v.spacing.minCoeff());
  const std::vector<float> w = gaussian(p.smoothing);
  // How far a voxel's phase reaches into the values of others, in voxels per axis.
  Index3 reach{};
  for (size_t a = 0; a < 3; ++a)
    reach[a] = p.signed_distance ? int64_t(std::ceil(band / v.spacing[int(a)])) + 1 : int64_t(w.size()) - 1;
  std::vector<int32_t> uniform = uniform_bricks(v, reach);
  auto fail = [&](const Index3& at) {
    throw InvalidInput(located(source, cat("voxel (", at[0], ", ", at[1], ", ", at[2], ") is farther than the ",
                                           p.signed_distance ? "band" : "smoothing radius",
                                           " from every label (a large region left without a phase); widen ",
                                           p.signed_distance ? "--band" : "--smoothing", " or keep the background")));
  };
  DenseBricks takes;
  for (size_t a = 0; a < 3; ++a) takes.nb[a] = (v.size[a] + kBrick - 1) / kBrick;
  const Index3& nb = takes.nb;
  for (size_t b = 0; b < uniform.size(); ++b)
    if (uniform[b] == -1) fail({int64_t(b) % nb[0] * kBrick, int64_t(b) / nb[0] % nb[1] * kBrick, int64_t(b) / (nb[0] * nb[1]) * kBrick});
  takes.dense.resize(uniform.size());
  for (size_t b = 0; b < uniform.size(); ++b) takes.dense[b] = uniform[b] < 0, uniform[b] = std::max(uniform[b], -1);
  const float top = p.signed_distance ? band : float(p.smoothing * std::sqrt(2 * std::numbers::pi) / 2 * v.spacing.minCoeff());
  auto field = std::make_shared<TopKGridField>(grid, p.k, v.names, v.labels, std::move(uniform), top);
  field->set_phase_colors(v.colors);
  const float lead = p.voxel_faithful ? float(kVoxelCentreLead * v.spacing.minCoeff()) : 0.f;
  // Blocks of kBlockBricks^3 bricks, computed independently over the box of
  // their dense bricks: each node is offered its phases by one task, in phase
  // order, so the result does not depend on the threads.
  Index3 nblock{};
  for (size_t a = 0; a < 3; ++a) nblock[a] = (nb[a] + kBlockBricks - 1) / kBlockBricks;
  const Box volume{{0, 0, 0}, v.size};
  parallel_for_each_index(size_t(nblock[0] * nblock[1] * nblock[2]), [&](size_t index) {
    const Index3 at{int64_t(index) % nblock[0], int64_t(index) / nblock[0] % nblock[1], int64_t(index) / (nblock[0] * nblock[1])};
    Box block{{0, 0, 0}, {0, 0, 0}};
    for (int64_t bk = at[2] * kBlockBricks; bk < std::min(nb[2], (at[2] + 1) * kBlockBricks); ++bk)
      for (int64_t bj = at[1] * kBlockBricks; bj < std::min(nb[1], (at[1] + 1) * kBlockBricks); ++bj)
        for (int64_t bi = at[0] * kBlockBricks; bi < std::min(nb[0], (at[0] + 1) * kBlockBricks); ++bi) {
          if (!takes.dense[size_t(bi + nb[0] * (bj + nb[1] * bk))]) continue;
          const Box brick{{bi * kBrick, bj * kBrick, bk * kBrick}, {(bi + 1) * kBrick, (bj + 1) * kBrick, (bk + 1) * kBrick}};
          if (block.empty()) block = brick;
          for (size_t a = 0; a < 3; ++a)
            block.lo[a] = std::min(block.lo[a], brick.lo[a]), block.hi[a] = std::max(block.hi[a], brick.hi[a]);
        }
    block = block.clipped(volume);
    if (block.empty()) return;
    if (p.signed_distance)
      offer_signed_distances(v, block, takes, reach, band, *field);
    else
      offer_smoothed_indicators(v, block, takes, reach, w, top, lead, *field);
  }, 1);
  // Voxel-faithful: every voxel centre leads in its own label, and improvement
  // keeps those of thin structures there (thicker ones keep theirs unaided).
  if (p.voxel_faithful) field->keep_nodes(thin_voxels(v));
  if (const int64_t empty = field->finish(p.signed_distance ? -band : 0.f); empty >= 0)
    fail({empty % v.size[0], (empty / v.size[0]) % v.size[1], empty / (v.size[0] * v.size[1])});
  return field;
}

} // namespace vm::detail
