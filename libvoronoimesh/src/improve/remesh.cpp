#include "voronoimesh/improve/remesh.hpp"

#include "core/huge_pages.hpp"
#include "core/indices_where.hpp"
#include "core/parallel.hpp"
#include "core/union_find.hpp"
#include "core/unset_vector.hpp"
#include "improve/curve_overshoots.hpp"
#include "improve/digon_faces.hpp"
#include "improve/edge_splits.hpp"
#include "improve/node_merge.hpp"
#include "improve/phase_islands.hpp"
#include "mesh/node_rings.hpp"

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>

namespace vm {
namespace {

using detail::constraint_order;
using detail::kLongEdge;
using detail::NodeRings;

/// Collapses edges shorter than this share of their target (Botsch and Kobbelt's 4/5).
constexpr double kShortEdge = 0.8;
/// The target edge length for a tolerance e where a surface curves by k is
/// sqrt(kCentroidRule e / k): an equilateral triangle of edge L on a sphere of
/// radius R has its centroid L^2 / (6 R) off it, and edges reach 4/3 of the
/// target before they split, so (3/4)^2 6 = 3.375.
constexpr double kCentroidRule = 3.375;
/// Pieces of the mesh (connected through triangles) with fewer nodes than this
/// are not coarsened: collapses would shrink a small closed surface, such as a
/// one-voxel label's, to a tetrahedron that need not enclose what it bounded.
constexpr int32_t kSmallPiece = 16;
/// Rounds of splits per call: each halves the edges still too long.
constexpr int kSplitRounds = 4;
/// A round of collapses that removed fewer than this share of the nodes ends
/// the call's collapses: the next would remove fewer still, and every round
/// costs the node tables and a check of the whole mesh (the liver's second call
/// spent 60 ms on three rounds of 28, 5 and 2 collapses); the short edges left
/// wait for the next call. Measured (2026-12-05, build/bench/pass_times, 2
/// threads, stopping when converged, medians of three alternated runs): the
/// liver's remesh pass 0.61 -> 0.54 s and its improvement 1.44 -> 1.37 s, the
/// CT-like volume's 1.82 -> 1.62 and 3.27 -> 3.08 s, 60 grains 0.58 -> 0.57
/// and 1.13 s both, with the same worst and mean quality (the CT-like volume's
/// mean 0.9452 -> 0.9451); the shipped scenes and bench/junction_scenes.sh
/// the same worst triangles.
constexpr double kFewCollapses = 0.01;

/// The unit normal of the level set of phi_j - phi_i through y, or zero.
Vec3 level_set_normal(const PhaseField& field, int i, int j, const Vec3& y) {
  const Vec3 g = field.gradient(j, y) - field.gradient(i, y);
  const double n = g.norm();
  return n > 0 && std::isfinite(n) ? Vec3(g / n) : Vec3::Zero();
}

/// sqrt(k1^2 + k2^2) of the interface between phases i and j at x (at least its
/// largest principal curvature), from the normal's change over +-delta along two
/// tangents; 0 where the normal is not defined.
double interface_curvature(const PhaseField& field, int i, int j, const Vec3& x, double delta) {
  const Vec3 n = level_set_normal(field, i, j, x);
  if (n.isZero()) return 0;
  Eigen::Index least = 0;
  n.cwiseAbs().minCoeff(&least);
  const Vec3 t1 = n.cross(Vec3::Unit(least)).normalized(), t2 = n.cross(t1);
  double sum = 0;
  for (const Vec3& t : {t1, t2}) {
    const Vec3 a = level_set_normal(field, i, j, x + delta * t), b = level_set_normal(field, i, j, x - delta * t);
    if (a.isZero() || b.isZero()) return 0;
    sum += ((a - b) / (2 * delta)).squaredNorm();
  }
  return std::sqrt(sum);
}

/// True when the nodes next to both a and b are exactly the third corners of
/// the triangles on edge a-b (the link condition, at the node level): else the
/// collapse would fold two edges into one that more triangles share.
bool link_condition(const NodeRings& mesh, int32_t a, int32_t b) {
  std::vector<int32_t> opposite, common;
  mesh.for_each_triangle_at(b, [&](int32_t x, int32_t y) {
    if (x == a) opposite.push_back(y);
    else if (y == a) opposite.push_back(x);
  });
  const auto ra = mesh.neighbours(a), rb = mesh.neighbours(b);
  std::set_intersection(ra.begin(), ra.end(), rb.begin(), rb.end(), std::back_inserter(common));
  return std::all_of(common.begin(), common.end(),
                     [&](int32_t n) { return std::find(opposite.begin(), opposite.end(), n) != opposite.end(); });
}

/// A collapse b -> a and how short its edge is against its target.
struct Candidate {
  double ratio;
  int32_t b, a;
  bool merge = false; ///< two corners merged at their midpoint: a moves too
};

/// A corner merge may leave the worst triangle around it this much worse than
/// it was (when that is below RemeshParams::min_quality): the edge between
/// corners a few hundredths of a target apart keeps every triangle on it a
/// sliver whatever moves come later, while the merged point's triangles can
/// still improve. Refused at 0.046 against 0.047 (seeds30_2, two quadruple
/// points 0.035 of a target apart), such a pair stayed the scene's worst
/// triangle for good (q 0.115).
constexpr double kCornerMergeSlack = 0.75;

/// For a corner b, the merge with a neighbouring corner a < b on the same box
/// faces closer than RemeshParams::merge_corners of the target, at their
/// midpoint: close quadruple points become one higher-order point, where no
/// triangle between them could be anything but a sliver. The phases keep their
/// topology (the merged mesh must validate); the curve between them goes. Its
/// worst triangle may be a little worse than the one it replaces (kCornerMergeSlack).
std::optional<Candidate> best_corner_merge(const NodeRings& mesh, std::span<const double> target, int32_t b,
                                           const RemeshParams& params) {
  if (params.merge_corners <= 0) return std::nullopt;
  const auto& pos = mesh.positions();
  std::optional<Candidate> best;
  for (int32_t a : mesh.neighbours(b)) {
    if (a > b || constraint_order(mesh, a) < 4 || mesh.box_faces()[size_t(a)] != mesh.box_faces()[size_t(b)]) continue;
    const double ratio = (pos[size_t(a)] - pos[size_t(b)]).norm() / std::min(target[size_t(a)], target[size_t(b)]);
    if (ratio >= params.merge_corners || (best && std::tie(best->ratio, best->a) <= std::tie(ratio, a))) continue;
    if (!link_condition(mesh, a, b)) continue;
    double old_q;
    const double new_q = detail::quality_after_merge(mesh, b, a, 0.5 * (pos[size_t(a)] + pos[size_t(b)]), true, &old_q);
    if (new_q < std::min(params.min_quality, kCornerMergeSlack * old_q)) continue;
    best = Candidate{ratio, b, a, true};
  }
  return best;
}

/// The best collapse of node b, if any: b's shortest edge below kShortEdge of
/// its target whose far end a lies on all of b's constraints (and, if b is on a
/// curve, is its neighbour along it inside the curve), that makes no edge longer than kLongEdge of its target and no
/// triangle worse than RemeshParams::min_quality (or the worst it replaces).
std::optional<Candidate> best_collapse(const NodeRings& mesh, std::span<const double> target, int32_t b,
                                       const RemeshParams& params) {
  const int order = constraint_order(mesh, b);
  if (order > 3) return best_corner_merge(mesh, target, b, params);
  const auto& pos = mesh.positions();
  auto ratio_of = [&](int32_t a) {
    return (pos[size_t(a)] - pos[size_t(b)]).norm() / std::min(target[size_t(a)], target[size_t(b)]);
  };
  // The short edges are judged shortest first (ties by a), and the first that
  // passes is the best: most nodes need one link condition and one quality
  // check, not one per short edge.
  std::pair<double, int32_t> judged{-1, -1};
  for (;;) {
    std::pair<double, int32_t> next{kShortEdge, -1};
    for (int32_t a : mesh.neighbours(b))
      if (const std::pair edge{ratio_of(a), a}; judged < edge && edge < next) next = edge;
    if (next.second < 0) return std::nullopt;
    judged = next;
    const auto [ratio, a] = next;
    // A curve node moves only into its neighbour along the same curve, never
    // into the curve's end: a curve of one edge between two corners would fold
    // onto another curve between them.
    if (!mesh.constraints_within(b, a)) continue;
    if (order == 3 && (constraint_order(mesh, a) != 3 || !mesh.along_curve(a, b))) continue;
    bool ok = true;
    for (int32_t w : mesh.neighbours(b))
      if (w != a && (pos[size_t(a)] - pos[size_t(w)]).norm() > kLongEdge * std::min(target[size_t(a)], target[size_t(w)]))
        ok = false;
    if (!ok || !link_condition(mesh, a, b)) continue;
    double old_q;
    const double new_q = detail::quality_after_merge(mesh, b, a, pos[size_t(a)], false, &old_q);
    if (new_q < std::min(params.min_quality, old_q)) continue;
    return Candidate{ratio, b, a};
  }
}

/// The collapses of one round, shortest first. No two nodes b that collapse
/// are neighbours, and no b is another collapse's a: then no triangle loses two
/// corners and every node a collapse's checks looked at stays where it was, so
/// each is judged exactly. Several may share their a. `blame` gets, for each
/// node a failure may be reported at (a, b and their rings), the collapses to
/// drop for it.
std::vector<std::pair<int64_t, int64_t>> choose_collapses(const NodeRings& mesh, std::span<const double> target,
                                                          std::span<const uint8_t> small, const RemeshParams& params,
                                                          detail::Blame& blame,
                                                          std::vector<Vec3>& moved_to) {
  // Fresh memory at every round (20 MB on 1M triangles, 0.08 s of page faults
  // in this thread), as is `blame` below: on huge pages.
  std::vector<std::optional<Candidate>> found;
  detail::resize_on_huge_pages(found, mesh.num_nodes());
  detail::parallel_for_each_index(mesh.num_nodes(),
                                  [&](size_t b) { found[b] = best_collapse(mesh, target, int32_t(b), params); });
  // Gathered and sorted in parallel (a node is b of one candidate at most, so
  // the order is total and the same for any thread count).
  const std::vector<int32_t> with = detail::indices_where(found.size(), [&](size_t b) { return found[b].has_value(); });
  std::vector<Candidate> candidates(with.size());
  detail::parallel_for_each_index(with.size(), [&](size_t i) { candidates[i] = *found[size_t(with[i])]; });
  detail::parallel_sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.ratio, x.b) < std::tie(y.ratio, y.b);
  });
  std::vector<std::pair<int64_t, int64_t>> chosen;
  std::vector<uint8_t> near_b(mesh.num_nodes(), 0), is_b(mesh.num_nodes(), 0);
  // Room for a collapse of every candidate with rings of 6 (most collapses are
  // of fewer): only what is used is touched.
  detail::reserve_on_huge_pages(blame, blame.size() + 14 * candidates.size());
  const auto& pos = mesh.positions();
  for (const Candidate& c : candidates) {
    if (small[size_t(c.b)] || near_b[size_t(c.b)] || is_b[size_t(c.a)] || (c.merge && near_b[size_t(c.a)])) continue;
    const int32_t id = int32_t(chosen.size());
    // A merge moves its a as well: a is then held like a b (nobody's target, no
    // neighbour of another b) so that every check stays exact.
    for (int32_t moved : {c.b, c.merge ? c.a : c.b}) {
      is_b[size_t(moved)] = near_b[size_t(moved)] = 1;
      for (int32_t n : mesh.neighbours(moved)) near_b[size_t(n)] = 1;
    }
    moved_to.push_back(c.merge ? Vec3(0.5 * (pos[size_t(c.a)] + pos[size_t(c.b)])) : Vec3::Constant(NAN));
    for (int32_t end : {c.a, c.b}) {
      blame.emplace_back(end, id);
      for (int32_t n : mesh.neighbours(end))
        if (n != c.a && n != c.b) blame.emplace_back(n, id);
    }
    chosen.push_back({c.a, c.b});
  }
  detail::parallel_sort(blame.begin(), blame.end(), std::less<std::pair<int64_t, int32_t>>());
  return chosen;
}

/// The `merges` into one point (improve/point_merges.hpp) that keep apart, as
/// collapses of each merged node into the kept one, which moves where the
/// phase functions say; a failure at any node of a merge or next to one drops
/// all of the merge's.
std::vector<std::pair<int64_t, int64_t>> choose_point_merges(const NodeRings& mesh,
                                                             std::vector<detail::PointMerge> merges,
                                                             detail::Blame& blame, std::vector<Vec3>& moved_to) {
  std::vector<std::pair<int64_t, int64_t>> chosen;
  for (const detail::PointMerge& merge : detail::keep_apart(mesh, std::move(merges))) {
    const auto first = int32_t(chosen.size());
    for (int32_t b : merge.merged) {
      chosen.push_back({merge.keep, b});
      moved_to.push_back(merge.to);
    }
    for (int32_t n : detail::nodes_around(mesh, merge))
      for (auto i = first; i < int32_t(chosen.size()); ++i) blame.emplace_back(n, i);
  }
  std::sort(blame.begin(), blame.end());
  return chosen;
}

/// Per node, whether it lies in a piece of `m` of fewer than kSmallPiece nodes.
std::vector<uint8_t> in_small_pieces(const NodeMesh& m) {
  detail::UnionFind pieces(m.num_nodes());
  for (const auto& t : m.triangles) pieces.unite(t[0], t[1]), pieces.unite(t[0], t[2]);
  std::vector<int32_t> nodes(m.num_nodes(), 0);
  for (size_t v = 0; v < m.num_nodes(); ++v) ++nodes[size_t(pieces.find(int32_t(v)))];
  std::vector<uint8_t> small(m.num_nodes());
  for (size_t v = 0; v < m.num_nodes(); ++v) small[v] = nodes[size_t(pieces.find(int32_t(v)))] < kSmallPiece;
  return small;
}

/// target_edge_lengths() of nodes at `positions` with phase sets `phases`.
std::vector<double> targets(const std::vector<Vec3>& positions, const std::vector<PhaseSet>& phases,
                            const PhaseField* field, double reference, const RemeshParams& params) {
  const double longest = params.size * reference, shortest = std::min(params.min_size, params.size) * reference;
  std::vector<double> target(positions.size(), longest);
  if (!field || params.tolerance <= 0) return target;
  const double tolerance = params.tolerance * reference, delta = 0.5 * reference;
  detail::parallel_for_each_index(positions.size(), [&](size_t v) {
    const PhaseSet& s = phases[v];
    const int count = std::min(phase_count(s), 3);
    double curvature = 0;
    for (int i = 0; i < count; ++i)
      for (int j = i + 1; j < count; ++j)
        curvature = std::max(curvature, interface_curvature(*field, s[size_t(i)], s[size_t(j)], positions[v], delta));
    if (curvature > 0) target[v] = std::clamp(std::sqrt(kCentroidRule * tolerance / curvature), shortest, longest);
  });
  return target;
}

} // namespace

std::vector<double> target_edge_lengths(const InterfaceMesh& mesh, const PhaseField* field, double reference,
                                        const RemeshParams& params) {
  return targets(mesh.positions(), mesh.phases(), field, reference, params);
}

RemeshStats remesh_edges(InterfaceMesh& mesh, const PhaseField* field, double reference, const RemeshParams& params) {
  RemeshStats stats;
  // Point merges, then collapses and splits in either order, each on the
  // NodeMesh the last one left: the InterfaceMesh is rebuilt once, at the end.
  NodeMesh m = mesh.to_node_mesh();
  // The old id of each triangle and node of m, followed through every change.
  std::vector<int32_t> triangle_was(m.num_triangles()), node_was(m.num_nodes());
  std::iota(triangle_was.begin(), triangle_was.end(), 0);
  std::iota(node_was.begin(), node_was.end(), 0);
  auto follow = [](std::vector<int32_t>& old, const std::vector<int32_t>& kept) {
    std::vector<int32_t> now(kept.size());
    for (size_t i = 0; i < kept.size(); ++i) now[i] = old[size_t(kept[i])];
    old = std::move(now);
  };
  std::vector<double> target;
  bool collapsed = false, target_current = false;
  // The node tables of m and the targets of its nodes, made when first asked
  // for and kept while m is unchanged: the point merges' serve the first
  // round of collapses when none passed.
  std::optional<NodeRings> rings;
  auto current_rings = [&]() -> const NodeRings& {
    if (!rings) {
      rings.emplace(m);
      target = targets(m.points, rings->phases(), field, reference, params);
      target_current = true;
    }
    return *rings;
  };
  // Applies one batch of merges or collapses, chosen on m as it is, to m;
  // false if none passed.
  auto apply = [&](std::vector<std::pair<int64_t, int64_t>>& chosen, detail::Blame& blame,
                   std::vector<Vec3>& moved_to, bool point_merges) {
    // Filled by the threads (made and numbered in this one, 4 MB of fresh
    // memory on 1M triangles cost 20-40 ms a round with the other core idle).
    detail::UnsetVector<int64_t> ids(m.num_nodes());
    detail::parallel_for_each_index(ids.size(), [&](size_t n) { ids[n] = int64_t(n); });
    std::vector<int32_t> kept_triangles, kept_nodes;
    const detail::MergeChecks checks{.guard_crossings = params.guard_crossings, .kept = field};
    NodeMesh merged;
    const size_t done =
        detail::merge_passing(m, merged, chosen, blame, checks, ids, kept_triangles, moved_to, nullptr, point_merges);
    if (done == 0) return false;
    m = std::move(merged);
    (point_merges ? stats.point_merges : stats.collapses) += done;
    detail::drop_unused_nodes(m, kept_nodes);
    follow(triangle_was, kept_triangles);
    follow(node_was, kept_nodes);
    collapsed = true;
    rings.reset();
    target_current = false; // its nodes were renumbered
    return true;
  };
  // Merges into one point first, in a batch of their own, before any split or
  // collapse changes the nodes around the points: each merges whole or not at
  // all, which the collapses' blame cannot say.
  auto merge_points = [&] {
    if ((params.merge_digons <= 0 && !params.merge_overshoots && params.merge_islands <= 0) || !field) return;
    auto merge = [&](const NodeRings& tables, std::vector<detail::PointMerge> merges) {
      detail::Blame blame;
      std::vector<Vec3> moved_to;
      std::vector<std::pair<int64_t, int64_t>> chosen =
          choose_point_merges(tables, detail::off_other_points(tables, std::move(merges), target), blame, moved_to);
      return !chosen.empty() && apply(chosen, blame, moved_to, true);
    };
    auto digons = [&](const NodeRings& tables) {
      return params.merge_digons > 0 ? detail::small_digon_faces(tables, target, *field, params.merge_digons)
                                     : std::vector<detail::PointMerge>{};
    };
    // Chains of digons first, each whole; then, on what they left, every
    // digon alone: where a chain's whole merge fails, its faces may still
    // merge one by one over the calls (seeds17_2: three corners of cells 3,
    // 11, 12 and 16 in a row, which only merge that way). After the digons,
    // the curve ends past their quadruple point (improve/curve_overshoots.hpp)
    // and the pockets of phases that the phase functions do not have
    // (improve/phase_islands.hpp).
    const NodeRings* tables = &current_rings(); // before `target` is read: it sets it
    std::vector<detail::PointMerge> merges = digons(*tables);
    if (merge(*tables, detail::digon_chains(merges, tables->num_nodes()))) {
      tables = &current_rings();
      merges = digons(*tables);
    }
    if (params.merge_overshoots)
      for (detail::PointMerge& m : detail::overshooting_curve_ends(*tables, target, *field))
        merges.push_back(std::move(m));
    if (params.merge_islands > 0)
      for (detail::PointMerge& m : detail::phase_islands(*tables, target, *field, params.merge_islands))
        merges.push_back(std::move(m));
    merge(*tables, std::move(merges));
  };
  // Collapses in rounds: each claims the rings around it, so one round reaches
  // a fraction of the short edges.
  auto collapse_short_edges = [&] {
    for (int round = 0; round < params.collapse_rounds; ++round) {
      const NodeRings& tables = current_rings(); // before `target` is read: it sets it
      detail::Blame blame;
      std::vector<Vec3> moved_to;
      std::vector<std::pair<int64_t, int64_t>> chosen =
          choose_collapses(tables, target, in_small_pieces(m), params, blame, moved_to);
      const size_t before = stats.collapses;
      if (chosen.empty() || !apply(chosen, blame, moved_to, false)) break;
      if (double(stats.collapses - before) < kFewCollapses * double(m.num_nodes())) break;
    }
  };
  // Splits in rounds too (new nodes take the mean target of their edge), so an
  // edge several times too long is cut down in one call. New triangles lie in
  // old ones, but on flat interfaces a rounded midpoint can stand a hair off a
  // coplanar neighbour's plane: with the guard, splits whose triangles cross
  // another are undone and the nodes around them held from splitting.
  auto split_long_edges_in_rounds = [&] {
    if (!target_current) current_rings();
    target_current = true; // the midpoints' targets are appended
    // What a retry puts back: the first round's replaced arrays (moved out,
    // not copied: 35 MB of fresh memory on 1M triangles, 0.1 s in one thread)
    // and the old nodes, the first ones.
    detail::Unsplit unsplit;
    const size_t old_nodes = m.num_nodes();
    std::vector<uint8_t> held(old_nodes, 0);
    size_t done = 0;
    for (int attempt = 0;; ++attempt) {
      std::vector<uint8_t> now_held = held;
      std::vector<std::array<int32_t, 2>> parents;
      done = 0;
      for (int round = 0; round < kSplitRounds; ++round) {
        if (params.max_triangles > 0 && m.num_triangles() >= params.max_triangles) break;
        const size_t splits =
            detail::split_long_edges(m, target, now_held, parents, triangle_was, round == 0 ? &unsplit : nullptr);
        if (splits == 0) break;
        done += splits;
      }
      if (done == 0 || !params.guard_crossings) break;
      std::vector<uint8_t> involved(m.num_triangles());
      detail::parallel_for_each_index(involved.size(), [&](size_t t) {
        const auto& tri = m.triangles[t];
        involved[t] = size_t(std::max({tri[0], tri[1], tri[2]})) >= old_nodes;
      });
      const IntersectionReport crossings =
          find_self_intersections(m, std::numeric_limits<size_t>::max(), involved, false);
      if (crossings.ok()) break;
      // Hold the old nodes behind every corner of a crossing triangle (a new
      // node's are those of the edge it split, walked back) and split again.
      std::vector<int32_t> walk;
      for (const auto& pair : crossings.pairs)
        for (int32_t t : pair)
          for (int32_t v : m.triangles[size_t(t)]) walk.push_back(v);
      while (!walk.empty()) {
        const int32_t v = walk.back();
        walk.pop_back();
        if (size_t(v) < old_nodes) held[size_t(v)] = 1;
        else walk.insert(walk.end(), parents[size_t(v) - old_nodes].begin(), parents[size_t(v) - old_nodes].end());
      }
      m.triangles = std::move(unsplit.triangles);
      m.pairs = std::move(unsplit.pairs);
      triangle_was = std::move(unsplit.origin);
      m.points.resize(old_nodes);
      target.resize(old_nodes);
      if (attempt == 2) { // still crossing: no splits in this call
        done = 0;
        break;
      }
    }
    stats.splits += done;
    if (done > 0) rings.reset();
    node_was.resize(m.num_nodes(), -1); // the splits' midpoints, after every old node
  };
  merge_points();
  if (params.split_first) {
    split_long_edges_in_rounds();
    collapse_short_edges();
  } else {
    collapse_short_edges();
    split_long_edges_in_rounds();
  }
  if (collapsed || stats.splits) {
    mesh.apply_edit(m, triangle_was, node_was);
    stats.old_triangles = std::move(triangle_was);
    stats.old_nodes = std::move(node_was);
  }
  return stats;
}

} // namespace vm
