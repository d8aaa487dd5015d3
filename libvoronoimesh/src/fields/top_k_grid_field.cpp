#include "fields/top_k_grid_field.hpp"

#include "core/atomic_lowest.hpp"
#include "core/huge_pages.hpp"
#include "core/parallel.hpp"
#include "fields/top_k.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace vm::detail {

namespace {

std::atomic<uint64_t> next_serial{1};

constexpr int64_t kBrickNodes = TopKGridField::kBrick * TopKGridField::kBrick * TopKGridField::kBrick;

/// Fills `ids[from..k)` with the lowest ids not among ids[0..from), as SampledField's tie rule would pick them.
void pad_ids(int16_t* ids, size_t from, size_t k) {
  int32_t next = 0;
  for (size_t slot = from; slot < k; ++slot) {
    while (std::find(ids, ids + slot, next) != ids + slot) ++next;
    ids[slot] = int16_t(next++);
  }
}

/// The floor of a node whose kept values run from `first` down to `last`: in
/// float, like the stored values, and strictly below the last of them.
float node_floor(float first, float last, double h) {
  float f = float(floor_below(first, last, h));
  if (f >= last) f = std::nextafter(last, -std::numeric_limits<float>::infinity());
  return f;
}

} // namespace

TopKGridField::TopKGridField(const GridSpec& grid, int k, std::vector<std::string> names, std::vector<int32_t> labels,
                             std::vector<int32_t> uniform, float top)
    : serial_(next_serial++), grid_(grid), spacing_(grid.spacing()), k_(std::min<int>(k, int(names.size()))), names_(std::move(names)), labels_(std::move(labels)),
      top_(top) {
  const auto nodes = grid_.nodes();
  for (size_t a = 0; a < 3; ++a) bricks_[a] = (nodes[a] + kBrick - 1) / kBrick;
  const size_t count = size_t(bricks_[0] * bricks_[1] * bricks_[2]);
  if (uniform.empty()) uniform.assign(count, -1);
  brick_.resize(count);
  int32_t dense = 0;
  for (size_t b = 0; b < count; ++b) brick_[b] = uniform[b] >= 0 ? -1 - uniform[b] : dense++;
  const size_t dense_nodes = size_t(dense) * size_t(kBrickNodes);
  assign_on_huge_pages(ids_, dense_nodes * size_t(k_), 0);
  assign_on_huge_pages(values_, dense_nodes * size_t(k_), 0.f);
  assign_on_huge_pages(floor_, dense_nodes, 0.f);
  assign_on_huge_pages(filled_, dense_nodes, 0);
}

size_t TopKGridField::slot(int64_t i, int64_t j, int64_t k) const {
  const int64_t b = brick_of(i, j, k);
  const int64_t local = i % kBrick + kBrick * (j % kBrick + kBrick * (k % kBrick));
  return size_t(int64_t(brick_[size_t(b)]) * kBrickNodes + local);
}

void TopKGridField::offer(int64_t n, int32_t id, float value) {
  const auto nodes = grid_.nodes();
  offer(n % nodes[0], n / nodes[0] % nodes[1], n / (nodes[0] * nodes[1]), id, value);
}

void TopKGridField::offer(int64_t i, int64_t j, int64_t k, int32_t id, float value) {
  const size_t s = slot(i, j, k);
  int16_t* ids = &ids_[s * size_t(k_)];
  float* vals = &values_[s * size_t(k_)];
  int at = filled_[s];
  if (at == k_) {
    if (!ranks_before(value, id, vals[k_ - 1], ids[k_ - 1])) return;
    --at; // replaces the smallest
  } else {
    ++filled_[s];
  }
  // Insertion sort step: move larger-ranked ones down until `value` fits.
  while (at > 0 && ranks_before(value, id, vals[at - 1], ids[at - 1])) {
    ids[at] = ids[at - 1];
    vals[at] = vals[at - 1];
    --at;
  }
  ids[at] = int16_t(id);
  vals[at] = value;
}

void TopKGridField::lead(int64_t i, int64_t j, int64_t k, int32_t id, float margin, float far) {
  const size_t s = slot(i, j, k);
  int16_t* ids = &ids_[s * size_t(k_)];
  float* vals = &values_[s * size_t(k_)];
  const int filled = filled_[s];
  // The values are in rank order: the first other phase is the largest one.
  const int own = int(std::find(ids, ids + filled, int16_t(id)) - ids);
  const int first_other = own == 0 ? 1 : 0;
  float other = first_other < filled ? vals[first_other] : far;
  const int others_offered = filled - (own < filled ? 1 : 0);
  if (others_offered < num_phases() - 1) other = std::max(other, far);
  const float wanted = other + margin;
  if (own < filled && vals[own] >= wanted) return;
  // Out of its slot (or in place of the smallest, when not kept), then first.
  int from = own < filled ? own : std::min(filled, k_ - 1);
  if (own == filled && filled < k_) ++filled_[s];
  for (; from > 0; --from) ids[from] = ids[from - 1], vals[from] = vals[from - 1];
  ids[0] = int16_t(id);
  vals[0] = wanted;
}

int64_t TopKGridField::finish(float far) {
  const size_t k = size_t(k_);
  const double h = grid_.h();
  const auto nodes = grid_.nodes();
  // The lowest node offered nothing: a minimum, whichever thread finds which.
  std::atomic<int64_t> empty{std::numeric_limits<int64_t>::max()};
  parallel_for_each_index(brick_.size(), [&](size_t b) {
    if (brick_[b] < 0) return;
    const int64_t bi = int64_t(b) % bricks_[0], bj = int64_t(b) / bricks_[0] % bricks_[1], bk = int64_t(b) / (bricks_[0] * bricks_[1]);
    for (int64_t k3 = bk * kBrick; k3 < std::min(nodes[2], (bk + 1) * kBrick); ++k3)
      for (int64_t j3 = bj * kBrick; j3 < std::min(nodes[1], (bj + 1) * kBrick); ++j3)
        for (int64_t i3 = bi * kBrick; i3 < std::min(nodes[0], (bi + 1) * kBrick); ++i3) {
          const size_t s = slot(i3, j3, k3);
          if (filled_[s] == 0) {
            const int64_t n = grid_.node_index(i3, j3, k3);
            detail::lower_atomically(empty, n);
          }
          int16_t* ids = &ids_[s * k];
          float* vals = &values_[s * k];
          pad_ids(ids, filled_[s], k);
          std::fill(vals + filled_[s], vals + k, far);
          floor_[s] = node_floor(vals[0], vals[k - 1], h);
        }
  }, 64);
  filled_.clear();
  filled_.shrink_to_fit();
  uniform_ids_.assign(size_t(num_phases()) * k, 0);
  uniform_values_.assign(k, far);
  uniform_values_[0] = top_;
  for (size_t p = 0; p < size_t(num_phases()); ++p) {
    uniform_ids_[p * k] = int16_t(p);
    pad_ids(&uniform_ids_[p * k], 1, k);
  }
  uniform_floor_ = node_floor(top_, k > 1 ? far : top_, h);
  return empty == std::numeric_limits<int64_t>::max() ? -1 : empty.load();
}

const TopKGridField::Cell& TopKGridField::cell(const Vec3& x) const {
  thread_local struct {
    uint64_t serial = 0;
    Vec3 x;
    Cell cell;
  } last;
  if (last.serial != serial_ || last.x != x) {
    Place p;
    locate(x, p);
    fill_cell(p, last.cell, true);
    last.serial = serial_, last.x = x;
  }
  return last.cell;
}

void TopKGridField::locate(const Vec3& x, Place& p) const {
  uint64_t brick[3][2]; // per axis, the brick of the cell's lower and upper node
  for (int a = 0; a < 3; ++a) {
    const double t = grid_steps(a, x[a]), in_grid = clamped(a, t);
    const uint64_t i0 = lower_node(a, in_grid);
    p.lower[a] = i0;
    p.f[a] = in_grid - double(i0);
    p.inside[a] = t == in_grid;
    for (uint64_t side = 0; side < 2; ++side) brick[a][side] = (i0 + side) / kBrick;
  }
  const auto nb0 = uint64_t(bricks_[0]), nb1 = uint64_t(bricks_[1]);
  for (int corner = 0; corner < 8; ++corner)
    p.brick[corner] = brick_[brick[0][corner & 1] + nb0 * (brick[1][(corner >> 1) & 1] + nb1 * brick[2][corner >> 2])];
  // Corners all in uniform bricks of one phase hold the same values.
  const int32_t b0 = p.brick[0];
  p.uniform = b0 < 0 && std::all_of(p.brick + 1, p.brick + 8, [&](int32_t b) { return b == b0; }) ? -1 - b0 : -1;
}

void TopKGridField::fill_cell(const Place& p, Cell& c, bool gradients) const {
  const Vec3& f = p.f;
  Vec3 dfd; // the fractions' derivatives
  for (int a = 0; a < 3; ++a) dfd[a] = p.inside[a] ? 1.0 / spacing_[a] : 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int bx = corner & 1, by = (corner >> 1) & 1, bz = corner >> 2;
    const double wx = bx ? f.x() : 1 - f.x(), wy = by ? f.y() : 1 - f.y(), wz = bz ? f.z() : 1 - f.z();
    const int32_t b = p.brick[corner];
    if (b < 0) {
      c.node[corner] = {&uniform_ids_[size_t(-1 - b) * size_t(k_)], uniform_values_.data(), uniform_floor_};
    } else {
      const uint64_t li = (p.lower[0] + uint64_t(bx)) % kBrick, lj = (p.lower[1] + uint64_t(by)) % kBrick,
                     lk = (p.lower[2] + uint64_t(bz)) % kBrick;
      const size_t s = size_t(uint64_t(b) * kBrickNodes + li + kBrick * (lj + kBrick * lk));
      c.node[corner] = {&ids_[s * size_t(k_)], &values_[s * size_t(k_)], floor_[s]};
    }
    c.w[corner] = wx * wy * wz;
    if (gradients) {
      const double sx = bx ? dfd.x() : -dfd.x(), sy = by ? dfd.y() : -dfd.y(), sz = bz ? dfd.z() : -dfd.z();
      c.dw[corner] = Vec3(sx * wy * wz, wx * sy * wz, wx * wy * sz);
    }
  }
}

float TopKGridField::node_value(const Node& n, int32_t phase) const {
  for (size_t slot = 0; slot < size_t(k_); ++slot)
    if (n.ids[slot] == phase) return n.vals[slot];
  return n.floor;
}

double TopKGridField::floor_at(const Cell& c) const {
  double v = 0;
  for (int corner = 0; corner < 8; ++corner) v += c.w[corner] * c.node[corner].floor;
  return v;
}

double TopKGridField::value(int i, const Vec3& x) const {
  const Cell& c = cell(x);
  double v = 0;
  for (int corner = 0; corner < 8; ++corner) v += c.w[corner] * node_value(c.node[corner], i);
  return v;
}

Vec3 TopKGridField::gradient(int i, const Vec3& x) const {
  const Cell& c = cell(x);
  Vec3 g = Vec3::Zero();
  for (int corner = 0; corner < 8; ++corner) g += c.dw[corner] * double(node_value(c.node[corner], i));
  return g;
}

void TopKGridField::values(const Vec3& x, std::span<double> out) const {
  const Cell& c = cell(x);
  std::fill(out.begin(), out.end(), floor_at(c));
  for (int corner = 0; corner < 8; ++corner)
    for (size_t slot = 0; slot < size_t(k_); ++slot) {
      const int32_t id = c.node[corner].ids[slot];
      double v = 0;
      for (int other = 0; other < 8; ++other) v += c.w[other] * node_value(c.node[other], id);
      out[size_t(id)] = v;
    }
}

void TopKGridField::keep_nodes(std::vector<int64_t> nodes) {
  kept_ = std::move(nodes);
  brick_keeps_.assign(brick_.size(), 0);
  const auto n = grid_.nodes();
  for (int64_t node : kept_) {
    const int64_t i = node % n[0], j = node / n[0] % n[1], k = node / (n[0] * n[1]);
    brick_keeps_[size_t(brick_of(i, j, k))] = 1;
  }
}

void TopKGridField::kept_points(const Vec3& lo, const Vec3& hi, std::vector<Vec3>& out) const {
  if (kept_.empty()) return;
  const auto nodes = grid_.nodes();
  std::array<int64_t, 3> first, last;
  for (int a = 0; a < 3; ++a) {
    first[size_t(a)] = std::max<int64_t>(0, int64_t(std::ceil((lo[a] - grid_.domain.min[a]) / spacing_[a])));
    last[size_t(a)] = std::min(nodes[size_t(a)] - 1, int64_t(std::floor((hi[a] - grid_.domain.min[a]) / spacing_[a])));
  }
  for (int64_t k = first[2]; k <= last[2]; ++k)
    for (int64_t j = first[1]; j <= last[1]; ++j)
      for (int64_t i = first[0]; i <= last[0]; ++i) {
        // Most boxes hold no kept node: their bricks say so without a search.
        if (!brick_keeps_[size_t(brick_of(i, j, k))]) continue;
        if (std::binary_search(kept_.begin(), kept_.end(), grid_.node_index(i, j, k)))
          out.push_back(grid_.domain.min + Vec3(double(i), double(j), double(k)).cwiseProduct(spacing_));
      }
}

bool TopKGridField::same_top_values(const Vec3& lo, const Vec3& hi) const {
  if (!lo.allFinite() || !hi.allFinite()) return false;
  // The bricks of every corner of every cell a point of the box interpolates
  // from (the cells of lo and hi and those between: locate() is monotone).
  std::array<uint64_t, 3> first{}, last{};
  for (int a = 0; a < 3; ++a) {
    first[size_t(a)] = lower_node(a, clamped(a, grid_steps(a, lo[a]))) / kBrick;
    last[size_t(a)] = (lower_node(a, clamped(a, grid_steps(a, hi[a]))) + 1) / kBrick;
  }
  const auto nb0 = uint64_t(bricks_[0]), nb1 = uint64_t(bricks_[1]);
  const int32_t one = brick_[first[0] + nb0 * (first[1] + nb1 * first[2])];
  if (one >= 0) return false; // values stored node by node
  for (uint64_t k = first[2]; k <= last[2]; ++k)
    for (uint64_t j = first[1]; j <= last[1]; ++j)
      for (uint64_t i = first[0]; i <= last[0]; ++i)
        if (brick_[i + nb0 * (j + nb1 * k)] != one) return false;
  return true;
}

void TopKGridField::top_values(const Vec3& x, std::span<int32_t> ids, std::span<double> vals) const {
  Place p; // not cell(): sampling asks once per point
  locate(x, p);
  // The phases stored at some corner (plain arrays: this runs once per grid
  // node when sampling); every other phase is at the interpolated floor, below them all.
  int32_t seen_id[8 * 16];
  double seen_value[8 * 16];
  size_t count = 0;
  double floor = 0;
  if (p.uniform >= 0) {
    // Every corner holds the same values, already in rank order: interpolation
    // gives them back, so the cell (most of a label volume's) is not filled.
    for (size_t slot = 0; slot < size_t(k_); ++slot)
      seen_id[count] = uniform_ids_[size_t(p.uniform) * size_t(k_) + slot], seen_value[count++] = uniform_values_[slot];
    floor = uniform_floor_;
  } else {
    Cell c;
    fill_cell(p, c, false);
    // Each phase's value at every corner (the corner's floor where not
    // stored), gathered in one pass over the corners' slots instead of
    // node_value()'s search per phase and corner; summed in corner order, as value() does.
    float at[8 * 16][8];
    for (int corner = 0; corner < 8; ++corner)
      for (size_t slot = 0; slot < size_t(k_); ++slot) {
        const int32_t id = c.node[corner].ids[slot];
        const size_t d = size_t(std::find(seen_id, seen_id + count, id) - seen_id);
        if (d == count) {
          seen_id[count++] = id;
          for (int other = 0; other < 8; ++other) at[d][other] = c.node[other].floor;
        }
        at[d][corner] = c.node[corner].vals[slot];
      }
    for (size_t d = 0; d < count; ++d) {
      double v = 0;
      for (int corner = 0; corner < 8; ++corner) v += c.w[corner] * at[d][corner];
      seen_value[d] = v;
    }
    floor = floor_at(c);
  }
  int order[8 * 16];
  for (size_t i = 0; i < count; ++i) order[i] = int(i);
  const size_t keep = std::min(count, ids.size());
  if (p.uniform < 0)
    std::partial_sort(order, order + keep, order + count, [&](int a, int b) {
      return ranks_before(seen_value[a], seen_id[a], seen_value[b], seen_id[b]);
    });
  for (size_t slot = 0; slot < keep; ++slot) ids[slot] = seen_id[order[slot]], vals[slot] = seen_value[order[slot]];
  int32_t next = 0;
  for (size_t slot = keep; slot < ids.size(); ++slot) {
    while (std::find(seen_id, seen_id + count, next) != seen_id + count) ++next;
    ids[slot] = next++;
    vals[slot] = floor;
  }
}

} // namespace vm::detail
