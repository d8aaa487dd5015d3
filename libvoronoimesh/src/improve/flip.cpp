#include "voronoimesh/improve/flip.hpp"

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/improve/collapse.hpp"

#include "core/indices_where.hpp"
#include "core/parallel.hpp"
#include "core/unset_vector.hpp"
#include "improve/field_orientation.hpp"
#include "improve/flip_log.hpp"
#include "improve/kept_points.hpp"
#include "improve/part_agreement.hpp"
#include "mesh/node_rings.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <span>
#include <tuple>

namespace vm {
namespace {

using detail::FlipCandidate;
using detail::FlipPeers;

/// Times a flip_edges() call flips again around the flips it undid for
/// crossings (banning those that crossed); if flips still cross after that,
/// the call flips nothing.
constexpr int kMaxFlipRepairs = 3;

/// Quality of every face, kept current across flips.
class FaceQuality {
public:
  explicit FaceQuality(const InterfaceMesh& mesh) : mesh_(mesh), q_(mesh.qualities()) {}
  double operator[](OMesh::FaceHandle f) const { return q_[size_t(f.idx())]; }
  /// After a flip changed face f (triangles() is updated only after the rounds).
  void update(OMesh::FaceHandle f) {
    const auto c = mesh_.face_nodes(f);
    const auto& pos = mesh_.positions();
    q_[size_t(f.idx())] = triangle_quality(pos[size_t(c[0])], pos[size_t(c[1])], pos[size_t(c[2])]);
  }

private:
  const InterfaceMesh& mesh_;
  std::vector<double> q_;
};

/// True when the face of halfedge h has boundary edges on both sides of h's
/// opposite corner and that corner lies on one curve: an "ear" whose three
/// corners lie on one junction curve (or the box). Projection pulls such
/// corners onto the curve, so an ear can only degenerate; flipping h away is
/// the only cure. Where the opposite corner is a corner of the patch (a
/// quadruple point, a box corner), its two boundary edges lie on two curves: a
/// corner triangle, which a flip only moves to the other side of the corner's
/// neighbour, where it was an "ear" again and flipped back, round after round
/// (on 30 Voronoi cells such a pair ended every flip pass as the worst
/// triangle: min q 0.064 after 20 iterations).
bool is_ear_across(const InterfaceMesh& mesh, OMesh::HalfedgeHandle h) {
  const OMesh& om = mesh.omesh();
  const auto n = om.next_halfedge_handle(h);
  return om.is_boundary(om.edge_handle(n)) && om.is_boundary(om.edge_handle(om.next_halfedge_handle(n))) &&
         detail::constraint_order(mesh, mesh.node(om.to_vertex_handle(n))) <= 3;
}

/// Algorithm 5 for one edge, read-only. Returns the quality gain of flipping it,
/// or a negative number if it must not flip. Beyond the paper: an ear below
/// p.ear_below on either side flips whenever the flip is legal (gain 1 + its
/// quality gain, so ears go first).
double flip_gain(const InterfaceMesh& mesh, const FaceQuality& quality, OMesh::EdgeHandle eh, const FlipParams& p,
                 std::array<int32_t, 4>& nodes) {
  const OMesh& om = mesh.omesh();
  if (om.is_boundary(eh)) return -1; // junction or domain edge: never flips
  // Judged from its lower node to its higher one, whichever way OpenMesh stores
  // the edge: the result must depend on the nodes alone, not on the history of
  // the mesh's halfedges (a part of the mesh built afresh must judge alike).
  auto h0 = om.halfedge_handle(eh, 0), h1 = om.halfedge_handle(eh, 1);
  if (mesh.node(om.from_vertex_handle(h0)) > mesh.node(om.to_vertex_handle(h0))) std::swap(h0, h1);
  const double before = std::min(quality[om.face_handle(h0)], quality[om.face_handle(h1)]);
  const bool ear = before < p.ear_below && (is_ear_across(mesh, h0) || is_ear_across(mesh, h1));
  if (before >= p.skip_quality && !ear) return -1;
  // Triangles (i, j, k) and (i, l, j) as in the paper's Fig. 5.
  nodes = {mesh.node(om.from_vertex_handle(h0)), mesh.node(om.to_vertex_handle(h0)),
           mesh.node(om.to_vertex_handle(om.next_halfedge_handle(h0))),
           mesh.node(om.to_vertex_handle(om.next_halfedge_handle(h1)))};
  const auto& pos = mesh.positions();
  const Vec3 &vi = pos[size_t(nodes[0])], &vj = pos[size_t(nodes[1])], &vk = pos[size_t(nodes[2])],
             &vl = pos[size_t(nodes[3])];
  // Most edges judged do not gain: one new triangle no better than the pair
  // now says so without the other's quality.
  const double first = triangle_quality(vi, vl, vk);
  if (first <= before && !ear) return -1;
  const double after = std::min(first, triangle_quality(vl, vj, vk));
  if (after <= before && !ear) return -1;
  // An ear flips even when that lowers the pair's quality, but never into a
  // triangle validate() calls zero-area (three nodes on one line, as planes
  // through lattice nodes make them).
  if (ear && (has_zero_area(vi, vl, vk) || has_zero_area(vl, vj, vk))) return -1;
  const Vec3 n3 = (vl - vi).cross(vk - vi), n4 = (vk - vj).cross(vl - vj);
  if (n3.dot(n4) <= 0) return -1; // the new pair would fold
  // Nor may it turn the pair over: both new normals agree with the old ones.
  const Vec3 old = (vj - vi).cross(vk - vi) + (vl - vi).cross(vj - vi);
  if (n3.dot(old) <= 0 || n4.dot(old) <= 0) return -1;
  // OpenMesh only sees this patch; the new edge must not exist in another one
  // (openmesh-probe.md, pitfall 2). Asked of every patch, this is all that
  // OpenMesh's is_flip_ok() asks besides the boundary test above (no new edge
  // between the opposite copies, which are no one vertex), so that is not
  // asked again (it was 3.7% of a run on 1,000 grains).
  if (nodes[2] == nodes[3] || mesh.adjacent(nodes[2], nodes[3])) return -1;
  // An edge along a box edge (its nodes share box faces of two axes) is a crease
  // of a closed domain's outside surface: flipping it would cut the box corner.
  const uint8_t common = mesh.box_faces()[size_t(nodes[0])] & mesh.box_faces()[size_t(nodes[1])];
  if (((common & 3) != 0) + ((common & 12) != 0) + ((common & 48) != 0) >= 2) return -1;
  // Nor may it sweep a kept point (a voxel-faithful volume's thin structures)
  // out of its phase (asked only of fields that keep points).
  if (p.field && p.field->keeps_points() &&
      detail::flip_loses_kept_point(pos, nodes, mesh.pair(om.face_handle(h0)), *p.field))
    return -1;
  return ear ? 1 + (after - before) : after - before;
}

/// One process's choice among `found` (best first): each candidate whose nodes
/// no better candidate took. Flips in one round share no node, so every
/// judgement stays true until its own flip.
void choose_greedily(const InterfaceMesh& mesh, const std::vector<FlipCandidate>& found, std::vector<uint8_t>& take) {
  std::vector<char> taken(mesh.num_nodes(), 0);
  for (size_t c = 0; c < found.size(); ++c) {
    const auto& nodes = found[c].nodes;
    take[c] = std::none_of(nodes.begin(), nodes.end(), [&](int32_t n) { return taken[size_t(n)]; });
    if (take[c])
      for (int32_t n : nodes) taken[size_t(n)] = 1;
  }
}

/// Best gain first, ties by the edge's nodes (not its OpenMesh id, so that the
/// order depends on the mesh alone).
bool better(const FlipCandidate& a, const FlipCandidate& b) {
  if (a.gain != b.gain) return a.gain > b.gain;
  return std::tie(a.nodes[0], a.nodes[1]) < std::tie(b.nodes[0], b.nodes[1]);
}

/// The rounds of Algorithm 5 over `edges` (every edge: the paper's), never
/// flipping a `banned` one (one flag an edge); every flip goes into `log`.
FlipStats flip_rounds(InterfaceMesh& mesh, const FlipParams& params, std::vector<int32_t> edges,
                      const std::vector<uint8_t>& banned, detail::FlipLog& log, FlipPeers* peers) {
  FlipStats stats;
  FaceQuality quality(mesh);
  const size_t logged = log.size();
  // Each edge's gain is written by the task of its edge: assigned in this
  // thread first, the first round's entries on 1M triangles were a serial pass
  // over fresh memory. Gains alone, and the few gaining edges judged again
  // for their nodes: whole candidates for every edge, 50 MB on 1M triangles,
  // came from fresh pages at every call (glibc maps anything over 32 MB anew),
  // a third of a run's page faults once collapses stopped rebuilding the mesh.
  detail::UnsetVector<double> gain;
  std::vector<FlipCandidate> found;
  std::vector<uint8_t> take;
  for (int round = 0; round < params.max_rounds; ++round) {
    detail::resize_to_overwrite(gain, edges.size());
    detail::parallel_for_each_index(edges.size(), [&](size_t i) {
      std::array<int32_t, 4> nodes;
      gain[i] = banned[size_t(edges[i])] ? -1 : flip_gain(mesh, quality, OMesh::EdgeHandle(edges[i]), params, nodes);
    });
    // Gathered and sorted in parallel: `better` is a total order (an edge's
    // nodes are its own), so the list is the same for any thread count.
    const std::vector<int32_t> gaining = detail::indices_where(gain.size(), [&](size_t i) { return gain[i] > 0; });
    found.resize(gaining.size());
    detail::parallel_for_each_index(gaining.size(), [&](size_t i) {
      const int32_t e = edges[size_t(gaining[i])];
      found[i] = FlipCandidate{gain[size_t(gaining[i])], e, {}};
      flip_gain(mesh, quality, OMesh::EdgeHandle(e), params, found[i].nodes);
    });
    detail::parallel_sort(found.begin(), found.end(), better);
    if (peers ? !peers->any(!found.empty()) : found.empty()) break;
    take.assign(found.size(), 0);
    if (peers) peers->choose(found, take);
    else choose_greedily(mesh, found, take);
    const OMesh& om = mesh.omesh();
    edges.clear();
    for (size_t c = 0; c < found.size(); ++c) {
      if (!take[c]) {
        edges.push_back(found[c].edge); // lost to a better flip nearby: judge it again next round
        continue;
      }
      const OMesh::EdgeHandle eh(found[c].edge);
      log.flip(mesh, eh, found[c].nodes);
      ++stats.flips;
      for (int side = 0; side < 2; ++side) {
        const auto f = om.face_handle(om.halfedge_handle(eh, side));
        quality.update(f);
        for (auto e : om.fe_range(f)) edges.push_back(e.idx());
      }
    }
    detail::parallel_sort(edges.begin(), edges.end(), std::less<int32_t>());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    stats.rounds = round + 1;
  }
  if (stats.flips) mesh.faces_changed(log.faces(logged));
  return stats;
}

/// The flips to blame (by their edge's nodes before the flip) for the
/// crossings of the faces flagged in `test` with any triangle: for each face of
/// a crossing pair, the last flip that made it and stays (`undone` flags those
/// that do not). With a field, also that flip for each tested junction face that
/// faces against its phase pair (a flip that would take a kept point out of its
/// phase is never made: flip_gain()). A face no staying flip made is as old as the
/// call, and so is a crossing of two such faces. `only_test_changed`: the faces in `test`
/// are the only ones changed since the guard's last check (in one process).
std::vector<std::array<int32_t, 2>> culprits_of(const InterfaceMesh& mesh, const detail::FlipLog& log,
                                                const std::vector<uint8_t>& undone, const std::vector<uint8_t>& test,
                                                const FlipParams& params, CrossingGuard& guard,
                                                FlipPeers* peers, bool only_test_changed) {
  std::vector<int32_t> last_flip(mesh.num_triangles(), -1);
  for (size_t i = 0; i < log.size(); ++i)
    if (!undone[i])
      for (int32_t f : log.faces_of(i)) last_flip[size_t(f)] = int32_t(i);
  const auto& triangles = mesh.triangles();
  if (peers) // another rank answers for the rest
    for (size_t f = 0; f < last_flip.size(); ++f)
      if (last_flip[f] >= 0 && !peers->answers_for(triangles[f])) last_flip[f] = -1;
  std::vector<std::array<int32_t, 2>> culprits;
  for (const auto& pair :
       only_test_changed && !peers ? guard.crossings_of_changed(mesh, test) : guard.crossings(mesh, test))
    for (int32_t f : pair)
      if (last_flip[size_t(f)] >= 0) culprits.push_back(log.edge_nodes(size_t(last_flip[size_t(f)])));
  if (params.field)
    for (size_t f = 0; f < last_flip.size(); ++f) {
      if (!test[f] || last_flip[f] < 0) continue;
      if (detail::touches_junction(mesh, triangles[f]) &&
          !detail::agrees_with_field(mesh.positions(), triangles[f], mesh.pair(OMesh::FaceHandle(int(f))),
                                     *params.field))
        culprits.push_back(log.edge_nodes(size_t(last_flip[f])));
    }
  return culprits;
}

/// The flips of `log` to undo now (one flag each): those not `undone` yet whose
/// edge's nodes are among `culprits`, and those that must be undone with them
/// (FlipLog::with_dependents()). With peers, a flip is flagged as one process
/// flags it once every rank has heard of the others' flags: each rank says
/// which flips it flagged since, each by its edge and how many flips of that
/// edge came before it (improve/flip_peers.hpp), until no rank flags one more.
/// (By its edge alone, an earlier flip of it would be undone too, as a culprit
/// is, where one process keeps it.)
std::vector<uint8_t> to_undo(const InterfaceMesh& mesh, const detail::FlipLog& log,
                             std::vector<std::array<int32_t, 2>> culprits, const std::vector<uint8_t>& undone,
                             FlipPeers* peers) {
  std::sort(culprits.begin(), culprits.end());
  std::vector<uint8_t> undo(log.size(), 0);
  for (size_t i = 0; i < log.size(); ++i)
    undo[i] = !undone[i] && std::binary_search(culprits.begin(), culprits.end(), log.edge_nodes(i));
  std::map<detail::FlipInstance, size_t> flip_of; // with peers: each flip by its name across ranks
  std::vector<int32_t> earlier(peers ? log.size() : 0);
  if (peers) {
    std::map<std::array<int32_t, 2>, int32_t> flips_of_edge;
    for (size_t i = 0; i < log.size(); ++i) {
      earlier[i] = flips_of_edge[log.edge_nodes(i)]++;
      flip_of[{log.edge_nodes(i), earlier[i]}] = i;
    }
  }
  while (true) {
    const std::vector<uint8_t> before = undo;
    log.with_dependents(undo, undone, mesh.num_nodes());
    if (!peers) return undo;
    std::vector<detail::FlipInstance> flagged;
    for (size_t i = 0; i < log.size(); ++i)
      if (undo[i] && !before[i]) flagged.push_back({log.edge_nodes(i), earlier[i]});
    if (!peers->agree_on_flips(flagged)) return undo;
    for (const detail::FlipInstance& f : flagged) {
      const auto found = flip_of.find(f);
      if (found != flip_of.end() && !undone[found->second]) undo[found->second] = 1;
    }
  }
}

/// The edges of the faces with a node of a flip flagged in `undone_now`, each
/// once: where flips may gain now, the undone ones' edges and those that lost
/// to them.
std::vector<int32_t> edges_around(const InterfaceMesh& mesh, const detail::FlipLog& log,
                                  const std::vector<uint8_t>& undone_now) {
  std::vector<uint8_t> near(mesh.num_nodes(), 0);
  for (size_t i = 0; i < log.size(); ++i)
    if (undone_now[i])
      for (int32_t n : log.quad(i)) near[size_t(n)] = 1;
  const OMesh& om = mesh.omesh();
  const auto& triangles = mesh.triangles();
  std::vector<int32_t> edges;
  for (size_t f = 0; f < triangles.size(); ++f)
    if (near[size_t(triangles[f][0])] || near[size_t(triangles[f][1])] || near[size_t(triangles[f][2])])
      for (auto e : om.fe_range(OMesh::FaceHandle(int(f)))) edges.push_back(e.idx());
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

/// Bans every edge whose flip would change a triangle at one of `nodes`: the
/// edges at each copy of the node and the edges across from it.
void ban_around(const InterfaceMesh& mesh, std::span<const int32_t> nodes, std::vector<uint8_t>& banned) {
  const OMesh& om = mesh.omesh();
  for (int32_t n : nodes)
    for (int32_t copy : mesh.copies(n))
      for (const auto h : om.voh_range(OMesh::VertexHandle(copy))) {
        banned[size_t(om.edge_handle(h).idx())] = 1;
        if (!om.is_boundary(h)) banned[size_t(om.edge_handle(om.next_halfedge_handle(h)).idx())] = 1;
      }
}

/// flip_edges() without the collapses, with or without peers.
FlipStats flip_all_rounds(InterfaceMesh& mesh, const FlipParams& params, FlipPeers* peers) {
  const size_t edge_count = mesh.omesh().n_edges();
  std::vector<int32_t> every(edge_count);
  std::iota(every.begin(), every.end(), 0);
  std::vector<uint8_t> banned(edge_count, 0);
  // The triangles kept for the floor pass, which runs in one process only.
  if (!peers) ban_around(mesh, params.keep_triangles_at, banned);
  detail::FlipLog log;
  const uint64_t unflipped = mesh.version();
  FlipStats stats = flip_rounds(mesh, params, std::move(every), banned, log, peers);
  if (!params.guard_crossings) return stats;
  // A flip moves no node but can still push the new diagonal through a
  // neighbouring surface where a phase is thinner than the quad. Such flips are
  // found after the rounds and undone exactly (improve/flip_log.hpp), with the
  // later flips that share a node with them; the culprits are banned for the
  // call, and the edges around what was undone flip again (up to
  // kMaxFlipRepairs times). The faces that brings back or makes are checked in
  // turn, until no crossing is left that a flip made: a mesh without crossings
  // keeps none. (Undoing every flip and flipping anew, as before, cost a third
  // of the pass on grain maps.)
  CrossingGuard own_guard;
  CrossingGuard& guard = params.guard ? *params.guard : own_guard;
  // Where the guard last checked the mesh as the flips found it (the commit of
  // the moves before them), the flipped faces are all that changed since: even
  // the first check costs time in them, not in the mesh.
  const bool only_flips_since_check = guard.checked_at(unflipped);
  std::vector<uint8_t> undone(log.size(), 0);
  std::vector<uint8_t> test(mesh.num_triangles(), 0);
  for (int32_t f : log.faces()) test[size_t(f)] = 1;
  for (int repairs = 0;; ++repairs) {
    std::vector<std::array<int32_t, 2>> culprits =
        log.empty() ? std::vector<std::array<int32_t, 2>>{}
                    : culprits_of(mesh, log, undone, test, params, guard, peers,
                                  repairs > 0 || only_flips_since_check);
    if (peers ? !peers->agree_on_culprits(culprits) : culprits.empty()) break;
    if (repairs == kMaxFlipRepairs) { // as crossed as ever: this call flips nothing
      std::vector<uint8_t> rest(log.size());
      for (size_t i = 0; i < rest.size(); ++i) rest[i] = !undone[i];
      log.undo(mesh, rest);
      undone.assign(log.size(), 1);
      break;
    }
    const std::vector<uint8_t> undo = to_undo(mesh, log, culprits, undone, peers);
    std::sort(culprits.begin(), culprits.end());
    std::fill(test.begin(), test.end(), 0);
    for (size_t i = 0; i < log.size(); ++i) {
      if (std::binary_search(culprits.begin(), culprits.end(), log.edge_nodes(i))) banned[size_t(log.edges()[i])] = 1;
      undone[i] = undone[i] || undo[i];
      if (undo[i])
        for (int32_t f : log.faces_of(i)) test[size_t(f)] = 1;
    }
    log.undo(mesh, undo);
    const size_t logged = log.size();
    const FlipStats again = flip_rounds(mesh, params, edges_around(mesh, log, undo), banned, log, peers);
    stats.flips += again.flips;
    stats.rounds += again.rounds;
    undone.resize(log.size(), 0);
    for (int32_t f : log.faces(logged)) test[size_t(f)] = 1;
  }
  stats.flips -= size_t(std::count(undone.begin(), undone.end(), 1));
  return stats;
}

} // namespace

FlipStats flip_edges(InterfaceMesh& mesh, const FlipParams& params) {
  FlipStats stats = flip_all_rounds(mesh, params, nullptr);
  stats.collapses = collapse_junction_slivers(
      mesh, CollapseParams{params.collapse_below, CollapseParams{}.max_collapses, params.guard_crossings, params.guard,
                           params.field});
  return stats;
}

namespace detail {

FlipStats flip_edges(InterfaceMesh& mesh, const FlipParams& params, PartAgreement& parts) {
  parts.before_topology_change(mesh);
  FlipStats stats = flip_all_rounds(mesh, params, &parts.flip_peers());
  CollapseKept kept;
  stats.collapses = collapse_junction_slivers(
      mesh, CollapseParams{params.collapse_below, CollapseParams{}.max_collapses, params.guard_crossings, params.guard,
                           params.field},
      parts.collapse_peers(), parts.node_ids(), parts.triangle_ids(), kept);
  if (stats.collapses) parts.renumbered(kept);
  return stats;
}

} // namespace detail

} // namespace vm
