#include "create/lattice.hpp"

#include "voronoimesh/core/errors.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace vm::detail {
namespace {

int64_t orientation(const std::array<GridPoint, 4>& p) {
  auto d = [&](int c, int k) { return int64_t(p[c][k]) - p[0][k]; };
  return d(1, 0) * (d(2, 1) * d(3, 2) - d(2, 2) * d(3, 1)) -
         d(1, 1) * (d(2, 0) * d(3, 2) - d(2, 2) * d(3, 0)) +
         d(1, 2) * (d(2, 0) * d(3, 1) - d(2, 1) * d(3, 0));
}

GridPoint add(GridPoint a, int axis, int amount) {
  a[axis] += amount;
  return a;
}

} // namespace

TetLattice::TetLattice(const GridSpec& grid, Lattice kind) : grid_(grid), kind_(kind) {
  block_ = kind == Lattice::bcc ? 2 : 1;
  for (int a = 0; a < 3; ++a) {
    if (grid.cells[a] < block_ || grid.cells[a] % block_ != 0)
      throw InvalidInput("lattice: the bcc lattice needs an even number of grid cells per axis, got " +
                         std::to_string(grid.cells[a]));
    blocks_[a] = grid.cells[a] / block_;
  }
  num_slabs_ = blocks_[2];
  if (kind == Lattice::bcc) {
    for (int a = 0; a < 3; ++a) {
      even_[a] = blocks_[a] + 1;
      odd_[a] = blocks_[a];
    }
    even_count_ = even_[0] * even_[1] * even_[2];
    num_nodes_ = even_count_ + odd_[0] * odd_[1] * odd_[2];
  } else {
    num_nodes_ = grid.node_count();
  }
  for (int cls = 0; cls < 64; ++cls) {
    std::array<bool, 6> on;
    for (int b = 0; b < 6; ++b) on[b] = (cls >> b) & 1;
    BlockTemplate& bt = by_class_[cls];
    bt.tets = templates_for(on);
    for (const Template& t : bt.tets) {
      std::array<uint8_t, 4> corners;
      for (int c = 0; c < 4; ++c) {
        auto it = std::find(bt.nodes.begin(), bt.nodes.end(), t.offsets[c]);
        corners[c] = uint8_t(it - bt.nodes.begin());
        if (it == bt.nodes.end()) bt.nodes.push_back(t.offsets[c]);
        reach_[0] = std::min(reach_[0], t.offsets[c][2]);
        reach_[1] = std::max(reach_[1], t.offsets[c][2]);
      }
      bt.corners.push_back(corners);
    }
  }
}

GridPoint TetLattice::grid_point(int64_t id) const {
  if (kind_ == Lattice::cube6) {
    auto n = grid_.nodes();
    return {int32_t(id % n[0]), int32_t(id / n[0] % n[1]), int32_t(id / (n[0] * n[1]))};
  }
  const bool odd = id >= even_count_;
  const auto& n = odd ? odd_ : even_;
  if (odd) id -= even_count_;
  const int32_t o = odd ? 1 : 0;
  return {int32_t(2 * (id % n[0])) + o, int32_t(2 * (id / n[0] % n[1])) + o, int32_t(2 * (id / (n[0] * n[1]))) + o};
}

NodeWindow TetLattice::window(int32_t z0, int32_t z1) const {
  NodeWindow w;
  w.z0 = std::max(0, z0);
  w.z1 = std::min(grid_.cells[2], z1);
  if (w.z1 < w.z0) return w;
  if (kind_ == Lattice::cube6) {
    const int64_t layer = grid_.nodes()[0] * grid_.nodes()[1];
    w.first[0] = w.z0 * layer;
    w.count[0] = (w.z1 - w.z0 + 1) * layer;
    return w;
  }
  // Corners lie on even layers, centres on odd ones; each kind is numbered layer by layer.
  auto run = [&](int parity, int64_t per_layer, int64_t offset, int r) {
    const int32_t lo = w.z0 + ((w.z0 & 1) != parity), hi = w.z1 - ((w.z1 & 1) != parity);
    w.first[r] = offset + int64_t(lo >> 1) * per_layer;
    w.count[r] = hi >= lo ? int64_t((hi - lo) / 2 + 1) * per_layer : 0;
  };
  run(0, even_[0] * even_[1], 0, 0);
  run(1, odd_[0] * odd_[1], even_count_, 1);
  return w;
}

int64_t TetLattice::num_node_rows() const {
  if (kind_ == Lattice::cube6) return grid_.nodes()[1] * grid_.nodes()[2];
  return even_[1] * even_[2] + odd_[1] * odd_[2];
}

TetLattice::NodeRow TetLattice::node_row(int64_t r) const {
  if (kind_ == Lattice::cube6) {
    auto n = grid_.nodes();
    return {r * n[0], 0, int32_t(r % n[1]), int32_t(r / n[1]), 1, int32_t(n[0])};
  }
  if (r < even_[1] * even_[2])
    return {r * even_[0], 0, int32_t(2 * (r % even_[1])), int32_t(2 * (r / even_[1])), 2, int32_t(even_[0])};
  r -= even_[1] * even_[2];
  return {even_count_ + r * odd_[0], 1, int32_t(2 * (r % odd_[1]) + 1), int32_t(2 * (r / odd_[1]) + 1), 2,
          int32_t(odd_[0])};
}

uint64_t TetLattice::num_tets() const {
  uint64_t n = 0;
  for (int cls = 0; cls < 64; ++cls) {
    // Count blocks of this class.
    uint64_t count = 1;
    for (int a = 0; a < 3; ++a) {
      bool lo = (cls >> (2 * a)) & 1, hi = (cls >> (2 * a + 1)) & 1;
      int nb = blocks_[a];
      uint64_t c;
      if (nb == 1) c = (lo && hi) ? 1 : 0;
      else if (lo && hi) c = 0;
      else if (lo || hi) c = 1;
      else c = uint64_t(nb - 2);
      count *= c;
    }
    n += count * by_class_[cls].tets.size();
  }
  return n;
}

std::vector<TetLattice::Template> TetLattice::templates_for(const std::array<bool, 6>& on) const {
  std::vector<Template> out;
  auto push = [&](std::array<GridPoint, 4> p) {
    if (orientation(p) < 0) std::swap(p[2], p[3]);
    out.push_back({p});
  };
  if (kind_ == Lattice::cube6) {
    // Kuhn split along the main diagonal: conforming across cells because every
    // face is cut along the diagonal through its lowest corner.
    int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (auto& p : perm) {
      GridPoint v0{0, 0, 0};
      GridPoint v1 = add(v0, p[0], 1);
      GridPoint v2 = add(v1, p[1], 1);
      push({v0, v1, v2, GridPoint{1, 1, 1}});
    }
    return out;
  }
  // BCC: the block is a 2x2x2 cube with its centre at (1,1,1). Across each
  // interior face two centres and the four edges of the face make four tets;
  // a face on the domain boundary closes the cube with a pyramid split in two.
  const GridPoint centre{1, 1, 1};
  for (int axis = 0; axis < 3; ++axis) {
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      GridPoint base{0, 0, 0};
      base[axis] = 2 * side;
      std::array<GridPoint, 4> square = {base, add(base, u, 2), add(add(base, u, 2), v, 2), add(base, v, 2)};
      bool boundary = on[2 * axis + side];
      if (boundary) {
        // The diagonal through the square's lowest corner, like cube6 does.
        push({centre, square[0], square[1], square[2]});
        push({centre, square[0], square[2], square[3]});
      } else if (side == 1) {
        GridPoint next = add(centre, axis, 2);
        for (int e = 0; e < 4; ++e) push({centre, next, square[e], square[(e + 1) % 4]});
      }
    }
  }
  return out;
}

void TetLattice::locate(const Vec3& p, std::array<int64_t, 4>& nodes, std::array<double, 4>& bary) const {
  int home[3];
  for (int a = 0; a < 3; ++a) {
    double u = std::clamp(p[a], 0.0, double(grid_.cells[a]));
    home[a] = std::min(int(u / block_), blocks_[a] - 1);
  }
  // A block's templates cover the tets across its upper faces; those across its
  // lower faces belong to the neighbours below, so search those too.
  double best = -INFINITY;
  for (int below = -1; below < 3; ++below) {
    int b[3] = {home[0], home[1], home[2]};
    if (below >= 0 && --b[below] < 0) continue;
    const Vec3 origin(b[0] * block_, b[1] * block_, b[2] * block_);
    for (const Template& t : by_class_[block_class(b)].tets) {
      Vec3 v[4];
      for (int c = 0; c < 4; ++c) v[c] = origin + Vec3(t.offsets[c][0], t.offsets[c][1], t.offsets[c][2]);
      Eigen::Matrix3d m;
      m << v[1] - v[0], v[2] - v[0], v[3] - v[0];
      Vec3 l = m.inverse() * (p - v[0]);
      std::array<double, 4> w{1 - l.sum(), l[0], l[1], l[2]};
      double worst = *std::min_element(w.begin(), w.end());
      if (worst > best) { // the tet the point is deepest inside (robust on faces)
        best = worst;
        bary = w;
        for (int c = 0; c < 4; ++c)
          nodes[c] = node_id(int64_t(v[c].x()), int64_t(v[c].y()), int64_t(v[c].z()));
      }
    }
  }
}

} // namespace vm::detail
