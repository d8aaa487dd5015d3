/// @file mpi/improve_part.cpp
/// vm::mpi::improve_part(): the pipeline over the ranks.
///
/// The ranks split space into bands of z, balanced by vertices; a vertex belongs
/// to the band it lies in (so a vertex that moves across a cut migrates by
/// itself), a triangle to the owner of its corner with the lowest id. Each
/// iteration a rank works on its window (window.hpp): every triangle with a
/// corner within a few edge lengths of its band, built afresh in the assembled
/// mesh's id order, so the passes see around its vertices exactly what one
/// process sees. Moves are computed for the whole window, then every window
/// vertex takes its owner's move; the guard and the flips agree across ranks
/// where one process would look at the whole mesh (improve/guard.hpp, flip_peers.hpp).
/// The RMS edge length is a fixed-point sum over the ranks' own edges. At the
/// end of an iteration the owners send the new positions, then the triangles
/// to the windows they touch.

#include "voronoimesh/mpi/distributed.hpp"
#include "voronoimesh/mesh/triangle_quality.hpp"

#include "improve/convergence.hpp"
#include "improve/edge_lengths.hpp"
#include "improve/field_checks.hpp"
#include "improve/part_agreement.hpp"
#include "mpi/window.hpp"
#include "mpi/window_collapse_peers.hpp"
#include "mpi/window_flip_peers.hpp"
#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <tuple>
#include <limits>
#include <unordered_map>

namespace vm::mpi {

namespace {

using detail::Bands;
using detail::Comm;
using detail::TriangleRecord;
using detail::VertexRecord;
using detail::Window;
using detail::exchange;

/// Every rank's `mine` added up (the same total, bit for bit, in any order).
double global_sum(Comm& comm, const vm::detail::FixedPointSum& mine) {
  const auto raw = mine.raw();
  const std::array<uint64_t, 2> halves{uint64_t(raw), uint64_t(raw >> 64)};
  const std::vector<uint64_t> all = comm.all_gather(std::span<const uint64_t>(halves));
  vm::detail::FixedPointSum total(mine.unit());
  for (size_t i = 0; i < all.size(); i += 2)
    total.add_raw(vm::detail::FixedPointSum::Raw((unsigned __int128)all[i + 1] << 64 | all[i]));
  return total.total();
}

/// The RMS edge length over every rank's window, each edge counted by the
/// owner of its lower vertex.
double global_rms_edge_length(Comm& comm, const InterfaceMesh& mesh, const std::vector<uint8_t>& own) {
  const vm::detail::SquaredEdgeLengths mine = vm::detail::squared_edge_lengths(mesh, own);
  const double total = global_sum(comm, mine.sum);
  const uint64_t edges = comm.sum(mine.edges);
  return edges ? std::sqrt(total / double(edges)) : 0.0;
}

/// The smallest and the mean triangle quality of the whole mesh, from each
/// rank's own triangles (quality_summary() of the mesh they make up).
std::pair<double, double> global_quality(Comm& comm, const std::vector<TriangleRecord>& own) {
  auto at = [](const double* p) { return Vec3(p[0], p[1], p[2]); };
  double worst = 1;
  vm::detail::FixedPointSum sum(1.0);
  for (const TriangleRecord& t : own) {
    const double q = triangle_quality(at(t.xyz[0]), at(t.xyz[1]), at(t.xyz[2]));
    worst = std::min(worst, q);
    sum.add(q);
  }
  const uint64_t count = comm.sum(own.size());
  return {comm.min(worst), count ? global_sum(comm, sum) / double(count) : 0.0};
}

/// Gives every vertex of the window its owner's move: each rank sends the moves
/// of its own vertices to the windows that reach them (`reach` from a band).
void share_moves(Comm& comm, const Window& w, const std::vector<uint8_t>& own, const Bands& bands, double reach,
                 std::vector<Vec3>& delta) {
  std::vector<VertexRecord> mine;
  for (size_t v = 0; v < own.size(); ++v)
    if (own[v]) mine.push_back({w.vertex_ids[v], {delta[v].x(), delta[v].y(), delta[v].z()}});
  size_t given = 0;
  for (const VertexRecord& r : exchange(comm, mine, [&](const VertexRecord& r, int to) {
         return bands.near(to, w.mesh.points[size_t(w.local(r.id))].z(), reach);
       })) {
    const int32_t v = w.local(r.id);
    if (v < 0) continue;
    delta[size_t(v)] = Vec3(r.xyz[0], r.xyz[1], r.xyz[2]);
    ++given;
  }
  if (given != delta.size())
    throw Error("mpi: internal error: " + std::to_string(delta.size() - given) +
                " vertices of a window got no move from their owner (please report this)");
}

/// The undone moves of every rank, in this window (the guard's agreement);
/// whether there were any.
bool agree_on_undone(Comm& comm, const Window& w, std::vector<int32_t>& undone) {
  std::vector<int64_t> ids;
  for (int32_t v : undone) ids.push_back(w.vertex_ids[size_t(v)]);
  std::vector<int64_t> all = comm.all_gather(std::span<const int64_t>(ids));
  if (all.empty()) return false;
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  undone.clear();
  for (int64_t id : all)
    if (const int32_t v = w.local(id); v >= 0) undone.push_back(v);
  return true;
}

/// How far a window must reach from its band for flips, when vertices have
/// moved up to `moved` and edges are up to `edge` long: a flip's decision looks
/// four edges from its lower vertex (the candidates sharing a node with its quad,
/// and their quads), and the window's faces were chosen before the moves.
double flip_reach(double edge, double moved) { return 5 * (edge + 2 * moved) + 2 * moved; }

/// This rank's part: its triangles and vertices (`positions`: of every vertex
/// it knows, by id).
void rebuild_part(MeshPart& part, const std::vector<TriangleRecord>& triangles,
                  const std::unordered_map<int64_t, Vec3>& positions, const Bands& bands, int me) {
  const Window w = detail::build_window(triangles, part);
  part.points = w.mesh.points;
  part.triangles = w.mesh.triangles;
  part.pairs = w.mesh.pairs;
  part.global_ids = w.vertex_ids;
  part.triangle_ids = w.triangle_ids;
  // Its own vertices that none of its triangles use (all theirs belong to
  // lower vertices of other ranks) are in the part too, so that every vertex is.
  std::vector<int64_t> unused;
  for (const auto& [id, p] : positions)
    if (bands.owner(p.z()) == me && !std::binary_search(w.vertex_ids.begin(), w.vertex_ids.end(), id))
      unused.push_back(id);
  std::sort(unused.begin(), unused.end());
  for (int64_t id : unused) {
    part.points.push_back(positions.at(id));
    part.global_ids.push_back(id);
  }
  part.owners.clear();
  for (const Vec3& p : part.points) part.owners.push_back(bands.owner(p.z()));
}

/// What stays the same through a run of improve_part().
struct Run {
  Comm& comm;
  const Bands& bands;
  const Pipeline& pipeline;
  std::vector<std::unique_ptr<Pass>> passes; // the pipeline's, made once
  const PhaseField& field;
  bool guard_crossings;
  const MeshPart& part; // domain and phases for the windows
  double tolerance;
  int iterations; // the run's last iteration
  uint64_t window_triangles = 0, own_triangles = 0;
  int wider_windows = 0;
};

/// The largest move of this rank's own vertices since the window was built.
double largest_move(Comm& comm, const InterfaceMesh& mesh, const Window& w, const std::vector<uint8_t>& own) {
  double moved = 0;
  for (size_t v = 0; v < own.size(); ++v)
    if (own[v]) moved = std::max(moved, (mesh.positions()[v] - w.mesh.points[v]).norm());
  return comm.max(moved);
}

/// Thrown on every rank at once when the moves of an iteration outgrew what
/// the flips' window was built for: the iteration runs again on wider windows.
struct WiderWindowsNeeded {
  double moved;
};

/// How the passes agree across the ranks' windows (improve/part_agreement.hpp).
/// A window covers every triangle within `margin` of the rank's band, `reach`
/// bounds how far from a band its vertices lie, edges are up to `edge` long.
class WindowAgreement : public vm::detail::PartAgreement {
public:
  WindowAgreement(Run& run, Window& w, std::vector<uint8_t>& own, double edge, double margin, double reach)
      : run_(run), w_(w), own_(own), edge_(edge), margin_(margin), reach_(reach) {}

  double rms_edge_length(const InterfaceMesh& mesh) override { return global_rms_edge_length(run_.comm, mesh, own_); }
  void share_moves(std::vector<Vec3>& delta) override {
    mpi::share_moves(run_.comm, w_, own_, run_.bands, reach_, delta);
  }
  bool agree_on_undone(std::vector<int32_t>& undone) override {
    return mpi::agree_on_undone(run_.comm, w_, undone);
  }
  void before_topology_change(const InterfaceMesh& mesh) override {
    const double moved = largest_move(run_.comm, mesh, w_, own_);
    if (flip_reach(edge_, moved) > margin_ - run_.tolerance) throw WiderWindowsNeeded{moved};
  }
  vm::detail::FlipPeers& flip_peers() override {
    return flip_peers_.emplace(run_.comm, w_, own_, run_.bands, reach_);
  }
  vm::detail::CollapsePeers& collapse_peers() override { return collapse_peers_.emplace(run_.comm, own_); }
  std::span<const int64_t> node_ids() const override { return w_.vertex_ids; }
  std::span<const int64_t> triangle_ids() const override { return w_.triangle_ids; }
  /// The window follows the nodes and triangles the edited mesh keeps (their
  /// start positions and ownership too), under the ids they have now.
  void renumbered(const vm::detail::CollapseKept& kept) override {
    std::vector<Vec3> start;
    std::vector<uint8_t> still_own;
    for (int32_t v : kept.nodes) {
      start.push_back(w_.mesh.points[size_t(v)]);
      still_own.push_back(own_[size_t(v)]);
    }
    w_.vertex_ids = kept.node_ids;
    w_.triangle_ids = kept.triangle_ids;
    w_.mesh.points = std::move(start);
    w_.mesh.triangles.clear(); // the rebuilt mesh has them
    w_.mesh.pairs.clear();
    own_ = std::move(still_own);
  }

private:
  Run& run_;
  Window& w_;
  std::vector<uint8_t>& own_;
  double edge_, margin_, reach_;
  std::optional<detail::WindowFlipPeers> flip_peers_;
  std::optional<detail::WindowCollapsePeers> collapse_peers_;
};

/// Iteration `iteration` (1-based, as PassContext::iteration) on windows
/// reaching `margin` from the bands, edges up to `edge` long, no move leaving a
/// triangle below `quality_floor`. Returns the largest move; or, when the moves
/// turned out too large for the flips' window, minus that move, with nothing
/// changed (the caller builds wider windows and runs the iteration again).
double iterate(Run& run, int iteration, double edge, double margin, double quality_floor,
               std::vector<TriangleRecord>& sending, std::unordered_map<int64_t, Vec3>& moved_to) {
  Comm& comm = run.comm;
  const Bands& bands = run.bands;
  const int me = comm.rank();
  Window w = detail::build_window(exchange(comm, sending, [&](const TriangleRecord& t, int r) {
                                    return bands.near(r, t.xyz[0][2], margin) || bands.near(r, t.xyz[1][2], margin) ||
                                           bands.near(r, t.xyz[2][2], margin);
                                  }),
                                  run.part);
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(w.mesh);
  std::vector<uint8_t> own(mesh.num_nodes());
  for (size_t v = 0; v < own.size(); ++v) own[v] = bands.owner(w.mesh.points[v].z()) == me;
  // A window's vertices lie within a triangle's reach of the window.
  const double reach = margin + edge + run.tolerance;

  // The pipeline's iteration, each pass agreeing with the other ranks where
  // one process would look at the whole mesh.
  WindowAgreement parts(run, w, own, edge, margin, reach);
  PassContext context(mesh, &run.field);
  context.guard_crossings = run.guard_crossings;
  context.iteration = iteration; // passes may depend on it (the flip pass's collapses do)
  context.iterations = run.iterations;
  context.quality_floor = quality_floor;
  context.parts = &parts;
  try {
    run.pipeline.iterate(context, run.passes);
  } catch (const WiderWindowsNeeded& wider) {
    return -wider.moved;
  }
  run.window_triangles += w.triangle_ids.size();

  // Where the vertices went: the owners send them to every window that may
  // use them next (edges grow by at most their ends' moves, a flip's new
  // diagonal is at most two edges).
  const double moved = largest_move(comm, mesh, w, own);
  if (moved >= margin)
    throw Error("mpi: internal error: a vertex moved farther than the window reaches (please report this)");
  const double next_reach = 3 * (edge + 2 * moved) + 2 * run.tolerance;
  std::vector<VertexRecord> mine;
  const auto& pos = mesh.positions();
  for (size_t v = 0; v < own.size(); ++v)
    if (own[v]) mine.push_back({w.vertex_ids[v], {pos[v].x(), pos[v].y(), pos[v].z()}});
  moved_to.clear();
  for (const VertexRecord& r : exchange(comm, mine, [&](const VertexRecord& r, int to) {
         return bands.near(to, r.xyz[2], next_reach);
       }))
    moved_to[r.id] = Vec3(r.xyz[0], r.xyz[1], r.xyz[2]);

  // This rank's triangles now: those whose lowest corner moved into its band.
  // A vertex moves less than a window's margin, so they are all in this window.
  const NodeMesh now = mesh.to_node_mesh(); // triangle t is still w's triangle t (flips keep faces)
  sending.clear();
  for (size_t t = 0; t < now.triangles.size(); ++t) {
    const auto& tri = now.triangles[t];
    const int32_t lowest = *std::min_element(tri.begin(), tri.end()); // local order is id order
    const auto found = moved_to.find(w.vertex_ids[size_t(lowest)]);
    if (found == moved_to.end() || bands.owner(found->second.z()) != me) continue;
    TriangleRecord r{w.triangle_ids[t], {}, now.pairs[t], {}};
    for (int k = 0; k < 3; ++k) {
      r.corners[k] = w.vertex_ids[size_t(tri[size_t(k)])];
      const auto corner = moved_to.find(r.corners[k]);
      if (corner == moved_to.end())
        throw Error("mpi: internal error: a triangle's corner is missing from its owner's window (please report this)");
      for (int a = 0; a < 3; ++a) r.xyz[k][a] = corner->second[a];
    }
    sending.push_back(r);
  }
  run.own_triangles += sending.size();
  return moved;
}

} // namespace

void improve_part(MPI_Comm c, MeshPart& part, const PhaseField& field, const Pipeline& pipeline, int iterations,
                  bool guard_crossings, DistributedStats* stats, bool stop_when_converged) {
  const auto start = std::chrono::steady_clock::now();
  Comm comm(c);
  uint64_t window_triangles = 0, own_triangles = 0;
  int wider_windows = 0, done = 0;
  comm.collectively([&] {
    for (const Pipeline::Step& s : pipeline.steps())
      if (!s.info.distributed)
        throw InvalidInput("mpi: the pass '" + s.info.name +
                           "' does not run on parts of a distributed mesh (of the built-in passes, smooth, project, "
                           "clamp and flip do)");
    if (iterations <= 0) return;
    vm::detail::require_phases(field, part.pairs);
    std::vector<double> own_z;
    for (size_t v = 0; v < part.points.size(); ++v)
      if (part.owners[v] == comm.rank()) own_z.push_back(part.points[v].z());
    const Bands bands(comm, std::move(own_z));
    Run run{comm,           bands, pipeline, pipeline.make_passes(), field,
            guard_crossings, part,  1e-9 * (part.domain.max - part.domain.min).norm(), iterations};
    // The triangles this rank sends to windows: its created ones, then its own.
    std::vector<TriangleRecord> sending = detail::records_of(part);
    std::unordered_map<int64_t, Vec3> moved_to;
    // The distributed passes that move no nodes change the topology (flip and its
    // collapses), and look farther than the moving passes.
    const bool flips = std::any_of(pipeline.steps().begin(), pipeline.steps().end(),
                                   [](const Pipeline::Step& s) { return !s.info.moves_nodes; });
    double expected_move = -1; // none yet
    RunOptions rule; // Pipeline::run's stopping rule
    rule.iterations = iterations;
    rule.stop_when_converged = stop_when_converged;
    auto [worst, mean] = global_quality(comm, sending); // worst: Pipeline::run's quality floor
    vm::detail::Convergence convergence(rule, worst, mean, pipeline.settled_from());
    for (int it = 1; it <= convergence.last(); ++it) {
      run.iterations = convergence.last();
      const double edge = comm.max(detail::longest_edge(sending));
      // Moving passes look two edges away (a neighbour's phases come from its
      // own ring); flips farther, for moves guessed from the last iteration's
      // (a quarter of an edge in the first, which moves most), and again wider
      // in the rare iteration whose moves outgrow the guess.
      if (expected_move < 0) expected_move = 0.25 * edge;
      while (true) {
        const double margin = (flips ? flip_reach(edge, expected_move) : 2 * edge) + run.tolerance;
        const double moved = iterate(run, it, edge, margin, worst, sending, moved_to);
        expected_move = 1.5 * std::abs(moved);
        if (moved >= 0) break;
        ++run.wider_windows;
      }
      std::tie(worst, mean) = global_quality(comm, sending);
      convergence.after(it, worst, mean);
      done = it;
    }
    rebuild_part(part, sending, moved_to, bands, comm.rank());
    // Collapses removed vertices and triangles.
    uint64_t own_vertices = 0;
    for (int32_t o : part.owners) own_vertices += o == comm.rank();
    part.global_nodes = int64_t(comm.sum(own_vertices));
    part.global_triangles = int64_t(comm.sum(part.triangles.size()));
    window_triangles = run.window_triangles;
    own_triangles = run.own_triangles;
    wider_windows = run.wider_windows;
  });
  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->mpi_seconds = comm.mpi_seconds();
    stats->bytes_sent = comm.bytes_sent();
    stats->collectives = comm.collectives();
    stats->window_triangles = window_triangles;
    stats->own_triangles = own_triangles;
    stats->wider_windows = wider_windows;
    stats->iterations = done;
  }
}

} // namespace vm::mpi
