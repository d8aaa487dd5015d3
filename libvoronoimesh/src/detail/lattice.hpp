#pragma once
/// @file lattice.hpp
/// The background tetrahedra of create: the BCC lattice over every second grid
/// node (paper Fig. 2 right) or the six-tetrahedra split of every cell (Fig. 2
/// left). Tetrahedra are enumerated slab by slab (one slab per layer along z) so
/// the work can be split across threads in a way that does not depend on how
/// many threads there are. Every tetrahedron is positively oriented.

#include "voronoimesh/create.hpp"
#include "voronoimesh/types.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm::detail {

/// Integer grid coordinates of a node.
using GridPoint = std::array<int32_t, 3>;

class TetLattice {
public:
  /// Throws InvalidInput if `kind` is bcc and a cell count is odd.
  TetLattice(const GridSpec& grid, Lattice kind);

  int num_slabs() const { return num_slabs_; }
  /// Number of tetrahedra in all slabs.
  uint64_t num_tets() const;

  /// The tetrahedron containing point `p` (grid units: node (i,j,k) is at (i,j,k))
  /// and the barycentric coordinates of p in it. Points outside the grid are
  /// clamped onto it. Used to evaluate the piecewise-linear field (tests).
  void locate(const Vec3& p, std::array<int64_t, 4>& nodes, std::array<double, 4>& bary) const;

  /// Calls f(std::array<int64_t,4> node_indices) for every tetrahedron of a slab.
  template <class F> void for_each_tet(int slab, F&& f) const;

private:
  struct Template {
    std::array<GridPoint, 4> offsets; // relative to the block origin
  };
  // Templates per block position class: index = (on_min_x, on_max_x, ...) bits.
  std::vector<Template> templates_for(const std::array<bool, 6>& on_boundary) const;

  GridSpec grid_;
  Lattice kind_;
  int block_ = 1;                 // grid cells per block edge: 2 (bcc) or 1 (cube6)
  std::array<int, 3> blocks_{};   // blocks per axis
  int num_slabs_ = 0;
  // Templates for each of the 64 boundary classes (computed once).
  std::array<std::vector<Template>, 64> by_class_;
};

template <class F> void TetLattice::for_each_tet(int slab, F&& f) const {
  const int bz = slab;
  std::array<int64_t, 4> nodes;
  for (int by = 0; by < blocks_[1]; ++by)
    for (int bx = 0; bx < blocks_[0]; ++bx) {
      int cls = (bx == 0) | (bx == blocks_[0] - 1) << 1 | (by == 0) << 2 |
                (by == blocks_[1] - 1) << 3 | (bz == 0) << 4 | (bz == blocks_[2] - 1) << 5;
      const int ox = bx * block_, oy = by * block_, oz = bz * block_;
      for (const Template& t : by_class_[cls]) {
        for (int c = 0; c < 4; ++c)
          nodes[c] = grid_.node_index(ox + t.offsets[c][0], oy + t.offsets[c][1], oz + t.offsets[c][2]);
        f(nodes);
      }
    }
}

} // namespace vm::detail
