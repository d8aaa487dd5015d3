#include "detail/label_field.hpp"

#include "voronoimesh/errors.hpp"

#include "detail/distance_transform.hpp"
#include "detail/parallel.hpp"
#include "detail/text.hpp"
#include "detail/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace vm::detail {

namespace {

using Index3 = std::array<int64_t, 3>;

/// A box of voxels [lo, hi) inside the volume, with a dense buffer over it.
struct Block {
  Index3 lo{}, hi{};
  Index3 size() const { return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}; }
  int64_t count() const { const Index3 s = size(); return s[0] * s[1] * s[2]; }
  /// Calls f(local index, volume index) for every voxel, in parallel over z-y rows.
  template <class F> void for_each(const Index3& volume, F&& f) const {
    const Index3 s = size();
    parallel_for_each_index(size_t(s[1] * s[2]), [&](size_t row) {
      const int64_t j = int64_t(row) % s[1], k = int64_t(row) / s[1];
      for (int64_t i = 0; i < s[0]; ++i)
        f(i + s[0] * (j + s[1] * k), (lo[0] + i) + volume[0] * ((lo[1] + j) + volume[1] * (lo[2] + k)));
    }, 4);
  }
};

/// The bounding boxes of every phase's voxels.
std::vector<Block> phase_boxes(const PhaseVoxels& v) {
  const int64_t big = std::numeric_limits<int64_t>::max();
  std::vector<Block> boxes(v.names.size(), Block{{big, big, big}, {-1, -1, -1}});
  for (int64_t k = 0, n = 0; k < v.size[2]; ++k)
    for (int64_t j = 0; j < v.size[1]; ++j)
      for (int64_t i = 0; i < v.size[0]; ++i, ++n) {
        const int32_t p = v.phase[size_t(n)];
        if (p < 0) continue;
        Block& b = boxes[size_t(p)];
        const Index3 at{i, j, k};
        for (size_t a = 0; a < 3; ++a) b.lo[a] = std::min(b.lo[a], at[a]), b.hi[a] = std::max(b.hi[a], at[a] + 1);
      }
  return boxes;
}

/// `b` grown by `r[a]` voxels along each axis, clipped to the volume.
Block grown(const Block& b, const Index3& r, const Index3& volume) {
  Block g;
  for (size_t a = 0; a < 3; ++a) g.lo[a] = std::max<int64_t>(0, b.lo[a] - r[a]), g.hi[a] = std::min(volume[a], b.hi[a] + r[a]);
  return g;
}

/// Convolves `buf` (over block `b`) along axis `a` with the symmetric kernel
/// w[0..r]. Beyond the volume the edge voxel repeats (a region touching the
/// edge stays whole there); beyond the block inside the volume values are 0.
void convolve_axis(std::vector<float>& buf, const Block& b, const Index3& volume, int a, const std::vector<double>& w) {
  const Index3 s = b.size();
  const std::array<int64_t, 3> stride{1, s[0], s[0] * s[1]};
  const int bb = (a + 1) % 3, cc = (a + 2) % 3;
  const int64_t n = s[size_t(a)], r = int64_t(w.size()) - 1;
  parallel_for_each_index(size_t(s[size_t(bb)] * s[size_t(cc)]), [&](size_t line) {
    thread_local std::vector<float> in;
    in.resize(size_t(n));
    const int64_t base = (int64_t(line) % s[size_t(bb)]) * stride[size_t(bb)] + (int64_t(line) / s[size_t(bb)]) * stride[size_t(cc)];
    for (int64_t q = 0; q < n; ++q) in[size_t(q)] = buf[size_t(base + q * stride[size_t(a)])];
    for (int64_t q = 0; q < n; ++q) {
      double sum = 0;
      for (int64_t t = -r; t <= r; ++t) {
        const int64_t local = std::clamp<int64_t>(b.lo[size_t(a)] + q + t, 0, volume[size_t(a)] - 1) - b.lo[size_t(a)];
        if (local >= 0 && local < n) sum += w[size_t(std::abs(t))] * in[size_t(local)];
      }
      buf[size_t(base + q * stride[size_t(a)])] = float(sum);
    }
  }, 16);
}

void smooth(std::vector<float>& buf, const Block& b, const Index3& volume, const std::vector<double>& w) {
  for (int a = 0; a < 3; ++a) convolve_axis(buf, b, volume, a, w);
}

/// Normalised Gaussian weights w[0..r] for sigma (voxels), cut at 3 sigma.
std::vector<double> gaussian(double sigma) {
  const int r = std::max(1, int(std::ceil(3 * sigma)));
  std::vector<double> w(size_t(r) + 1);
  double total = 0;
  for (int t = 0; t <= r; ++t) total += (t ? 2 : 1) * (w[size_t(t)] = std::exp(-0.5 * t * t / (sigma * sigma)));
  for (double& x : w) x /= total;
  return w;
}

void add_smoothed_indicators(const PhaseVoxels& v, const LabelFieldParams& p, TopKGridField& field) {
  const std::vector<double> w = gaussian(p.smoothing);
  const int64_t r = int64_t(w.size()) - 1;
  const float scale = float(p.smoothing * std::sqrt(2 * std::numbers::pi) / 2 * v.spacing.minCoeff());
  const Block all{{0, 0, 0}, v.size};
  // Where some voxels are not a phase, each value is divided by the smoothed
  // weight of the voxels that are, so the phases around a gap share it.
  std::vector<float> known;
  if (std::find(v.phase.begin(), v.phase.end(), -1) != v.phase.end()) {
    known.resize(v.phase.size());
    for (size_t n = 0; n < known.size(); ++n) known[n] = v.phase[n] >= 0 ? 1.f : 0.f;
    smooth(known, all, v.size, w);
  }
  const std::vector<Block> boxes = phase_boxes(v);
  std::vector<float> buf;
  for (int32_t phase = 0; phase < int32_t(boxes.size()); ++phase) {
    if (boxes[size_t(phase)].hi[0] < 0) continue; // no voxel left (cannot happen for listed labels)
    const Block b = grown(boxes[size_t(phase)], {r, r, r}, v.size);
    buf.assign(size_t(b.count()), 0.f);
    b.for_each(v.size, [&](int64_t local, int64_t n) { buf[size_t(local)] = v.phase[size_t(n)] == phase ? 1.f : 0.f; });
    smooth(buf, b, v.size, w);
    b.for_each(v.size, [&](int64_t local, int64_t n) {
      float value = buf[size_t(local)];
      if (!known.empty()) value = known[size_t(n)] > 0 ? value / known[size_t(n)] : 0.f;
      if (value > 0) field.offer(n, phase, value * scale);
    });
  }
}

void add_signed_distances(const PhaseVoxels& v, TopKGridField& field, float band) {
  Index3 r{};
  for (size_t a = 0; a < 3; ++a) r[a] = int64_t(std::ceil(band / v.spacing[int(a)])) + 1;
  // Half the distance between neighbouring voxel centres: the boundary lies halfway.
  const float half = float(v.spacing.minCoeff() / 2);
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<Block> boxes = phase_boxes(v);
  std::vector<float> to_inside, to_outside;
  for (int32_t phase = 0; phase < int32_t(boxes.size()); ++phase) {
    if (boxes[size_t(phase)].hi[0] < 0) continue;
    const Block b = grown(boxes[size_t(phase)], r, v.size);
    to_inside.assign(size_t(b.count()), inf);
    to_outside.assign(size_t(b.count()), inf);
    b.for_each(v.size, [&](int64_t local, int64_t n) {
      (v.phase[size_t(n)] == phase ? to_inside : to_outside)[size_t(local)] = 0.f;
    });
    squared_distance_transform(to_inside, b.size(), v.spacing);
    squared_distance_transform(to_outside, b.size(), v.spacing);
    b.for_each(v.size, [&](int64_t local, int64_t n) {
      const bool inside = v.phase[size_t(n)] == phase;
      const float d = inside ? std::sqrt(to_outside[size_t(local)]) - half : half - std::sqrt(to_inside[size_t(local)]);
      const float value = std::clamp(d, -band, band);
      if (value > -band) field.offer(n, phase, value);
    });
  }
}

} // namespace

std::shared_ptr<const TopKGridField> label_field(const PhaseVoxels& v, const LabelFieldParams& p, const std::string& source) {
  const GridSpec grid = voxel_grid(v.size, v.spacing, v.origin, source, "a label volume");
  auto field = std::make_shared<TopKGridField>(grid, p.k, v.names, v.labels);
  const float band = float(p.band * v.spacing.minCoeff());
  if (p.signed_distance)
    add_signed_distances(v, *field, band);
  else
    add_smoothed_indicators(v, p, *field);
  if (const int64_t empty = field->finish(p.signed_distance ? -band : 0.f); empty >= 0) {
    const int64_t i = empty % v.size[0], j = (empty / v.size[0]) % v.size[1], k = empty / (v.size[0] * v.size[1]);
    throw InvalidInput(located(source, cat("voxel (", i, ", ", j, ", ", k, ") is farther than the ",
                                           p.signed_distance ? "band" : "smoothing radius",
                                           " from every label (a large region left without a phase); widen ",
                                           p.signed_distance ? "--band" : "--smoothing", " or keep the background")));
  }
  return field;
}

} // namespace vm::detail
