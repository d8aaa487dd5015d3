#include "voronoimesh/improve/collapse.hpp"

#include "core/parallel.hpp"
#include "improve/collapse_peers.hpp"
#include "improve/merges_made.hpp"
#include "improve/mesh_part.hpp"
#include "improve/node_merge.hpp"
#include "mesh/node_rings.hpp"

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace vm {
namespace {

/// Junction nodes within this share of a sliver's longest edge of the target
/// merge into it with the sliver's collapse (find_slivers()).
constexpr double kHuddle = 0.1;
/// A collapse target moves onto the box faces of the node merging into it
/// when it lies within this share of the sliver's longest edge of them
/// (onto_box_faces()).
constexpr double kOntoBox = 0.25;
/// A call makes up to one collapse per this many candidates when that is more
/// than CollapseParams::max_collapses. An eighth, not more: on the property
/// tier's coarse random cases, whose junction triangles are nearly all
/// candidates, a quarter folded 108 more surface edges (of 5,140) and an eighth
/// 39, both measured before collapses that fold were refused.
constexpr size_t kCandidatesPerCollapse = 8;

using detail::CollapsePeers;
using detail::SliverCollapse;
using detail::merge_passing;

/// The collapses of one batch, chosen from the `slivers` (sorted worst first,
/// ties by triangle, then b) but the `passed_over` ones, at most `max` of them,
/// that share no triangle: each claims its two nodes and their rings. The
/// collapses of one sliver (its b and the nodes huddled round its a, see
/// find_slivers()) are chosen together, and each id a group claims blames all
/// of them: they fail together. `claimed` gets the collapses claiming each id,
/// `from` the sliver of each collapse.
std::vector<std::pair<int64_t, int64_t>> choose(const std::vector<SliverCollapse>& slivers,
                                                const std::vector<uint8_t>& passed_over, size_t max,
                                                std::unordered_multimap<int64_t, int32_t>& claimed,
                                                std::vector<size_t>& from) {
  claimed.clear();
  from.clear();
  std::vector<std::pair<int64_t, int64_t>> chosen;
  for (size_t i = 0, end = 0; i < slivers.size(); i = end) {
    for (end = i + 1; end < slivers.size() && slivers[end].triangle == slivers[i].triangle;) ++end;
    const SliverCollapse& s = slivers[i];
    if (chosen.size() >= max) break;
    if (s.a < 0 || passed_over[i] ||
        std::any_of(s.claims.begin(), s.claims.end(), [&](int64_t n) { return claimed.count(n); }))
      continue;
    for (size_t j = i; j < end; ++j) {
      for (int64_t n : s.claims) claimed.emplace(n, int32_t(chosen.size()));
      chosen.push_back({slivers[j].a, slivers[j].b});
      from.push_back(j);
    }
  }
  return chosen;
}

/// Where a goes when b, a node on box faces a is not on, merges into it: onto
/// those faces (a's coordinates across them set to theirs), if b's phases are
/// among a's and a lies within `reach` of the faces; not finite otherwise. A
/// junction a hair off the box (a quadruple point 0.08 h inside, the curve
/// from it ending on the box 0.08 h away) leaves a sliver no ordinary collapse
/// may remove: neither end lies on all the other's constraints.
Vec3 onto_box_faces(const InterfaceMesh& mesh, int32_t b, int32_t a, double reach) {
  const uint8_t box_a = mesh.box_faces()[size_t(a)], box_b = mesh.box_faces()[size_t(b)];
  const Vec3 none = Vec3::Constant(NAN);
  if ((box_b & ~box_a) == 0 || (box_a & ~box_b) != 0 ||
      !detail::constraints_within(mesh.phases()[size_t(b)], 0, mesh.phases()[size_t(a)], 0))
    return none;
  Vec3 to = mesh.positions()[size_t(a)];
  for (int k = 0; k < 3; ++k) {
    if (box_b >> (2 * k) & 1u) to[k] = mesh.domain().min[k];
    if (box_b >> (2 * k + 1) & 1u) to[k] = mesh.domain().max[k];
  }
  return (to - mesh.positions()[size_t(a)]).norm() <= reach ? to : none;
}

/// When no edge of a sliver (corners `c`, quality q) may collapse, or its
/// collapse would leave a triangle no better: the merge of one of its corners b
/// into a junction neighbour a off the sliver on all of b's constraints (a curve
/// node into the next node along its curve or into the quadruple point it
/// leaves) that leaves b's triangles best, if better than q; {-1, -1} if none.
/// Two curves of one face that leave a quadruple point at a small angle hold
/// slivers across the face whose edges run across it or along a curve into a
/// worse triangle; taking a curve node out beside them leaves the corner
/// triangle the angle allows.
std::array<int32_t, 2> merge_off_the_sliver(const InterfaceMesh& mesh, const std::array<int32_t, 3>& c, double q,
                                            std::span<const int64_t> node_ids) {
  std::tuple<double, int64_t, int64_t> best{q, 0, 0};
  std::array<int32_t, 2> merge{-1, -1};
  for (int32_t b : c)
    for (int32_t a : mesh.neighbours(b)) {
      if (std::find(c.begin(), c.end(), a) != c.end() || junction_order(mesh, a) < 3 || !mesh.constraints_within(b, a))
        continue;
      // Best quality first, ties to the lowest ids: the same choice on every rank.
      const double after = detail::quality_after_merge(mesh, b, a, mesh.positions()[size_t(a)], false);
      const std::tuple<double, int64_t, int64_t> candidate{after, -node_ids[size_t(b)], -node_ids[size_t(a)]};
      if (candidate > best) best = candidate, merge = {a, b};
    }
  return merge;
}

/// The slivers this rank answers for, with the collapse each would make.
std::vector<SliverCollapse> find_slivers(const InterfaceMesh& mesh, const CollapseParams& params, CollapsePeers* peers,
                                         std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids) {
  // Found on the faces so that the common case (none) costs two parallel
  // passes (nodes, then faces) and no copy. Face f is triangle f of
  // to_node_mesh() (triangles() is current: the flips before updated it).
  const auto& pos = mesh.positions();
  const auto& triangles = mesh.triangles();
  // Two corners on junctions can be an edge along a junction (a triple curve
  // with nodes bunched where a tiny face ends), which no flip may touch; a
  // sliver with fewer is the flips' to mend.
  const std::vector<double>& quality = mesh.qualities(); // kept current through the flips
  std::vector<uint8_t> on_junction(mesh.num_nodes()), is_sliver(triangles.size(), 0);
  detail::parallel_for_each_index(mesh.num_nodes(),
                                  [&](size_t n) { on_junction[n] = junction_order(mesh, int32_t(n)) >= 3; });
  detail::parallel_for_each_index(triangles.size(), [&](size_t f) {
    const std::array<int32_t, 3>& c = triangles[f];
    is_sliver[f] = on_junction[size_t(c[0])] + on_junction[size_t(c[1])] + on_junction[size_t(c[2])] >= 2 &&
                   quality[f] < params.below_quality;
  });
  std::vector<SliverCollapse> slivers;
  for (size_t face = 0; face < triangles.size(); ++face) {
    if (!is_sliver[face]) continue;
    const std::array<int32_t, 3>& c = triangles[face];
    if (peers && !peers->answers_for(*std::min_element(c.begin(), c.end()))) continue;
    const double q = quality[face];
    // The edge (b -> a) to collapse: the shortest whose b has its constraints
    // among a's, judged with the original phases; or whose ends are two
    // corners on the same box faces (quadruple points closer than the mesh
    // resolves, with nothing but slivers between them), which merge into one
    // higher-order point: the lower id (of the whole mesh) stays; or whose b
    // lies on box faces and a a hair off them, a moving onto them
    // (onto_box_faces()).
    auto corner = [&](int32_t v) { return detail::constraint_order(mesh, v) >= 4; };
    auto squared_length = [&](int k) {
      return (pos[size_t(c[size_t(k)])] - pos[size_t(c[size_t((k + 1) % 3)])]).squaredNorm();
    };
    const double longest2 = std::max({squared_length(0), squared_length(1), squared_length(2)});
    const double reach = kOntoBox * std::sqrt(longest2);
    std::pair<double, std::array<int32_t, 2>> best{INFINITY, {-1, -1}};
    Vec3 to = Vec3::Constant(NAN); // where a goes, if it moves
    for (int k = 0; k < 3; ++k) {
      const int32_t u = c[size_t(k)], w = c[size_t((k + 1) % 3)];
      const double len = squared_length(k);
      if (len >= best.first) continue;
      Vec3 onto = Vec3::Constant(NAN);
      if (mesh.constraints_within(w, u)) best = {len, {u, w}};
      else if (mesh.constraints_within(u, w)) best = {len, {w, u}};
      else if (corner(u) && corner(w) && mesh.box_faces()[size_t(u)] == mesh.box_faces()[size_t(w)])
        best = {len, node_ids[size_t(u)] < node_ids[size_t(w)] ? std::array{u, w} : std::array{w, u}};
      else if (onto = onto_box_faces(mesh, w, u, reach); onto.allFinite()) best = {len, {u, w}};
      else if (onto = onto_box_faces(mesh, u, w, reach); onto.allFinite()) best = {len, {w, u}};
      else continue;
      to = onto;
    }
    // Junction nodes huddled round where a goes (closer than a tenth of the
    // sliver's longest edge, with their constraints among a's there) merge into
    // a with b: where quadruple points and curve nodes bunch, b alone would fold
    // the cluster's faces onto each other (30 Voronoi cells: a 5-phase point with
    // a curve node 0.01 h and a quadruple point 0.03 h from it, duplicate
    // triangles whichever merged alone; min q 0.039, which no pass could mend).
    // They are judged together with b: where a moves onto the box, each alone
    // can leave a triangle as bad as the sliver (seeds30_2: a curve end 0.1 h
    // from a box edge, between two nodes on it, which both merge into it). If
    // they do worse together, b goes alone; if that too leaves a triangle no
    // better than the sliver, nothing: that would trade one sliver for another
    // (voronoi30 at grid 48 with collapse_below=0.15: min q 0.065 -> 0.012),
    // and the quality floor cannot undo it.
    const double huddle = std::pow(kHuddle, 2) * longest2;
    auto merged_with = [&](const std::array<int32_t, 2>& edge, const Vec3& moved) {
      const auto [a, b] = edge;
      const bool moves = moved.allFinite();
      const Vec3 at = moves ? moved : pos[size_t(a)];
      const auto& box = mesh.box_faces();
      const uint8_t box_there = uint8_t(box[size_t(a)] | (moves ? box[size_t(b)] : 0));
      std::vector<int32_t> merged{b};
      for (int32_t w : mesh.neighbours(a))
        if (w != b && junction_order(mesh, w) >= 3 && (pos[size_t(w)] - at).squaredNorm() <= huddle &&
            detail::constraints_within(mesh.phases()[size_t(w)], box[size_t(w)], mesh.phases()[size_t(a)], box_there))
          merged.push_back(w);
      if (merged.size() > 1 && detail::quality_after_merges(mesh, merged, a, at, moves) <= q) merged.resize(1);
      if (detail::quality_after_merges(mesh, merged, a, at, moves) <= q) merged.clear();
      return merged;
    };
    std::vector<int32_t> merged;
    if (best.second[0] >= 0) merged = merged_with(best.second, to);
    // Else one of its corners may merge into a node off it instead.
    if (merged.empty()) {
      best.second = merge_off_the_sliver(mesh, c, q, node_ids);
      to = Vec3::Constant(NAN);
      if (best.second[0] >= 0) merged = merged_with(best.second, to);
    }
    SliverCollapse s{q, triangle_ids[face], -1, -1, {}, to};
    const auto [a, b] = best.second;
    if (merged.empty()) {
      slivers.push_back(std::move(s));
      continue;
    }
    s.a = node_ids[size_t(a)];
    s.b = node_ids[size_t(b)];
    for (int32_t n : merged) {
      s.claims.push_back(node_ids[size_t(n)]);
      for (int32_t w : mesh.neighbours(n)) s.claims.push_back(node_ids[size_t(w)]);
    }
    s.claims.push_back(node_ids[size_t(a)]);
    for (int32_t w : mesh.neighbours(a)) s.claims.push_back(node_ids[size_t(w)]);
    for (size_t k = 1; k < merged.size(); ++k)
      slivers.push_back(SliverCollapse{q, s.triangle, s.a, node_ids[size_t(merged[k])], s.claims, s.to});
    slivers.push_back(std::move(s));
  }
  return slivers;
}

size_t collapse(InterfaceMesh& mesh, const CollapseParams& params, CollapsePeers* peers,
                std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids, detail::CollapseKept& kept) {
  if (params.below_quality <= 0) return 0;
  std::vector<SliverCollapse> slivers = find_slivers(mesh, params, peers, node_ids, triangle_ids);
  if (peers) slivers = peers->all(slivers);
  if (slivers.empty()) return 0;
  std::sort(slivers.begin(), slivers.end(), [](const SliverCollapse& x, const SliverCollapse& y) {
    return std::tie(x.quality, x.triangle, x.b) < std::tie(y.quality, y.triangle, y.b);
  });
  // A collapse that fails (it would make a triangle cross another surface, or
  // the mesh invalid) still claimed its rings, keeping a neighbouring sliver's
  // collapse out of the batch at every call: on 30 Voronoi cells, a sliver
  // between a 5-phase point and a quadruple point 0.025 h from it stayed, as the
  // worse sliver beside it always came first and always failed. So once, the
  // batch is chosen again without the collapses that failed, if that lets any
  // other in, and tried on the mesh as it was.
  // In one process, the guard's index finds the crossings around the merges.
  const detail::CrossingIndex* index =
      params.guard && params.guard_crossings && !peers ? params.guard->index_for(mesh) : nullptr;
  const size_t most = std::max(size_t(std::max(params.max_collapses, 0)), slivers.size() / kCandidatesPerCollapse);
  std::vector<uint8_t> passed_over(slivers.size(), 0), made;
  std::vector<size_t> from, tried;
  // The merges are tried on the part of the mesh they can change: the faces
  // at the nodes the collapses claim (their ends and rings), which hold every
  // face a merge renames or removes and every face whose validity it can
  // change. Not in a distributed run, nor where crossings are searched for
  // without the index: both look at the whole mesh.
  const bool whole = peers || (params.guard_crossings && !index);
  std::vector<int32_t> seeds;
  if (!whole)
    for (const SliverCollapse& s : slivers)
      if (s.a >= 0)
        for (const int64_t id : s.claims) seeds.push_back(int32_t(id)); // one process: ids are nodes
  const detail::MeshPart part = whole ? detail::whole_part(mesh) : detail::part_at(mesh, seeds);
  std::vector<int64_t> part_ids;
  if (!whole)
    for (const int32_t n : part.nodes) part_ids.push_back(node_ids[size_t(n)]);
  NodeMesh m;
  std::vector<int32_t> kept_triangles;
  size_t done = 0;
  for (int attempt = 0; attempt < 2; ++attempt) {
    std::unordered_multimap<int64_t, int32_t> claimed; // id -> the collapses claiming it
    const auto chosen = choose(slivers, passed_over, most, claimed, from);
    if (attempt > 0 && std::includes(tried.begin(), tried.end(), from.begin(), from.end())) break;
    NodeMesh trial;
    std::vector<int32_t> trial_kept;
    // A failure can only be at a node some collapse claims (its a, b and rings).
    detail::Blame blame(claimed.begin(), claimed.end());
    std::sort(blame.begin(), blame.end());
    std::vector<Vec3> moved_to; // only if some target moves: else merges copy no points
    for (size_t i : from) moved_to.push_back(slivers[i].to);
    if (std::none_of(moved_to.begin(), moved_to.end(), [](const Vec3& to) { return to.allFinite(); })) moved_to.clear();
    const detail::MergeChecks checks{.guard_crossings = params.guard_crossings, .refuse_surface_folds = true,
                                     .kept = params.kept, .peers = peers, .index = index, .part = &part};
    const size_t trial_done = merge_passing(part.mesh, trial, chosen, blame, checks, whole ? node_ids : part_ids,
                                            trial_kept, moved_to, &made);
    if (trial_done >= done && trial_done > 0)
      m = std::move(trial), kept_triangles = std::move(trial_kept), done = trial_done;
    tried = from; // ascending, as choose() goes through the slivers in order
    bool any_failed = false;
    for (size_t c = 0; c < chosen.size(); ++c)
      if (!made[c]) passed_over[from[c]] = 1, any_failed = true;
    if (!any_failed) break;
  }
  if (done) {
    detail::make_merges(mesh, part, m, kept_triangles, peers, node_ids, triangle_ids, kept);
    if (params.guard) {
      if (kept.in_place)
        params.guard->edited(kept.removed_triangles, kept.moves.faces, kept.removed_nodes, kept.moves.nodes);
      else
        params.guard->renumbered(mesh, kept.triangles, kept.nodes);
    }
  }
  return done;
}

} // namespace

size_t collapse_junction_slivers(InterfaceMesh& mesh, const CollapseParams& params) {
  std::vector<int64_t> ids(std::max(mesh.num_nodes(), mesh.num_triangles()));
  std::iota(ids.begin(), ids.end(), 0);
  detail::CollapseKept kept;
  return collapse(mesh, params, nullptr, std::span(ids).first(mesh.num_nodes()),
                  std::span(ids).first(mesh.num_triangles()), kept);
}

namespace detail {

size_t collapse_junction_slivers(InterfaceMesh& mesh, const CollapseParams& params, CollapsePeers& peers,
                                 std::span<const int64_t> node_ids, std::span<const int64_t> triangle_ids,
                                 CollapseKept& kept) {
  return collapse(mesh, params, &peers, node_ids, triangle_ids, kept);
}

} // namespace detail

} // namespace vm
