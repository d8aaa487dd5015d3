#pragma once
/// @file lattice.hpp
/// The background tetrahedra of create: the BCC lattice over every second grid
/// node (paper Fig. 2 right) or the six-tetrahedra split of every cell (Fig. 2
/// left). Tetrahedra are enumerated slab by slab (one slab per layer along z) so
/// the work can be split across threads in a way that does not depend on how
/// many threads there are. Every tetrahedron is positively oriented.
///
/// Lattice nodes have their own compact ids: bcc uses only the grid nodes whose
/// indices are all even (cube corners) or all odd (cube centres), a quarter of
/// the grid, so per-node data is indexed by lattice id, not grid index.

#include "voronoimesh/core/types.hpp"
#include "voronoimesh/create/create.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace vm::detail {

/// Integer grid coordinates of a node.
using GridPoint = std::array<int32_t, 3>;

/// The lattice nodes on a range of grid layers (z = z0..z1), numbered
/// consecutively: what one rank of a distributed create holds values for. Their
/// ids form at most two runs of consecutive ids (bcc numbers all cube corners
/// before all centres), stored one after the other. The whole grid's window
/// numbers every node by its id.
struct NodeWindow {
  int32_t z0 = 0, z1 = -1;                       ///< grid layers
  std::array<int64_t, 2> first{0, std::numeric_limits<int64_t>::max()}; ///< first id of each run
  std::array<int64_t, 2> count{0, 0};            ///< ids in each run
  /// Nodes in the window.
  int64_t size() const { return count[0] + count[1]; }
  /// Position of node `id` (which must be in the window) in the window's numbering.
  int64_t local(int64_t id) const { return id - (id >= first[1] ? first[1] - count[0] : first[0]); }
  /// True when node `id` is in the window.
  bool contains(int64_t id) const {
    return (id >= first[0] && id < first[0] + count[0]) || (id >= first[1] && id < first[1] + count[1]);
  }
};

class TetLattice {
public:
  /// Throws InvalidInput if `kind` is bcc and a cell count is odd.
  TetLattice(const GridSpec& grid, Lattice kind);

  /// The grid whose nodes the lattice uses.
  const GridSpec& grid() const { return grid_; }
  /// Which tetrahedra: bcc or cube6.
  Lattice kind() const { return kind_; }
  int num_slabs() const { return num_slabs_; }

  /// The slabs whose tetrahedra use lattice node `id`: first..last (bcc
  /// tetrahedra join cube centres of neighbouring slabs).
  std::array<int, 2> slabs_of_node(int64_t id) const {
    const int z = grid_point(id)[2];
    // Slab s uses nodes at z in [s * block_ + reach_[0], s * block_ + reach_[1]];
    // z - reach_[1] + block_ * num_slabs_ keeps the dividend positive.
    const int first = (z - reach_[1] + block_ * num_slabs_ + block_ - 1) / block_ - num_slabs_;
    const int last = (z - reach_[0] + block_ * num_slabs_) / block_ - num_slabs_;
    return {std::max(0, first), std::min(num_slabs_ - 1, last)};
  }

  /// The grid layers (z) holding the nodes of the tetrahedra of slabs first..last.
  std::array<int32_t, 2> layers_of_slabs(int first, int last) const {
    return {std::max(0, first * block_ + reach_[0]), std::min(grid_.cells[2], last * block_ + reach_[1])};
  }
  /// The nodes on grid layers z0..z1 (clamped to the grid).
  NodeWindow window(int32_t z0, int32_t z1) const;

  /// Number of lattice nodes (ids are 0 .. num_nodes()-1).
  int64_t num_nodes() const { return num_nodes_; }
  /// Id of the lattice node at grid point (i, j, k), which must be one.
  int64_t node_id(int64_t i, int64_t j, int64_t k) const {
    if (kind_ == Lattice::cube6) return grid_.node_index(i, j, k);
    if (i & 1) return even_count_ + (i >> 1) + odd_[0] * ((j >> 1) + odd_[1] * (k >> 1));
    return (i >> 1) + even_[0] * ((j >> 1) + even_[1] * (k >> 1));
  }
  /// Grid point of a lattice node.
  GridPoint grid_point(int64_t id) const;
  /// Calls f(neighbour id) for every lattice node within one lattice block of
  /// node `id` (a superset of the nodes sharing a tetrahedron with it, box
  /// templates included): the 26 around it for cube6; for bcc the 26 same-kind
  /// nodes two grid steps away and the 8 of the other kind one step away.
  template <class F> void for_each_neighbour(int64_t id, F&& f) const {
    const GridPoint p = grid_point(id);
    auto visit = [&](int step) {
      for (int dz = -step; dz <= step; dz += step)
        for (int dy = -step; dy <= step; dy += step)
          for (int dx = -step; dx <= step; dx += step) {
            const int64_t x = p[0] + dx, y = p[1] + dy, z = p[2] + dz;
            if ((dx | dy | dz) == 0 || x < 0 || y < 0 || z < 0 || x > grid_.cells[0] || y > grid_.cells[1] ||
                z > grid_.cells[2])
              continue;
            f(node_id(x, y, z));
          }
    };
    visit(kind_ == Lattice::cube6 ? 1 : 2);
    if (kind_ == Lattice::bcc)
      for (int dz = -1; dz <= 1; dz += 2)
        for (int dy = -1; dy <= 1; dy += 2)
          for (int dx = -1; dx <= 1; dx += 2) {
            const int64_t x = p[0] + dx, y = p[1] + dy, z = p[2] + dz;
            if (x >= 0 && y >= 0 && z >= 0 && x <= grid_.cells[0] && y <= grid_.cells[1] && z <= grid_.cells[2])
              f(node_id(x, y, z));
          }
  }

  /// Lattice nodes come in rows along x with consecutive ids: row r holds
  /// `count` nodes, ids first_id.., at grid points (x0 + step * n, y, z).
  struct NodeRow {
    int64_t first_id;
    int32_t x0, y, z, step, count;
  };
  int64_t num_node_rows() const;
  NodeRow node_row(int64_t r) const;
  /// Number of tetrahedra in all slabs.
  uint64_t num_tets() const;

  /// The tetrahedron containing point `p` (grid units: node (i,j,k) is at (i,j,k))
  /// and the barycentric coordinates of p in it. Points outside the grid are
  /// clamped onto it. Used to evaluate the piecewise-linear field (tests).
  void locate(const Vec3& p, std::array<int64_t, 4>& nodes, std::array<double, 4>& bary) const;

  /// Visits the tetrahedra of a slab block by block. For each block (a 2x2x2 cube
  /// of cells for bcc, one cell for cube6), skip(nodes, count) is first asked
  /// with the distinct nodes of its tetrahedra; if it returns false,
  /// f(std::array<int64_t,4> node_indices) is called for every tetrahedron.
  /// Returns the number of tetrahedra of the slab, skipped or not.
  template <class Skip, class F> uint64_t for_each_tet(int slab, Skip&& skip, F&& f) const;

private:
  struct Template {
    std::array<GridPoint, 4> offsets; // relative to the block origin
  };
  /// The tetrahedra of one kind of block (which domain faces it touches), and
  /// their corners as indices into the block's distinct nodes.
  struct BlockTemplate {
    std::vector<Template> tets;
    std::vector<GridPoint> nodes;
    std::vector<std::array<uint8_t, 4>> corners;
  };
  std::vector<Template> templates_for(const std::array<bool, 6>& on_boundary) const;
  int block_class(const int b[3]) const {
    return (b[0] == 0) | (b[0] == blocks_[0] - 1) << 1 | (b[1] == 0) << 2 | (b[1] == blocks_[1] - 1) << 3 |
           (b[2] == 0) << 4 | (b[2] == blocks_[2] - 1) << 5;
  }

  GridSpec grid_;
  Lattice kind_;
  int block_ = 1;               // grid cells per block edge: 2 (bcc) or 1 (cube6)
  std::array<int, 3> blocks_{}; // blocks per axis
  int num_slabs_ = 0;
  int64_t num_nodes_ = 0, even_count_ = 0;
  std::array<int64_t, 3> even_{}, odd_{}; // bcc corner and centre nodes per axis
  std::array<BlockTemplate, 64> by_class_; // by block_class(), computed once
  std::array<int32_t, 2> reach_{0, 0};     // least and greatest z offset of a tetrahedron's node in a block
};

template <class Skip, class F> uint64_t TetLattice::for_each_tet(int slab, Skip&& skip, F&& f) const {
  uint64_t visited = 0;
  int64_t node[16];
  std::array<int64_t, 4> tet;
  for (int by = 0; by < blocks_[1]; ++by)
    for (int bx = 0; bx < blocks_[0]; ++bx) {
      const int b[3] = {bx, by, slab};
      const BlockTemplate& t = by_class_[block_class(b)];
      const int ox = bx * block_, oy = by * block_, oz = slab * block_;
      for (size_t c = 0; c < t.nodes.size(); ++c)
        node[c] = node_id(ox + t.nodes[c][0], oy + t.nodes[c][1], oz + t.nodes[c][2]);
      visited += t.tets.size();
      if (skip(node, int(t.nodes.size()))) continue;
      for (const auto& corners : t.corners) {
        for (int c = 0; c < 4; ++c) tet[c] = node[corners[c]];
        f(tet);
      }
    }
  return visited;
}

} // namespace vm::detail
