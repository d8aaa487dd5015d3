#pragma once
/// @file tiny_loop_volume.hpp
/// A label volume on which create once left a closed triple curve far smaller
/// than a cell (create/tiny_loops.hpp), for the one-process and the MPI tests.

#include <cstdint>
#include <vector>

namespace vm::test {

/// A 6^3 crop of a random label volume (`make_label_volume ellipsoids 32 4 V 1`,
/// voxels 16-21, 6-11 and 6-11; x fastest, z slowest): labels 1 and 2 cross a
/// lattice edge where the background nearly ties them, so the three met on a
/// closed triple curve of three nodes 0.006 of a cell across around it, with
/// triangles of q 0.010 that 20 iterations raised to 0.015 at most (the whole
/// volume: 0.012).
inline std::vector<int32_t> tiny_loop_labels() {
  return {
      0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
      0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0,
      0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
      1, 1, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 1, 1, 2, 2, 2, 2, 2, 1, 2, 2, 2, 2, 1, 1, 1, 1, 1, 1, 1, 1,
      1, 1, 1, 1, 1, 0, 2, 2, 2, 2, 1, 1, 2, 2, 2, 2, 2, 1, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 1,
      1, 1, 1, 1, 1, 0, 2, 2, 2, 2, 2, 1, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2,
  };
}

} // namespace vm::test
