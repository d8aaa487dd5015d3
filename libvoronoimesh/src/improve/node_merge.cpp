#include "improve/node_merge.hpp"

#include "improve/collapse_peers.hpp"
#include "improve/kept_points.hpp"
#include "improve/mesh_part.hpp"

#include "check/crossing_index.hpp"
#include "core/indices_where.hpp"
#include "core/parallel.hpp"

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"

#include <algorithm>
#include <atomic>
#include <limits>

namespace vm::detail {
namespace {

Vec3 normal(const NodeMesh& m, const std::array<int32_t, 3>& t) {
  const Vec3& a = m.points[size_t(t[0])];
  return (m.points[size_t(t[1])] - a).cross(m.points[size_t(t[2])] - a);
}

/// Whether a corner of triangle t of `m` is flagged (one flag per node).
bool touches(const NodeMesh& m, std::span<const uint8_t> flags, size_t t) {
  const auto& tri = m.triangles[t];
  return (flags[size_t(tri[0])] | flags[size_t(tri[1])] | flags[size_t(tri[2])]) != 0;
}

/// Flags the corners of triangle t of `m` (one flag per node), from any
/// thread: several triangles share a corner.
void flag_corners(const NodeMesh& m, size_t t, std::vector<uint8_t>& flags) {
  for (int32_t v : m.triangles[t]) std::atomic_ref<uint8_t>(flags[size_t(v)]).store(1, std::memory_order_relaxed);
}

/// The flags of `target` that lie within `rings` rings of a node flagged in
/// `seeds` (one flag per node of `m`).
std::vector<uint8_t> targets_near(const NodeMesh& m, const std::vector<uint8_t>& target, std::span<const uint8_t> seeds,
                                  int rings) {
  std::vector<uint8_t> near(seeds.begin(), seeds.end());
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<uint8_t> wider = near;
    parallel_for_each_index(m.num_triangles(), [&](size_t t) {
      if (touches(m, near, t)) flag_corners(m, t, wider);
    });
    near = std::move(wider);
  }
  parallel_for_each_index(near.size(), [&](size_t v) { near[v] &= target[v]; });
  return near;
}

/// find_merge_failures()'s crossings through the index of the mesh `before`
/// is `part` of (all of it if null): the trial's triangles at targets
/// (`involved`) against the mesh's triangles that no merge touched, and each
/// other. Appends the nodes of both triangles of each crossing pair (those
/// of the trial).
void report_trial_crossings(const NodeMesh& trial, std::span<const uint8_t> involved, const NodeMesh& before,
                            const std::vector<int32_t>& into, const CrossingIndex& index, const MeshPart* part,
                            std::vector<int32_t>& nodes) {
  auto whole_node = [&](int32_t n) { return part ? part->whole_node(n) : n; };
  std::vector<CrossingIndex::TrialTriangle> extra;
  std::vector<int32_t> extra_of; // the trial's triangle of each extra one
  for (size_t t = 0; t < trial.num_triangles(); ++t) {
    if (!involved[t]) continue;
    const auto& tri = trial.triangles[t];
    extra.push_back({{whole_node(tri[0]), whole_node(tri[1]), whole_node(tri[2])},
                     {trial.points[size_t(tri[0])], trial.points[size_t(tri[1])], trial.points[size_t(tri[2])]}});
    extra_of.push_back(int32_t(t));
  }
  // What the extra triangles replace: every triangle at a merged node or a
  // target (the targets are the nodes the merged ones go into).
  std::vector<uint8_t> at_merge(before.num_nodes(), 0);
  std::vector<int32_t> left_out;
  for (size_t b = 0; b < into.size(); ++b)
    if (into[b] >= 0) at_merge[b] = 1, at_merge[size_t(into[b])] = 1;
  for (size_t t = 0; t < before.num_triangles(); ++t)
    if (touches(before, at_merge, t)) left_out.push_back(part ? part->whole_triangle(int32_t(t)) : int32_t(t));
  const auto points = part ? part->whole_points : std::span<const Vec3>(before.points);
  const auto triangles = part ? part->whole_triangles : std::span<const Triangle>(before.triangles);
  const CrossingIndex::TrialCrossings found = index.crossings_with(points, triangles, extra, left_out);
  auto add_trial_triangle = [&](int32_t e) {
    const auto& tri = trial.triangles[size_t(extra_of[size_t(e)])];
    nodes.insert(nodes.end(), tri.begin(), tri.end());
  };
  for (const auto& [e, s] : found.with_mesh) {
    add_trial_triangle(e);
    // A node of the mesh outside the part takes part in no merge: no merge is blamed there.
    for (const int32_t v : triangles[size_t(s)])
      if (const int32_t n = part ? part->part_node(v) : v; n >= 0) nodes.push_back(n);
  }
  for (const auto& [e, f] : found.among_extra) add_trial_triangle(e), add_trial_triangle(f);
}

/// Two triangles at a merge target that became the same three nodes, of the
/// same pair, turned opposite ways: a strip of a face one triangle wide
/// between merged nodes closed up (beside a digon face, improve/digon_faces.hpp).
/// Both go; `kept_triangles` and `moved` (one entry per triangle of `out`) follow.
void close_folds_at_targets(const std::vector<int32_t>& into, NodeMesh& out, std::vector<int32_t>& kept_triangles,
                            std::vector<uint8_t>& moved) {
  std::vector<uint8_t> target(out.num_nodes(), 0);
  for (int32_t a : into)
    if (a >= 0) target[size_t(a)] = 1;
  std::vector<std::pair<std::array<int32_t, 3>, int32_t>> at_targets; // sorted corners, triangle
  for (size_t t = 0; t < out.num_triangles(); ++t) {
    if (!touches(out, target, t)) continue;
    auto corners = out.triangles[t];
    std::sort(corners.begin(), corners.end());
    at_targets.push_back({corners, int32_t(t)});
  }
  std::sort(at_targets.begin(), at_targets.end());
  // A rotation of the sorted corners, or of their reverse.
  auto even = [](const std::array<int32_t, 3>& t) { return (t[0] < t[1]) + (t[1] < t[2]) + (t[2] < t[0]) == 2; };
  std::vector<uint8_t> gone(out.num_triangles(), 0);
  for (size_t i = 0; i + 1 < at_targets.size(); ++i) {
    const bool pair_alone = at_targets[i].first == at_targets[i + 1].first &&
                            (i + 2 == at_targets.size() || at_targets[i + 2].first != at_targets[i].first) &&
                            (i == 0 || at_targets[i - 1].first != at_targets[i].first);
    if (!pair_alone) continue;
    const auto t = size_t(at_targets[i].second), u = size_t(at_targets[i + 1].second);
    if (out.pairs[t] == out.pairs[u] && even(out.triangles[t]) != even(out.triangles[u])) gone[t] = gone[u] = 1;
  }
  size_t kept = 0;
  for (size_t t = 0; t < out.num_triangles(); ++t)
    if (!gone[t]) {
      out.triangles[kept] = out.triangles[t];
      out.pairs[kept] = out.pairs[t];
      kept_triangles[kept] = kept_triangles[t];
      moved[kept++] = moved[t];
    }
  out.triangles.resize(kept);
  out.pairs.resize(kept);
  kept_triangles.resize(kept);
  moved.resize(kept);
}

/// Makes the nodes of m's triangles, which name nodes of `points`, m's own:
/// those used, in the order of their ids in `points`, renamed from 0. Appends
/// each one's id in `points` to `kept`.
void keep_used_nodes(std::span<const Vec3> points, NodeMesh& m, std::vector<int32_t>& kept) {
  std::vector<uint8_t> used(points.size(), 0);
  parallel_for_each_index(m.num_triangles(), [&](size_t t) { flag_corners(m, t, used); });
  const std::vector<int32_t> now_kept = indices_where(points.size(), [&](size_t v) { return used[v] != 0; });
  // m's own nodes, all used (every mesh improve_mesh() is given, as a rule):
  // nothing to renumber or copy.
  if (now_kept.size() == points.size() && points.data() == m.points.data()) {
    kept.insert(kept.end(), now_kept.begin(), now_kept.end());
    return;
  }
  std::vector<int32_t> id(points.size(), -1);
  std::vector<Vec3> kept_points(now_kept.size());
  parallel_for_each_index(now_kept.size(), [&](size_t i) {
    id[size_t(now_kept[i])] = int32_t(i);
    kept_points[i] = points[size_t(now_kept[i])];
  });
  parallel_for_each_index(m.num_triangles(), [&](size_t t) {
    for (int32_t& v : m.triangles[t]) v = id[size_t(v)];
  });
  m.points = std::move(kept_points); // `points` may be m's: read to the end first
  kept.insert(kept.end(), now_kept.begin(), now_kept.end());
}

} // namespace

void merge_nodes(const NodeMesh& m, const std::vector<int32_t>& into, NodeMesh& out, std::vector<int32_t>& turned,
                 std::vector<int32_t>& kept_triangles, const std::vector<Vec3>* points, bool close_folds,
                 std::vector<uint8_t>* reshaped) {
  out = m.empty_like();
  out.points = points ? *points : m.points;
  auto merged = [&](size_t t) {
    auto tri = m.triangles[t];
    for (int32_t& v : tri)
      if (into[size_t(v)] >= 0) v = into[size_t(v)];
    return tri;
  };
  // The triangles that keep three corners, found and copied in parallel, in
  // their order (serial, the scans were a fifth of a merge on 1M triangles).
  kept_triangles = indices_where(m.num_triangles(), [&](size_t t) {
    const auto tri = merged(t);
    return tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2];
  });
  const size_t kept = kept_triangles.size();
  out.triangles.resize(kept);
  out.pairs.resize(kept);
  std::vector<uint8_t> moved(kept);
  parallel_for_each_index(kept, [&](size_t i) {
    const auto t = size_t(kept_triangles[i]);
    out.triangles[i] = merged(t);
    out.pairs[i] = m.pairs[t];
    bool moves = false;
    for (size_t k = 0; k < 3; ++k) {
      const auto v = size_t(out.triangles[i][k]);
      moves = moves || into[size_t(m.triangles[t][k])] >= 0 || (points && out.points[v] != m.points[v]);
    }
    moved[i] = moves;
  });
  if (close_folds) close_folds_at_targets(into, out, kept_triangles, moved);
  const auto turns = [&](size_t i) {
    return moved[i] && normal(out, out.triangles[i]).dot(normal(m, m.triangles[size_t(kept_triangles[i])])) <= 0;
  };
  for (int32_t i : indices_where(out.num_triangles(), turns))
    turned.insert(turned.end(), out.triangles[size_t(i)].begin(), out.triangles[size_t(i)].end());
  if (reshaped) *reshaped = std::move(moved);
}

void drop_unused_nodes(NodeMesh& m, std::vector<int32_t>& kept) { keep_used_nodes(m.points, m, kept); }

bool find_merge_failures(const NodeMesh& trial, const std::vector<int32_t>& into, const MergeChecks& checks,
                         std::vector<int32_t>& nodes, std::span<const uint8_t> changed, const NodeMesh* before,
                         std::span<const uint8_t> reshaped) {
  CollapsePeers* const peers = checks.peers;
  // Validation is local: a merge changes only triangles at its target a, whose
  // corners (a and its ring, the "core") are the only nodes whose triangles,
  // edges and fans can change. The triangles at core nodes are validated alone;
  // problems they show only at other nodes are where that cut-out ends, and the
  // mesh around them is as it was (valid). Linear in the mesh only for scans.
  std::vector<uint8_t> target(trial.num_nodes(), 0), core(trial.num_nodes(), 0);
  for (int32_t a : into)
    if (a >= 0 && (!peers || peers->answers_for(a))) target[size_t(a)] = 1; // another rank checks its own
  const std::vector<int32_t> at_target =
      indices_where(trial.num_triangles(), [&](size_t t) { return touches(trial, target, t); });
  // On a retry only the targets near what changed since the last trial are
  // validated again; the others' cut-outs are as they were, and passed. A
  // node's triangles change only next to a changed node, and a target's
  // problems are those of its ring's triangles: the targets within two rings.
  const std::vector<uint8_t> validated = changed.empty() ? target : targets_near(trial, target, changed, 2);
  parallel_for_each_index(at_target.size(), [&](size_t i) {
    const auto t = size_t(at_target[i]);
    if (touches(trial, validated, t)) flag_corners(trial, t, core);
  });
  // The cut-out has its own nodes: validating it with all the trial's (a
  // copy of every point, tables over every node) cost more than the merge on
  // 1.4M triangles.
  // Made in parallel, its nodes in the trial's order: on 1M triangles the first
  // round of a remesh call cuts out nearly the whole mesh (0.2 s in one thread,
  // 0.1 s in two).
  NodeMesh local = trial.empty_like();
  const std::vector<int32_t> cut =
      indices_where(trial.num_triangles(), [&](size_t t) { return touches(trial, core, t); });
  local.triangles.resize(cut.size());
  local.pairs.resize(cut.size());
  std::vector<uint8_t> local_at_target(cut.size());
  parallel_for_each_index(cut.size(), [&](size_t i) {
    const auto t = size_t(cut[i]);
    local.triangles[i] = trial.triangles[t];
    local.pairs[i] = trial.pairs[t];
    local_at_target[i] = touches(trial, validated, t);
  });
  std::vector<int32_t> trial_id; // the trial's id of each node of the cut-out
  keep_used_nodes(trial.points, local, trial_id);
  const ValidationReport report = validate(local);
  if (!report.ok() && report.nodes.empty()) return false;
  for (int32_t n : report.nodes)
    if (core[size_t(trial_id[size_t(n)])]) nodes.push_back(trial_id[size_t(n)]);
  // A fold with a triangle at a target is the merge's (the cut-out holds both
  // triangles of every edge at a core node), and blamed on its corners.
  if (checks.refuse_surface_folds)
    for (const Fold& f : sharpest_folds(local, std::numeric_limits<size_t>::max()))
      for (size_t t : f.triangles)
        if (local_at_target[t])
          for (int32_t v : local.triangles[t]) nodes.push_back(trial_id[size_t(v)]);
  if (checks.kept && before && checks.kept->keeps_points())
    for (int32_t a : merges_losing_kept_points(*before, trial, into, target, *checks.kept)) nodes.push_back(a);
  if (!checks.guard_crossings) return true;
  // A crossing counts if one of its triangles is at a target. After a retry,
  // only pairs with a triangle at a changed node can be new: any other pair was
  // tested in the last trial, and had it crossed, its collapses would be gone.
  std::vector<uint8_t> involved(trial.num_triangles(), 0), searched;
  for (int32_t t : at_target) involved[size_t(t)] = 1;
  if (checks.index && before) {
    report_trial_crossings(trial, involved, *before, into, *checks.index, checks.part, nodes);
    return true;
  }
  // A triangle at a target as it was (only its target's other triangles
  // changed) can cross only a reshaped one, whose search finds the pair.
  if (!reshaped.empty())
    for (size_t t = 0; t < trial.num_triangles(); ++t) involved[t] &= reshaped[t];
  if (!changed.empty()) {
    searched.assign(trial.num_triangles(), 0);
    for (size_t t = 0; t < trial.num_triangles(); ++t)
      for (int32_t v : trial.triangles[t]) searched[t] |= changed[size_t(v)];
  }
  const IntersectionReport crossings =
      find_self_intersections(trial, std::numeric_limits<size_t>::max(), changed.empty() ? involved : searched, false);
  for (const auto& pair : crossings.pairs) {
    if (!involved[size_t(pair[0])] && !involved[size_t(pair[1])]) continue;
    for (int32_t t : pair) nodes.insert(nodes.end(), trial.triangles[size_t(t)].begin(), trial.triangles[size_t(t)].end());
  }
  return true;
}

size_t merge_passing(const NodeMesh& m, NodeMesh& merged, std::span<const std::pair<int64_t, int64_t>> chosen,
                     const Blame& blame, const MergeChecks& checks, std::span<const int64_t> node_ids,
                     std::vector<int32_t>& kept_triangles, std::span<const Vec3> moved_to, std::vector<uint8_t>* made,
                     bool close_folds) {
  CollapsePeers* const peers = checks.peers;
  // Ids back to this mesh's nodes (ids ascend with the nodes). Ids from 0 to
  // the last node are the nodes themselves (one process): no search, which
  // took 10 ms a round on 1M triangles.
  const auto count = int64_t(node_ids.size());
  const bool own_ids = count == 0 || (node_ids.front() == 0 && node_ids.back() == count - 1);
  auto local = [&](int64_t id) {
    if (own_ids) return id >= 0 && id < count ? int32_t(id) : -1;
    const auto at = std::lower_bound(node_ids.begin(), node_ids.end(), id);
    return at != node_ids.end() && *at == id ? int32_t(at - node_ids.begin()) : -1;
  };
  // All at once, checked once. Collapses in a batch share no triangle, so a
  // failing node is blamed on the few collapses around it: those are dropped
  // and the rest checked again (one whole-mesh check, then searches around the
  // dropped collapses only; not one check per collapse).
  std::vector<char> active(chosen.size(), 1);
  if (made) made->assign(chosen.size(), 0);
  std::vector<int32_t> into(m.num_nodes(), -1), failed;
  std::vector<uint8_t> reshaped; // per triangle of the trial
  // Once a trial has been checked: the ends of the collapses dropped since and
  // the nodes that failed.
  std::vector<uint8_t> changed;
  NodeMesh trial;
  size_t done = 0;
  std::vector<Vec3> points;
  for (size_t left = chosen.size(); left > 0;) {
    std::fill(into.begin(), into.end(), -1);
    if (!moved_to.empty()) points = m.points;
    for (size_t i = 0; i < chosen.size(); ++i)
      if (const int32_t a = local(chosen[i].first), b = local(chosen[i].second); active[i] && a >= 0 && b >= 0) {
        into[size_t(b)] = a;
        if (!moved_to.empty() && moved_to[i].allFinite()) points[size_t(a)] = moved_to[i];
      }
    failed.clear();
    merge_nodes(m, into, trial, failed, kept_triangles, moved_to.empty() ? nullptr : &points, close_folds, &reshaped);
    if (peers) std::erase_if(failed, [&](int32_t n) { return !peers->answers_for(n); });
    // Triangles that turn over are failures enough; only without them is the
    // merged mesh validated (by every rank, if any rank saw them).
    bool blamed = peers ? peers->any(!failed.empty()) : !failed.empty();
    if (!blamed) {
      blamed = find_merge_failures(trial, into, checks, failed, changed, &m, reshaped);
      changed.assign(m.num_nodes(), 0);
    }
    if (peers) blamed = !peers->any(!blamed);
    std::vector<int64_t> failed_ids;
    for (int32_t n : failed) failed_ids.push_back(node_ids[size_t(n)]);
    if (peers) failed_ids = peers->all(failed_ids);
    if (blamed && failed_ids.empty()) {
      merged = std::move(trial);
      done = left;
      if (made) made->assign(active.begin(), active.end());
      break;
    }
    size_t dropped = 0;
    for (int64_t id : failed_ids) {
      // Where the next trial differs, or may fail again: a failure near a
      // collapse that no blame dropped is found again there (find_merge_failures()).
      if (const int32_t n = local(id); n >= 0 && !changed.empty()) changed[size_t(n)] = 1;
      for (auto c = std::lower_bound(blame.begin(), blame.end(), std::pair{id, std::numeric_limits<int32_t>::min()});
           c != blame.end() && c->first == id; ++c)
        if (active[size_t(c->second)]) {
          active[size_t(c->second)] = 0, ++dropped;
          for (int64_t end_id : {chosen[size_t(c->second)].first, chosen[size_t(c->second)].second})
            if (const int32_t n = local(end_id); n >= 0 && !changed.empty()) changed[size_t(n)] = 1;
        }
    }
    if (!blamed || dropped == 0) break; // a failure no collapse answers for: keep the mesh as it was
    left -= dropped;
  }
  return done;
}

} // namespace vm::detail
