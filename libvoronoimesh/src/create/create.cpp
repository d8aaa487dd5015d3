#include "voronoimesh/create/create.hpp"

#include "check/validate_part.hpp"
#include "core/clock.hpp"
#include "core/huge_pages.hpp"
#include "core/text.hpp"
#include "create/coincident_triangles.hpp"
#include "create/create_slabs.hpp"
#include "create/lattice.hpp"
#include "create/limit_key_index.hpp"
#include "create/node_values.hpp"
#include "create/slab_numbering.hpp"
#include "create/tet_cutter.hpp"
#include "create/tiny_loops.hpp"
#include "fields/node_sampling.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <numeric>
#include <tuple>

namespace vm {
namespace {

/// The largest closed triple curve closed, in cells along each axis (create/tiny_loops.hpp).
constexpr double kTinyLoopCells = 0.1;
/// How far below the leader, in snaps, a tiny loop's phase rises, up to kMaxSnap.
constexpr double kTinyLoopSnap = 2;
/// The farthest snap: CreateParams::snap's largest.
constexpr double kMaxSnap = 0.5;

using detail::SlabsMesh;
using detail::CutTriangle;
using detail::LimitKey;
using detail::LimitKeyIndex;
using SlabRange = std::array<int, 2>;

/// What one slab of the lattice produced: its distinct limit points (with
/// positions) and triangles indexing them.
struct SlabResult {
  std::vector<LimitKey> keys;
  std::vector<Vec3> points;
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<PhasePair> pairs;
  detail::CutCounters counters;
  uint64_t tets = 0;
  uint64_t dropped = 0;
  uint64_t box_triangles = 0;
};

/// Cuts the tetrahedra of one slab, and with `outside` >= 0 their faces on the
/// box too. Points are numbered within the slab; a triangle with two corners on
/// one point is dropped.
void cut_slab(const detail::TetLattice& lattice, const detail::NodeValues& values, const GridSpec& grid, int slab,
              int32_t outside, SlabResult& r) {
  detail::TetCutter cutter(values, lattice, grid);
  LimitKeyIndex local;
  std::vector<CutTriangle> cut;
  // A block whose nodes all have the same winner holds no interface: that phase
  // beats every other at every corner of every tet in it.
  auto one_winner = [&](const int64_t* nodes, int count) {
    const int32_t label = values.label(nodes[0]);
    for (int c = 1; c < count; ++c)
      if (values.label(nodes[c]) != label) return false;
    return true;
  };
  // Closing needs every block on the box, even with one winner: its faces there
  // are that phase's boundary.
  auto on_box = [&](const int64_t* nodes, int count) {
    for (int c = 0; c < count; ++c) {
      const detail::GridPoint p = lattice.grid_point(nodes[c]);
      for (int a = 0; a < 3; ++a)
        if (p[size_t(a)] == 0 || p[size_t(a)] == grid.cells[size_t(a)]) return true;
    }
    return false;
  };
  auto skip = [&](const int64_t* nodes, int count) {
    return one_winner(nodes, count) && !(outside >= 0 && on_box(nodes, count));
  };
  r.tets = lattice.for_each_tet(slab, skip, [&](const std::array<int64_t, 4>& nodes) {
    cut.clear();
    cutter.cut(nodes, cut, r.counters);
    const size_t interior = cut.size();
    if (outside >= 0) cutter.cut_box_faces(nodes, outside, cut, r.counters);
    r.box_triangles += cut.size() - interior;
    for (const CutTriangle& t : cut) {
      std::array<int32_t, 3> tri;
      for (int c = 0; c < 3; ++c) {
        const auto [id, inserted] = local.insert(t.corners[c], r.keys);
        if (inserted) {
          r.keys.push_back(t.corners[c]);
          r.points.push_back(cutter.position(t.corners[c]));
        }
        tri[c] = id;
      }
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
        ++r.dropped;
        continue;
      }
      r.triangles.push_back(tri);
      r.pairs.push_back(t.pair);
    }
  });
}

/// Cuts the tetrahedra of the slabs cut[0]..cut[1] flagged in `recut` (in
/// parallel, slab by slab; the others keep what an earlier round found, their
/// nodes' values being unchanged) and numbers the limit points of those slabs
/// in order of first appearance. Slabs are a property of the lattice, not of
/// the thread count, and are merged in order: the result is the same for any
/// number of threads, and the same as cutting every slab again. Statistics
/// count the `owned` slabs.
SlabsMesh extract(const detail::TetLattice& lattice, const detail::NodeValues& values, const GridSpec& grid,
                   int32_t outside, const std::vector<char>& recut, std::vector<SlabResult>& slabs, SlabRange owned,
                   SlabRange cut, CreateStats& stats) {
  detail::parallel_for(cut[0], cut[1] + 1, [&](int s) {
    if (!recut[size_t(s)]) return;
    slabs[size_t(s)] = SlabResult{};
    cut_slab(lattice, values, grid, s, outside, slabs[size_t(s)]);
  });

  std::vector<const std::vector<LimitKey>*> slab_keys;
  for (int slab = cut[0]; slab <= cut[1]; ++slab) slab_keys.push_back(&slabs[size_t(slab)].keys);
  const detail::SlabNumbering numbering = detail::number_slabs(lattice, slab_keys, cut[0]);
  const size_t n = size_t(cut[1] - cut[0] + 1), points = size_t(numbering.fresh[n]);
  SlabsMesh e;
  detail::resize_on_huge_pages(e.points, points);
  detail::resize_on_huge_pages(e.keys, points);
  detail::assign_on_huge_pages(e.where, points, 0);
  std::vector<size_t> first_triangle(n + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const int slab = cut[0] + int(i);
    const SlabResult& s = slabs[size_t(slab)];
    first_triangle[i + 1] = first_triangle[i] + s.triangles.size();
    const uint8_t place = slab < owned[0]   ? detail::kBelowOwned
                          : slab > owned[1] ? detail::kAboveOwned
                                            : detail::kInOwned;
    if (place == detail::kInOwned) {
      stats.tets_visited += s.tets;
      stats.tets_cut += s.counters.tets_cut;
      stats.polygons += s.counters.polygons;
      stats.degenerate_cuts += s.counters.degenerate;
      stats.collapsed_polygons += s.counters.collapsed;
      stats.dropped_triangles += s.dropped;
      stats.box_triangles += s.box_triangles;
    }
    // Marks where each point was made, from every slab that holds it.
    const uint8_t where = place | (recut[size_t(slab)] ? detail::kRecut : 0);
    for (const int32_t id : numbering.global[i]) e.where[size_t(id)] |= where;
    if (slab == owned[0]) e.owned_begin = first_triangle[i];
    if (slab == owned[1]) e.owned_end = first_triangle[i + 1];
  }
  detail::resize_on_huge_pages(e.triangles, first_triangle[n]);
  detail::resize_on_huge_pages(e.pairs, first_triangle[n]);
  // Each point is written by the slab where it first appears.
  detail::parallel_for(size_t(0), n, [&](size_t i) {
    const SlabResult& s = slabs[size_t(cut[0]) + i];
    const std::vector<int32_t>& global = numbering.global[i];
    for (size_t k = 0; k < s.keys.size(); ++k)
      if (global[k] >= numbering.fresh[i] && global[k] < numbering.fresh[i + 1]) {
        e.points[size_t(global[k])] = s.points[k];
        e.keys[size_t(global[k])] = s.keys[k];
      }
    for (size_t t = 0; t < s.triangles.size(); ++t) {
      const auto& tri = s.triangles[t];
      e.triangles[first_triangle[i] + t] = {global[size_t(tri[0])], global[size_t(tri[1])], global[size_t(tri[2])]};
      e.pairs[first_triangle[i] + t] = s.pairs[t];
    }
  });
  e.first_owned_slab = numbering.global[size_t(owned[0] - cut[0])];
  if (cut[1] > owned[1]) e.slab_above = numbering.global[n - 1];
  return e;
}

} // namespace

GridSpec grid_for_lattice(const GridSpec& grid, Lattice lattice) {
  GridSpec g = grid;
  if (lattice == Lattice::bcc)
    for (int& c : g.cells) c += c % 2;
  return g;
}

namespace {

uint64_t saturated(double bytes) { return bytes > 1.8e19 ? UINT64_MAX : uint64_t(bytes); }

/// Bytes of one node's samples (SampledField): id (4 B) + value (8 B) per slot, floor 8 B.
double bytes_per_sample(int k) { return 12.0 * k + 8; }

double sample_bytes(const GridSpec& grid, int k, std::array<int32_t, 2> layers) {
  const double nodes = double(grid.cells[0] + 1) * double(grid.cells[1] + 1) * double(layers[1] - layers[0] + 1);
  return nodes * bytes_per_sample(k);
}

} // namespace

uint64_t estimate_sample_memory(const GridSpec& grid, int k, std::array<int32_t, 2> layers) {
  return saturated(sample_bytes(grid, k, layers));
}

uint64_t estimate_create_memory(const GridSpec& grid, Lattice lattice) {
  const double nodes = double(grid.cells[0] + 1) * double(grid.cells[1] + 1) * double(grid.cells[2] + 1);
  const double lattice_nodes = lattice == Lattice::bcc ? nodes / 4 : nodes;
  // NodeValues near interfaces at its peak: winner, lead and key (4 B each),
  // the held flag (1 B) per lattice node.
  return saturated(lattice_nodes * 13);
}

namespace {

void check_params(const CreateParams& params) {
  if (!(params.snap >= 0 && params.snap <= kMaxSnap))
    throw InvalidOption("snap", "must be between 0 and 0.5 (a fraction of the grid spacing h), got " +
                                    detail::cat(params.snap));
}

/// The grid layers whose nodes the owner of slabs `owned` counts in statistics:
/// from the first layer of its first slab to below the first layer of the next
/// owner's, so every layer is counted once.
std::array<int32_t, 2> counted_layers(const detail::TetLattice& lattice, SlabRange owned, int32_t top) {
  const int next = owned[1] + 1;
  return {lattice.layers_of_slabs(owned[0], owned[0])[0],
          next < lattice.num_slabs() ? lattice.layers_of_slabs(next, next)[0] - 1 : top};
}

uint64_t count_snapped(const detail::NodeValues& values, const detail::TetLattice& lattice,
                       std::array<int32_t, 2> layers) {
  const detail::NodeWindow w = lattice.window(layers[0], layers[1]);
  uint64_t snapped = 0;
  for (int r = 0; r < 2; ++r)
    for (int64_t id = w.first[size_t(r)]; id < w.first[size_t(r)] + w.count[size_t(r)]; ++id)
      snapped += values.snapped(id);
  return snapped;
}

/// The lattice nodes of the vertices in the problems validate() finds around
/// the vertices of the owned slabs, and how many problems it finds. `whole`:
/// the part is the whole mesh. Otherwise only the vertices made in the owned
/// slabs have all their triangles in the part: they are numbered first and
/// validate_first_nodes() checks them alone, which finds exactly the problems
/// validate() finds at them in the whole mesh. `only_recut` (with `whole`):
/// the slabs not cut in this round are as the last round, which found no
/// problem at their vertices, left them, so only the vertices of slabs cut in
/// this round are checked, the same way. (Every vertex of a problem is one:
/// its lattice nodes were repaired, and their slabs cut again.)
std::pair<std::vector<int64_t>, size_t> offending_nodes(SlabsMesh& part, const Box& domain, bool whole,
                                                        bool only_recut) {
  NodeMesh mesh;
  mesh.domain = domain;
  ValidationReport report;
  if (whole && !only_recut) {
    mesh.points = std::move(part.points);
    mesh.triangles = std::move(part.triangles);
    mesh.pairs = std::move(part.pairs);
    report = validate(mesh);
    part.points = std::move(mesh.points);
    part.triangles = std::move(mesh.triangles);
    part.pairs = std::move(mesh.pairs);
  } else {
    const uint8_t first = whole ? detail::kRecut : detail::kInOwned; // the vertices checked
    std::vector<int32_t> order, renumbered(part.points.size());
    for (int pass = 0; pass < 2; ++pass)
      for (size_t v = 0; v < part.points.size(); ++v)
        if (((part.where[v] & first) != 0) == (pass == 0)) {
          renumbered[v] = int32_t(order.size());
          order.push_back(int32_t(v));
        }
    size_t checked = 0;
    while (checked < order.size() && (part.where[size_t(order[checked])] & first)) ++checked;
    mesh.points.reserve(order.size());
    for (int32_t v : order) mesh.points.push_back(part.points[size_t(v)]);
    mesh.triangles.reserve(part.triangles.size());
    for (const auto& t : part.triangles)
      mesh.triangles.push_back({renumbered[size_t(t[0])], renumbered[size_t(t[1])], renumbered[size_t(t[2])]});
    mesh.pairs = part.pairs;
    report = detail::validate_first_nodes(mesh, checked);
    for (int32_t& v : report.nodes) v = order[size_t(v)];
  }
  std::vector<int64_t> nodes;
  for (int32_t v : report.nodes)
    for (int c = 0; c < part.keys[size_t(v)].count; ++c) nodes.push_back(part.keys[size_t(v)].nodes[c]);
  return {std::move(nodes), report.problem_count};
}

} // namespace

namespace detail {

CreateStats create_slabs(const NodeSource& field, NodeValues& values, const CreateParams& params, SlabRange owned,
                         CreatePeers& peers, SlabsMesh& part) {
  const auto start = std::chrono::steady_clock::now();
  check_params(params);
  const GridSpec& grid = field.grid();
  TetLattice lattice(grid, params.lattice);
  const int num_slabs = lattice.num_slabs();
  if (owned[0] < 0 || owned[1] >= num_slabs || owned[0] > owned[1])
    throw InvalidInput(cat("create: slabs ", owned[0], "..", owned[1], " are not within the lattice's 0..",
                           num_slabs - 1));
  // The slab on each side too, so that every triangle around a vertex of the
  // owned slabs is here (a lattice node's tetrahedra lie in two neighbouring slabs).
  const SlabRange cut{std::max(0, owned[0] - 1), std::min(num_slabs - 1, owned[1] + 1)};
  const bool whole = cut == owned;
  const std::array<int32_t, 2> layers = lattice.layers_of_slabs(cut[0], cut[1]);
  if (field.layers()[0] > layers[0] || field.layers()[1] < layers[1])
    throw InvalidInput(cat("create: the samples hold grid layers ", field.layers()[0], "..", field.layers()[1],
                           ", slabs ", cut[0], "..", cut[1], " need ", layers[0], "..", layers[1]));
  const NodeWindow& window = values.window();
  if (window.z0 > layers[0] || window.z1 < layers[1])
    throw InvalidInput(cat("create: the node values hold grid layers ", window.z0, "..", window.z1, ", slabs ", cut[0],
                           "..", cut[1], " need ", layers[0], "..", layers[1]));
  const std::array<int32_t, 2> counted = counted_layers(lattice, owned, grid.cells[2]);
  auto is_counted = [&](int64_t node) {
    const int32_t z = lattice.grid_point(node)[2];
    return z >= counted[0] && z <= counted[1];
  };

  // Snapping can tie three phases at both ends of a lattice edge, or tie phases at
  // a node so that one phase touches it from two sides: a pinched, non-manifold
  // phase boundary (DESIGN.md, "Snapping can pinch a phase"). Data can hold such
  // ties themselves (labels, integer values, seeds on grid nodes), and crossings
  // of three phases at one point of a lattice edge without any tie at its nodes.
  // The symbolic perturbation keeps all of these apart, but only infinitesimally:
  // their limit points coincide and merge. Where the result shows a problem,
  // create repairs the lattice nodes of the offending vertices and makes the mesh
  // again: snapping is undone where it changed something, then the node's values
  // are moved by a small pseudo-random amount (NodeValues::RepairLevel), drawn
  // anew each time the node offends again. Moved values hold no coincidences
  // (bar a chance of one in 16 or more per draw), so this ends: in practice after
  // a few rounds. Only the slabs holding a node repaired in the last round are
  // cut again. Every rank repairs the nodes all ranks found, so all make the
  // repairs one process makes.
  using Level = NodeValues::RepairLevel;
  std::vector<Level> repair; // by the window's numbering
  std::vector<SlabResult> slabs(static_cast<size_t>(num_slabs));
  std::vector<char> recut(slabs.size(), 0);
  std::fill(recut.begin() + cut[0], recut.begin() + cut[1] + 1, 1);
  CreateStats stats;
  double check_seconds = 0;
  bool wide_snapped = false;
  // Marks the cut slabs that hold a repaired node's tetrahedra, to cut again.
  auto recut_around = [&](int64_t node) {
    const auto [first, last] = lattice.slabs_of_node(node);
    for (int slab = std::max(first, cut[0]); slab <= std::min(last, cut[1]); ++slab) recut[size_t(slab)] = 1;
  };
  for (int round = 0;; ++round) {
    CreateStats round_stats;
    const bool every_slab_cut =
        std::all_of(recut.begin() + cut[0], recut.begin() + cut[1] + 1, [](char c) { return c != 0; });
    part = extract(lattice, values, grid, params.close ? int32_t(field.num_phases()) : -1, recut, slabs, owned, cut,
                   round_stats);
    resolve_coincident_triangles(part, round_stats);
    round_stats.snapped_nodes = whole ? values.snapped_nodes() : count_snapped(values, lattice, counted);
    round_stats.unsnapped_nodes = stats.unsnapped_nodes;
    round_stats.untied_nodes = stats.untied_nodes;
    round_stats.tiny_loop_nodes = stats.tiny_loop_nodes;
    round_stats.repair_rounds = round;
    stats = round_stats;
    if (round == kMaxRepairRounds) break;

    const auto check_start = std::chrono::steady_clock::now();
    // Not a structured binding: lambdas below capture `nodes`, which clang 14
    // refuses for bindings (the fuzz build).
    std::vector<int64_t> nodes;
    size_t problems = 0;
    std::tie(nodes, problems) = offending_nodes(part, grid.domain, whole, !every_slab_cut);
    check_seconds += detail::seconds_since(check_start);
    nodes = peers.merge_nodes(std::move(nodes));
    if (peers.sum(problems) == 0) {
      // Valid: closed triple curves far smaller than a cell are closed at
      // their lattice nodes, once (create/tiny_loops.hpp), and checked again.
      if (!wide_snapped)
        nodes = values.close_loops(peers.merge_closings(tiny_loop_closings(part, kTinyLoopCells * grid.h())));
      if (wide_snapped || nodes.empty()) {
        stats.validated = true;
        break;
      }
      wide_snapped = true;
      if (repair.empty()) repair.assign(size_t(window.size()), NodeValues::kSnap);
      values.hold(field, lattice, repair, nodes);
      std::fill(recut.begin(), recut.end(), 0);
      size_t widened = 0; // nodes[0..widened): those whose level changes, for values.redo()
      uint64_t counted_widened = 0;
      for (const int64_t node : nodes) {
        if (!window.contains(node)) continue;
        Level& level = repair[size_t(window.local(node))];
        if (level != NodeValues::kSnap) continue;
        level = NodeValues::kWideSnap;
        nodes[widened++] = node;
        counted_widened += is_counted(node);
        recut_around(node);
      }
      stats.tiny_loop_nodes = peers.sum(counted_widened);
      if (peers.sum(uint64_t(widened)) == 0) {
        stats.validated = true;
        break;
      }
      values.widen_snap(std::min(kTinyLoopSnap * params.snap, kMaxSnap) * grid.h());
      values.redo(field, lattice, repair, std::span<const int64_t>(nodes.data(), widened));
      continue;
    }
    if (repair.empty()) repair.assign(size_t(window.size()), NodeValues::kSnap);
    std::fill(recut.begin(), recut.end(), 0);
    uint64_t unsnapped = 0, untied = 0;
    // Repairs that stay at the offending nodes can move the problem to the next
    // node along (unsnapping one node of a snapped region leaves its neighbours'
    // ties): from the second round on, the neighbours are repaired with them.
    if (round >= 1) {
      const size_t offending = nodes.size();
      for (size_t i = 0; i < offending; ++i)
        lattice.for_each_neighbour(nodes[i], [&](int64_t n) { nodes.push_back(n); });
    }
    // Where the problems keep moving on instead (a snapped label field: each
    // repaired node leaves its snapped neighbours pinched), one repair of every
    // node ends it: no snapping left anywhere and every value moved, so no
    // coincidences but by chance, which the remaining rounds redraw.
    const bool everywhere = round + 1 == kLocalRepairRounds;
    if (everywhere) {
      nodes.resize(size_t(lattice.num_nodes()));
      std::iota(nodes.begin(), nodes.end(), int64_t(0));
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    // Values near interfaces only: a neighbour may not be held yet, and whether
    // snapping changed it decides its repair.
    if (!everywhere) values.hold(field, lattice, repair, nodes);
    size_t repaired = 0; // nodes[0..repaired): those whose level changes, for values.redo()
    for (const int64_t node : nodes) {
      if (!window.contains(node)) continue; // no slab cut here uses it
      Level& level = repair[size_t(window.local(node))];
      if (level == std::numeric_limits<Level>::max()) continue;
      nodes[repaired++] = node; // in place: never ahead of the node read
      if (!everywhere && level == NodeValues::kSnap && values.snapped(node)) {
        level = NodeValues::kUnsnap;
        unsnapped += is_counted(node);
      } else {
        level = level == NodeValues::kWideSnap ? NodeValues::kFirstUntie
                                               : std::max<Level>(level + 1, NodeValues::kFirstUntie);
        untied += is_counted(node);
      }
      recut_around(node);
    }
    unsnapped = peers.sum(unsnapped);
    untied = peers.sum(untied);
    if (unsnapped + untied == 0) break; // nothing left to repair: the caller's validation reports it
    values.redo(field, lattice, repair, std::span<const int64_t>(nodes.data(), repaired));
    stats.unsnapped_nodes += unsnapped;
    stats.untied_nodes += untied;
  }
  stats.seconds = detail::seconds_since(start);
  stats.check_seconds = check_seconds;
  return stats;
}

} // namespace detail

namespace {

/// Create in one process from `values`, made from `source` near interfaces only.
CreateStats create_whole(const detail::NodeSource& source, const detail::TetLattice& lattice,
                         detail::NodeValues& values, const CreateParams& params, NodeMesh& out) {
  detail::CreatePeers alone;
  SlabsMesh part;
  CreateStats stats = detail::create_slabs(source, values, params, {0, lattice.num_slabs() - 1}, alone, part);
  stats.held_nodes = uint64_t(values.held_nodes());
  out = NodeMesh{};
  out.domain = source.grid().domain;
  out.grid_spacing = source.grid().h();
  out.outside_phase = params.close ? int32_t(source.num_phases()) : -1;
  out.points = std::move(part.points);
  out.triangles = std::move(part.triangles);
  out.pairs = std::move(part.pairs);
  return stats;
}

} // namespace

CreateStats create_initial_mesh(const SampledField& field, const CreateParams& params, NodeMesh& out) {
  check_params(params);
  const auto start = std::chrono::steady_clock::now();
  const detail::TetLattice lattice(field.grid(), params.lattice);
  const double h = field.grid().h();
  const detail::NodeSource source(field);
  detail::NodeValues values(source, lattice, params.snap * h, kUntieFraction * h, params.close);
  const double quantizing = detail::seconds_since(start);
  CreateStats stats = create_whole(source, lattice, values, params, out);
  stats.seconds += quantizing;
  return stats;
}

CreateStats create_initial_mesh(const PhaseField& field, const GridSpec& grid, int k, const CreateParams& params,
                                NodeMesh& out, const std::function<void()>& sampled) {
  check_params(params);
  detail::check_phases_per_node(k);
  const auto start = std::chrono::steady_clock::now();
  const detail::TetLattice lattice(grid, params.lattice);
  const detail::NodeSource source(field, grid, k);
  detail::NodeValues values(source, lattice, params.snap * grid.h(), kUntieFraction * grid.h(), params.close);
  const double sampling = detail::seconds_since(start);
  if (sampled) sampled();
  CreateStats stats = create_whole(source, lattice, values, params, out);
  stats.sampling_seconds = sampling;
  return stats;
}

void name_phases(NodeMesh& mesh, const PhaseField& field) {
  mesh.phase_names.clear();
  mesh.phase_labels.clear();
  mesh.phase_colors.clear();
  for (int p = 0; p < field.num_phases(); ++p) {
    mesh.phase_names.push_back(field.phase_name(p));
    if (field.phase_label(p) != p) mesh.phase_labels.resize(size_t(field.num_phases()));
    if (const auto color = field.phase_color(p)) {
      mesh.phase_colors.resize(size_t(p) + 1);
      mesh.phase_colors[size_t(p)] = color;
    }
  }
  for (size_t p = 0; p < mesh.phase_labels.size(); ++p) mesh.phase_labels[p] = field.phase_label(int(p));
}

} // namespace vm
