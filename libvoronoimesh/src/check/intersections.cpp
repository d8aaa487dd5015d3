/// @file check/intersections.cpp
/// Exact self-intersection test of a node-level mesh: overlapping triangle
/// boxes give candidate pairs (check/box_pairs.hpp), exact predicates decide
/// each pair (check/triangle_pair.hpp).

#include "voronoimesh/check/intersections.hpp"

#include "voronoimesh/core/errors.hpp"

#include "check/box_pairs.hpp"
#include "check/embedded_fans.hpp"
#include "check/self_intersections.hpp"
#include "check/triangle_pair.hpp"
#include "core/indices_where.hpp"
#include "core/key_set.hpp"
#include "core/parallel.hpp"
#include "core/unset_vector.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace vm {

namespace {

using detail::Bounds;
using detail::MeshArrays;

/// Intersecting pairs found by one thread: all counted, the smallest kept.
struct Found {
  size_t count = 0;
  std::vector<std::array<int32_t, 2>> smallest; ///< a max-heap of at most `limit` pairs

  void add(int32_t t, int32_t s, size_t limit) {
    ++count;
    const std::array<int32_t, 2> pair{std::min(t, s), std::max(t, s)};
    if (smallest.size() < limit) {
      smallest.push_back(pair);
      std::push_heap(smallest.begin(), smallest.end());
    } else if (limit > 0 && pair < smallest.front()) {
      std::pop_heap(smallest.begin(), smallest.end());
      smallest.back() = pair;
      std::push_heap(smallest.begin(), smallest.end());
    }
  }
};

void check_input(const MeshArrays& m, bool needs_pairs) {
  if (needs_pairs && m.pairs.size() != m.triangles.size())
    throw InvalidInput("find_self_intersections: one phase pair per triangle expected");
  // Scanned in parallel (each check scans the whole mesh); of bad node ids, the first bad triangle's is named.
  if (!detail::indices_where(m.points.size(), [&](size_t v) { return !m.points[v].allFinite(); }).empty())
    throw InvalidInput("find_self_intersections: non-finite node coordinate");
  const auto n = int32_t(m.points.size());
  auto out_of_range = [&](int32_t id) { return id < 0 || id >= n; };
  const std::vector<int32_t> bad = detail::indices_where(m.triangles.size(), [&](size_t t) {
    return std::any_of(m.triangles[t].begin(), m.triangles[t].end(), out_of_range);
  });
  if (!bad.empty()) {
    const auto& tri = m.triangles[size_t(bad.front())];
    throw InvalidInput("find_self_intersections: triangle " + std::to_string(bad.front()) + " has node id " +
                       std::to_string(*std::find_if(tri.begin(), tri.end(), out_of_range)) + " out of range");
  }
}


/// The triangles whose bounding box can overlap that of a flagged triangle (the
/// flagged ones included), in increasing order, through a hash of coarse cells
/// covering the flagged boxes; all triangles when a third or more are flagged
/// (no gain then). Lets a check after a few local changes skip most of the mesh.
std::vector<int32_t> near_flagged(const MeshArrays& m, std::span<const uint8_t> flagged) {
  const size_t nt = m.triangles.size();
  auto box_of = [&](size_t t) { return detail::triangle_bounds(m.points, m.triangles[t]); };
  // Every scan of the whole mesh here runs in parallel: a remesh call checks it a dozen times.
  const std::vector<int32_t> flagged_ids =
      flagged.empty() ? std::vector<int32_t>{} : detail::indices_where(nt, [&](size_t t) { return flagged[t] != 0; });
  if (flagged.empty() || 3 * flagged_ids.size() >= nt) {
    std::vector<int32_t> all(nt);
    std::iota(all.begin(), all.end(), 0);
    return all;
  }
  // Coarse cells the size of the largest flagged box (the largest is the same
  // whatever order the boxes are taken in).
  double cell = detail::parallel_reduce(
      tbb::blocked_range<size_t>(0, flagged_ids.size()), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double largest) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const Bounds b = box_of(size_t(flagged_ids[i]));
          largest = std::max(largest, (b.hi - b.lo).maxCoeff());
        }
        return largest;
      },
      [](double a, double b) { return std::max(a, b); });
  if (!(cell > 0)) cell = 1;
  auto key = [](int64_t i, int64_t j, int64_t k) {
    return uint64_t(i) * 0x9E3779B97F4A7C15ull ^ uint64_t(j) * 0xC2B2AE3D27D4EB4Full ^ uint64_t(k) * 0x165667B19E3779F9ull;
  };
  // Calls f(key) for each cell of box b; false if b covers too many to list.
  // Counted in doubles: with flagged triangles far smaller than the others, a
  // box's cells can number beyond 2^63 (a product of int64 extents wrapped
  // round to a small count, and the loops below then never ended).
  constexpr double kBeyondCells = 1e15; // cell coordinates stay exact integers in int64 and double
  auto cells = [&](const Bounds& b, auto&& f) {
    const Vec3 lo = (b.lo / cell).array().floor().matrix(), hi = (b.hi / cell).array().floor().matrix();
    if (!(lo.cwiseAbs().maxCoeff() < kBeyondCells && hi.cwiseAbs().maxCoeff() < kBeyondCells)) return false;
    if ((hi - lo + Vec3::Ones()).prod() > 64) return false;
    const int64_t i0 = int64_t(lo.x()), i1 = int64_t(hi.x()), j0 = int64_t(lo.y()), j1 = int64_t(hi.y()),
                  k0 = int64_t(lo.z()), k1 = int64_t(hi.z());
    for (int64_t i = i0; i <= i1; ++i)
      for (int64_t j = j0; j <= j1; ++j)
        for (int64_t k = k0; k <= k1; ++k) f(key(i, j, k));
    return true;
  };
  // The flagged triangles' cells, listed in parallel.
  std::vector<size_t> offset(flagged_ids.size() + 1, 0);
  detail::parallel_for(size_t(0), flagged_ids.size(), [&](size_t i) {
    cells(box_of(size_t(flagged_ids[i])), [&](uint64_t) { ++offset[i + 1]; });
  });
  for (size_t i = 0; i < flagged_ids.size(); ++i) offset[i + 1] += offset[i];
  std::vector<uint64_t> covered(offset.back());
  detail::parallel_for(size_t(0), flagged_ids.size(), [&](size_t i) {
    size_t at = offset[i];
    cells(box_of(size_t(flagged_ids[i])), [&](uint64_t k) { covered[at++] = k; });
  });
  // Every triangle's cells are looked up: in a hash set, not a sorted list
  // (its binary searches were the largest share of the liver's one-off checks).
  const detail::KeySet covered_set(covered);
  return detail::indices_where(nt, [&](size_t t) {
    bool near = false;
    const bool listed = cells(box_of(t), [&](uint64_t k) { near = near || covered_set.contains(k); });
    return flagged[t] || !listed || near;
  });
}

IntersectionReport find_in(const MeshArrays& m, size_t max_reported, std::span<const uint8_t> involved,
                           bool across_surfaces_only);

} // namespace

IntersectionReport find_self_intersections(const NodeMesh& m, size_t max_reported, std::span<const uint8_t> involved,
                                           bool across_surfaces_only) {
  return detail::find_self_intersections(MeshArrays{m.points, m.triangles, m.pairs}, max_reported, involved,
                                         across_surfaces_only);
}

IntersectionReport detail::find_self_intersections(const MeshArrays& m, size_t max_reported,
                                                   std::span<const uint8_t> involved, bool across_surfaces_only) {
  check_input(m, across_surfaces_only);
  if (!involved.empty() && involved.size() != m.triangles.size())
    throw InvalidInput("find_self_intersections: one involved flag per triangle expected");
  const std::vector<int32_t> near = near_flagged(m, involved);
  if (near.size() == m.triangles.size()) return find_in(m, max_reported, involved, across_surfaces_only);
  // Only the triangles near the flagged ones, with the same nodes (shared nodes
  // are compared by id). `near` is increasing, so pairs stay sorted.
  std::vector<std::array<int32_t, 3>> part_triangles;
  std::vector<PhasePair> part_pairs;
  std::vector<uint8_t> part_involved;
  for (int32_t t : near) {
    part_triangles.push_back(m.triangles[size_t(t)]);
    if (!m.pairs.empty()) part_pairs.push_back(m.pairs[size_t(t)]);
    part_involved.push_back(involved[size_t(t)]);
  }
  IntersectionReport report =
      find_in(MeshArrays{m.points, part_triangles, part_pairs}, max_reported, part_involved, across_surfaces_only);
  for (auto& pair : report.pairs)
    for (int32_t& t : pair) t = near[size_t(t)];
  return report;
}

namespace {

IntersectionReport find_in(const MeshArrays& m, size_t max_reported, std::span<const uint8_t> involved,
                           bool across_surfaces_only) {
  const size_t nt = m.triangles.size();
  IntersectionReport report;
  if (nt < 2) return report;

  detail::UnsetVector<Bounds> boxes(nt); // each written below, by the thread of its triangle
  detail::UnsetVector<int8_t> axis(nt);
  detail::parallel_for(size_t(0), nt, [&](size_t t) {
    const auto& tri = m.triangles[t];
    boxes[t] = detail::triangle_bounds(m.points, tri);
    axis[t] = detail::projection_axis(m.points[size_t(tri[0])], m.points[size_t(tri[1])], m.points[size_t(tri[2])]);
  });
  // Almost every candidate pair shares a node (99% on the liver's mesh), and
  // two triangles of a node's star certified embedded meet only where they
  // share corners: those pairs are not tested. (Two triangles of the same three
  // nodes always intersect improperly; no star holding both is certified.)
  // Certifying costs about what it saves where every triangle's pairs are
  // wanted, and more than it saves where a few are: only the former certify.
  const size_t wanted =
      involved.empty() ? nt : size_t(std::count_if(involved.begin(), involved.end(), [](uint8_t f) { return f != 0; }));
  const std::vector<uint8_t> embedded_star =
      2 * wanted > nt ? detail::embedded_stars(m.points, m.triangles) : std::vector<uint8_t>{};
  auto in_embedded_star = [&](const std::array<int32_t, 3>& a, const std::array<int32_t, 3>& b) {
    if (embedded_star.empty()) return false;
    for (int32_t x : a)
      if ((x == b[0] || x == b[1] || x == b[2]) && embedded_star[size_t(x)]) return true;
    return false;
  };
  // Each candidate pair is tested as it is found.
  tbb::enumerable_thread_specific<Found> found;
  detail::for_each_overlapping_box_pair(boxes, involved, [&](std::span<const detail::BoxPair> candidates) {
    Found& f = found.local();
    for (const auto [t, s] : candidates) {
      if (across_surfaces_only && m.pairs[size_t(t)] == m.pairs[size_t(s)]) continue;
      if (in_embedded_star(m.triangles[size_t(t)], m.triangles[size_t(s)])) continue;
      if (detail::intersect_improperly(m.points, m.triangles[size_t(t)], m.triangles[size_t(s)], axis[size_t(t)],
                                       axis[size_t(s)]))
        f.add(t, s, max_reported);
    }
  });

  for (const Found& f : found) {
    report.count += f.count;
    report.pairs.insert(report.pairs.end(), f.smallest.begin(), f.smallest.end());
  }
  std::sort(report.pairs.begin(), report.pairs.end());
  if (report.pairs.size() > max_reported) report.pairs.resize(max_reported);
  return report;
}

} // namespace

} // namespace vm
