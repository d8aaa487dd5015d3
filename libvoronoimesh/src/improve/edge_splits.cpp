/// @file improve/edge_splits.cpp
/// split_long_edges() (improve/edge_splits.hpp).

#include "improve/edge_splits.hpp"

#include "core/huge_pages.hpp"
#include "core/indices_where.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <tuple>

namespace vm::detail {

size_t split_long_edges(NodeMesh& m, std::vector<double>& target, std::vector<uint8_t>& held,
                        std::vector<std::array<int32_t, 2>>& parents, std::vector<int32_t>& origin,
                        Unsplit* replaced) {
  const size_t nt = m.num_triangles(), old_nodes = m.num_nodes();
  // Side 3 t + k of triangle t runs from its corner k to the next.
  auto ends = [&](size_t side) {
    const auto& t = m.triangles[side / 3];
    return std::pair{t[side % 3], t[(side + 1) % 3]};
  };
  std::vector<uint8_t> is_long(3 * nt);
  parallel_for_each_index(3 * nt, [&](size_t side) {
    const auto [u, v] = ends(side);
    const double len = (m.points[size_t(u)] - m.points[size_t(v)]).norm();
    is_long[side] =
        len > kLongEdge * std::min(target[size_t(u)], target[size_t(v)]) && !held[size_t(u)] && !held[size_t(v)];
  });
  // The long sides by edge, then by place: each edge's first side leads its
  // group. Midpoints are numbered in the order of their edges' first sides,
  // as a scan of the triangles meets them (the same mesh for any thread count).
  struct Side {
    uint64_t edge;
    uint32_t at;
  };
  const std::vector<int32_t> long_sides =
      indices_where(3 * nt, [&](size_t side) { return is_long[side] != 0; });
  if (long_sides.empty()) return 0;
  std::vector<Side> sides(long_sides.size());
  parallel_for_each_index(sides.size(), [&](size_t i) {
    const auto [u, v] = ends(size_t(long_sides[i]));
    sides[i] = {uint64_t(uint32_t(std::min(u, v))) << 32 | uint32_t(std::max(u, v)), uint32_t(long_sides[i])};
  });
  parallel_sort(sides.begin(), sides.end(),
                [](const Side& x, const Side& y) { return std::tie(x.edge, x.at) < std::tie(y.edge, y.at); });
  std::vector<std::pair<uint32_t, uint32_t>> leads; // (first side, its group's start in `sides`)
  for (size_t i = 0; i < sides.size(); ++i)
    if (i == 0 || sides[i].edge != sides[i - 1].edge) leads.push_back({sides[i].at, uint32_t(i)});
  parallel_sort(leads.begin(), leads.end(), std::less<std::pair<uint32_t, uint32_t>>());
  // This call's arrays are fresh memory (on 1M triangles 50 MB, 0.1 s of page
  // faults in one thread): on huge pages.
  std::vector<int32_t> mid; // the midpoint on each side, or -1
  assign_on_huge_pages(mid, 3 * nt, -1);
  const size_t made = leads.size();
  m.points.resize(old_nodes + made);
  target.resize(old_nodes + made);
  held.resize(old_nodes + made, 0);
  parents.resize(parents.size() + made);
  const size_t first_parent = parents.size() - made;
  parallel_for_each_index(made, [&](size_t r) {
    const auto [u, v] = ends(leads[r].first);
    const auto node = int32_t(old_nodes + r);
    m.points[size_t(node)] = 0.5 * (m.points[size_t(u)] + m.points[size_t(v)]);
    target[size_t(node)] = 0.5 * (target[size_t(u)] + target[size_t(v)]);
    parents[first_parent + r] = {u, v};
    for (size_t i = leads[r].second; i < sides.size() && sides[i].edge == sides[leads[r].second].edge; ++i)
      mid[sides[i].at] = node;
  });
  // Each triangle's pieces (one, or one more than its split sides), at their
  // place in the new list (in triangle order).
  auto splits = [&](size_t t) { return (mid[3 * t] >= 0) + (mid[3 * t + 1] >= 0) + (mid[3 * t + 2] >= 0); };
  std::vector<size_t> first_piece(nt + 1, 0);
  for (size_t t = 0; t < nt; ++t) {
    const int split = splits(t);
    first_piece[t + 1] = first_piece[t] + size_t(split == 0 ? 1 : split + 1);
  }
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<PhasePair> pairs;
  std::vector<int32_t> origins;
  resize_on_huge_pages(triangles, first_piece[nt]);
  resize_on_huge_pages(pairs, first_piece[nt]);
  resize_on_huge_pages(origins, first_piece[nt], -1);
  parallel_for_each_index(nt, [&](size_t i) {
    const auto t = m.triangles[i];
    const PhasePair p = m.pairs[i];
    size_t at = first_piece[i];
    auto add = [&](int32_t a, int32_t b, int32_t c) {
      triangles[at] = {a, b, c};
      pairs[at++] = p;
    };
    const std::array<int32_t, 3> on{mid[3 * i], mid[3 * i + 1], mid[3 * i + 2]};
    const int split = splits(i);
    if (split == 0) {
      add(t[0], t[1], t[2]);
      origins[first_piece[i]] = origin[i];
    } else if (split == 3) {
      add(t[0], on[0], on[2]);
      add(on[0], t[1], on[1]);
      add(on[2], on[1], t[2]);
      add(on[0], on[1], on[2]);
    } else {
      // Rotate so that edge (r0, r1) is split, and with two splits also (r1, r2).
      int k = 0;
      while (!(on[size_t(k)] >= 0 && (split == 1 || on[size_t((k + 1) % 3)] >= 0))) ++k;
      const int32_t r0 = t[size_t(k)], r1 = t[size_t((k + 1) % 3)], r2 = t[size_t((k + 2) % 3)];
      const int32_t m01 = on[size_t(k)];
      if (split == 1) {
        add(r0, m01, r2);
        add(m01, r1, r2);
      } else {
        const int32_t m12 = on[size_t((k + 1) % 3)];
        add(m01, r1, m12);
        // The quad r0, m01, m12, r2 by its shorter diagonal.
        const auto& x = m.points;
        if ((x[size_t(r0)] - x[size_t(m12)]).squaredNorm() <= (x[size_t(m01)] - x[size_t(r2)]).squaredNorm()) {
          add(r0, m01, m12);
          add(r0, m12, r2);
        } else {
          add(r0, m01, r2);
          add(m01, m12, r2);
        }
      }
    }
  });
  if (replaced) *replaced = {std::move(m.triangles), std::move(m.pairs), std::move(origin)};
  m.triangles = std::move(triangles);
  m.pairs = std::move(pairs);
  origin = std::move(origins);
  return made;
}

} // namespace vm::detail
