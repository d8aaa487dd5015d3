#include "detail/top_k_grid_field.hpp"

#include "detail/top_k.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace vm::detail {

TopKGridField::TopKGridField(const GridSpec& grid, int k, std::vector<std::string> names, std::vector<int32_t> labels)
    : grid_(grid), k_(std::min<int>(k, int(names.size()))), names_(std::move(names)), labels_(std::move(labels)) {
  const size_t nodes = size_t(grid_.node_count());
  ids_.assign(nodes * size_t(k_), 0);
  values_.assign(nodes * size_t(k_), 0.f);
  floor_.assign(nodes, 0.f);
  filled_.assign(nodes, 0);
}

void TopKGridField::offer(int64_t n, int32_t id, float value) {
  int32_t* ids = &ids_[size_t(n) * size_t(k_)];
  float* vals = &values_[size_t(n) * size_t(k_)];
  int slot = filled_[size_t(n)];
  if (slot == k_) {
    if (!ranks_before(value, id, vals[k_ - 1], ids[k_ - 1])) return;
    --slot; // replaces the smallest
  } else {
    ++filled_[size_t(n)];
  }
  // Insertion sort step: move larger-ranked ones down until `value` fits.
  while (slot > 0 && ranks_before(value, id, vals[slot - 1], ids[slot - 1])) {
    ids[slot] = ids[slot - 1];
    vals[slot] = vals[slot - 1];
    --slot;
  }
  ids[slot] = id;
  vals[slot] = value;
}

int64_t TopKGridField::finish(float far) {
  const size_t k = size_t(k_);
  const double h = grid_.h();
  int64_t empty = -1;
  for (size_t n = 0; n < floor_.size(); ++n) {
    int32_t* ids = &ids_[n * k];
    float* vals = &values_[n * k];
    if (filled_[n] == 0 && empty < 0) empty = int64_t(n);
    // Pad with the lowest ids not kept, as SampledField's tie rule would pick them.
    int32_t next = 0;
    for (size_t slot = filled_[n]; slot < k; ++slot) {
      while (std::find(ids, ids + slot, next) != ids + slot) ++next;
      ids[slot] = next++;
      vals[slot] = far;
    }
    // In float, like the stored values, and strictly below the last of them.
    float f = float(floor_below(vals[0], vals[k - 1], h));
    if (f >= vals[k - 1]) f = std::nextafter(vals[k - 1], -std::numeric_limits<float>::infinity());
    floor_[n] = f;
  }
  filled_.clear();
  filled_.shrink_to_fit();
  return empty;
}

TopKGridField::Cell TopKGridField::cell(const Vec3& x) const {
  const Vec3 h = grid_.spacing();
  std::array<int64_t, 3> i0{};
  Vec3 f, dfd; // fraction in the cell, and its derivative along the axis (0 outside the domain)
  for (int a = 0; a < 3; ++a) {
    const double t = (x[a] - grid_.domain.min[a]) / h[a];
    const double clamped = std::clamp(t, 0.0, double(grid_.cells[a]));
    i0[a] = std::min<int64_t>(int64_t(clamped), grid_.cells[a] - 1);
    f[a] = clamped - double(i0[a]);
    dfd[a] = t == clamped ? 1.0 / h[a] : 0.0;
  }
  Cell c{};
  for (int corner = 0; corner < 8; ++corner) {
    const int bx = corner & 1, by = (corner >> 1) & 1, bz = corner >> 2;
    const double wx = bx ? f.x() : 1 - f.x(), wy = by ? f.y() : 1 - f.y(), wz = bz ? f.z() : 1 - f.z();
    const double sx = bx ? dfd.x() : -dfd.x(), sy = by ? dfd.y() : -dfd.y(), sz = bz ? dfd.z() : -dfd.z();
    c.node[corner] = grid_.node_index(i0[0] + bx, i0[1] + by, i0[2] + bz);
    c.w[corner] = wx * wy * wz;
    c.dw[corner] = Vec3(sx * wy * wz, wx * sy * wz, wx * wy * sz);
  }
  return c;
}

float TopKGridField::node_value(int64_t n, int32_t phase) const {
  const size_t base = size_t(n) * size_t(k_);
  for (size_t slot = 0; slot < size_t(k_); ++slot)
    if (ids_[base + slot] == phase) return values_[base + slot];
  return floor_[size_t(n)];
}

double TopKGridField::floor_at(const Cell& c) const {
  double v = 0;
  for (int corner = 0; corner < 8; ++corner) v += c.w[corner] * floor_[size_t(c.node[corner])];
  return v;
}

double TopKGridField::value(int i, const Vec3& x) const {
  const Cell c = cell(x);
  double v = 0;
  for (int corner = 0; corner < 8; ++corner) v += c.w[corner] * node_value(c.node[corner], i);
  return v;
}

Vec3 TopKGridField::gradient(int i, const Vec3& x) const {
  const Cell c = cell(x);
  Vec3 g = Vec3::Zero();
  for (int corner = 0; corner < 8; ++corner) g += c.dw[corner] * double(node_value(c.node[corner], i));
  return g;
}

void TopKGridField::values(const Vec3& x, std::span<double> out) const {
  const Cell c = cell(x);
  std::fill(out.begin(), out.end(), floor_at(c));
  for (int corner = 0; corner < 8; ++corner)
    for (size_t slot = 0; slot < size_t(k_); ++slot) {
      const int32_t id = ids_[size_t(c.node[corner]) * size_t(k_) + slot];
      double v = 0;
      for (int other = 0; other < 8; ++other) v += c.w[other] * node_value(c.node[other], id);
      out[size_t(id)] = v;
    }
}

void TopKGridField::top_values(const Vec3& x, std::span<int32_t> ids, std::span<double> vals) const {
  const Cell c = cell(x);
  // The phases stored at some corner; every other phase is at the interpolated floor, below them all.
  std::array<std::pair<double, int32_t>, 8 * 16> seen;
  size_t count = 0;
  for (int corner = 0; corner < 8; ++corner)
    for (size_t slot = 0; slot < size_t(k_); ++slot) {
      const int32_t id = ids_[size_t(c.node[corner]) * size_t(k_) + slot];
      if (std::any_of(seen.begin(), seen.begin() + std::ptrdiff_t(count), [&](const auto& s) { return s.second == id; }))
        continue;
      double v = 0;
      for (int other = 0; other < 8; ++other) v += c.w[other] * node_value(c.node[other], id);
      seen[count++] = {v, id};
    }
  const size_t keep = std::min(count, ids.size());
  std::partial_sort(seen.begin(), seen.begin() + std::ptrdiff_t(keep), seen.begin() + std::ptrdiff_t(count),
                    [](const auto& a, const auto& b) { return ranks_before(a.first, a.second, b.first, b.second); });
  for (size_t slot = 0; slot < keep; ++slot) ids[slot] = seen[slot].second, vals[slot] = seen[slot].first;
  const double floor = floor_at(c);
  int32_t next = 0;
  for (size_t slot = keep; slot < ids.size(); ++slot) {
    while (std::any_of(seen.begin(), seen.begin() + std::ptrdiff_t(count), [&](const auto& s) { return s.second == next; }))
      ++next;
    ids[slot] = next++;
    vals[slot] = floor;
  }
}

} // namespace vm::detail
