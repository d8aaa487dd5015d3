#pragma once
/// @file tet_cutter.hpp
/// One tetrahedron of Algorithm 2: for every pair (i, j) of phases that can win
/// inside it, the convex polygon phi'_i = phi'_j, chopped by phi'_i >= phi'_k for
/// every other phase k, triangulated. All decisions are exact (exact.hpp) in the
/// perturbed order of node_values.hpp.

#include "create/lattice.hpp"
#include "create/limit_key.hpp"
#include "create/node_values.hpp"
#include "voronoimesh/core/types.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm::detail {

/// A triangle produced by the cutter: three limit points and the phase pair
/// (first < second), oriented with its normal pointing from first into second.
struct CutTriangle {
  std::array<LimitKey, 3> corners;
  PhasePair pair;
};

/// Counters for CreateStats.
struct CutCounters {
  uint64_t tets_cut = 0;
  uint64_t polygons = 0;
  uint64_t degenerate = 0; ///< zero signs even after perturbation (ties of ties)
  uint64_t collapsed = 0;  ///< polygons whose limit has fewer than 3 distinct points
};

class TetCutter {
public:
  TetCutter(const NodeValues& values, const TetLattice& lattice, const GridSpec& grid)
      : values_(values), lattice_(lattice), grid_(grid) {}

  /// Cuts the tetrahedron (positively oriented, lattice node ids) and appends its
  /// triangles to `out`. Returns false without work when one phase wins at all four
  /// nodes.
  bool cut(const std::array<int64_t, 4>& nodes, std::vector<CutTriangle>& out, CutCounters& counters);

  /// Appends, for every face of the tetrahedron on the domain box, the region of
  /// each phase on that face (the face chopped by phi'_a >= phi'_k for every other
  /// k), triangulated, as triangles of pair (a, outside) whose normals point out
  /// of the box. Corners are limit points like those of cut(), so they are the
  /// very vertices where the interfaces meet the box. `outside` must exceed every
  /// phase id.
  void cut_box_faces(const std::array<int64_t, 4>& nodes, int32_t outside, std::vector<CutTriangle>& out,
                     CutCounters& counters);

  /// Coordinates of a limit point.
  Vec3 position(const LimitKey& key) const;

private:
  struct PolyVertex {
    uint8_t mask = 0;             // tet-local nodes spanning its element
    uint8_t size = 0;             // phases in `phases`
    std::array<uint8_t, 4> phases{}; // local phase indices tied at the vertex
  };
  using Polygon = std::vector<PolyVertex>;

  void collect_phases(const std::array<int64_t, 4>& nodes);
  int perturbed_sign_at_node(int a, int b, int corner) const;
  /// Sign of phi'_a - phi'_b at vertex v (+1, -1, or 0 if tied even after perturbation).
  int sign_at(const PolyVertex& v, int a, int b, CutCounters& counters) const;
  LimitKey limit_key(const PolyVertex& v) const;
  LimitKey edge_limit_key(const PolyVertex& v, int ca, int cb) const;
  void initial_polygon(int a, int b, Polygon& poly) const;
  bool chop(Polygon& poly, int a, int b, int k, CutCounters& counters);
  void emit(const Polygon& poly, const PhasePair& pair, std::vector<CutTriangle>& out, CutCounters& counters);

  const NodeValues& values_;
  const TetLattice& lattice_;
  const GridSpec& grid_;
  std::array<int64_t, 4> nodes_{};
  // Phases that can win in the current tet, in increasing id order, and their
  // values at the four corners.
  std::vector<int32_t> ids_;
  std::vector<std::array<int64_t, 4>> vals_;
  // Scratch buffers reused from tet to tet.
  Polygon poly_, scratch_;
  std::vector<int> signs_;
  std::vector<size_t> candidates_;
  std::vector<char> keep_;
  std::vector<LimitKey> keys_;
  std::vector<Vec3> pos_;
};

} // namespace vm::detail
