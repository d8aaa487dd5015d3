/// @file mpi/create_part.cpp
/// vm::mpi::create_part(): plan (blocks, value range, balanced slabs), move
/// the layers each rank needs, create each rank's part with the repair rounds
/// of one process (detail::create_slabs), then number the vertices as one
/// process does: in order of first appearance, slab after slab.

#include "voronoimesh/mpi/distributed.hpp"

#include "core/text.hpp"
#include "create/create_slabs.hpp"
#include "create/lattice.hpp"
#include "create/node_values.hpp"
#include "mpi/balance.hpp"
#include "mpi/comm.hpp"
#include "mpi/layers.hpp"
#include "mpi/memory.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/outside_phase.hpp"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <optional>

namespace vm::mpi {

namespace {

using detail::Comm;
using detail::Layers;
using vm::detail::SlabsMesh;
using SlabRange = std::array<int, 2>;

/// The repair rounds' view of the other ranks.
class MpiPeers : public vm::detail::CreatePeers {
public:
  explicit MpiPeers(Comm& comm) : comm_(comm) {}
  std::vector<int64_t> merge_nodes(std::vector<int64_t> nodes) override {
    std::vector<int64_t> all = comm_.all_gather(std::span<const int64_t>(nodes));
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
  }
  std::vector<vm::detail::LoopClosing> merge_closings(std::vector<vm::detail::LoopClosing> closings) override {
    std::vector<int64_t> flat;
    for (const auto& c : closings) flat.insert(flat.end(), {c.node, int64_t(c.phase)});
    const std::vector<int64_t> all = comm_.all_gather(std::span<const int64_t>(flat));
    closings.clear();
    for (size_t i = 0; i + 1 < all.size(); i += 2) closings.push_back({all[i], int32_t(all[i + 1])});
    std::sort(closings.begin(), closings.end());
    closings.erase(std::unique(closings.begin(), closings.end()), closings.end());
    return closings;
  }
  uint64_t sum(uint64_t value) override { return comm_.sum(value); }

private:
  Comm& comm_;
};

/// Who does what: the ranks' blocks, the range of values, the slabs each owns.
struct Plan {
  std::vector<Layers> blocks;
  std::array<double, 2> range{};
  std::vector<SlabRange> slabs;
  std::vector<uint64_t> interface_tets; ///< per rank
};

Plan plan(Comm& comm, const SampledField& block, Lattice kind) {
  const GridSpec& grid = block.grid();
  const vm::detail::TetLattice lattice(grid, kind);
  if (comm.size() > lattice.num_slabs())
    throw InvalidInput("mpi: " + std::to_string(comm.size()) + " ranks need at least as many slabs of the lattice, " +
                       "this grid has " + std::to_string(lattice.num_slabs()) + " (grid cells along z" +
                       (kind == Lattice::bcc ? " / 2)" : ")"));
  Plan p;
  p.blocks = detail::agree_on_blocks(comm, block.layers(), grid.cells[2]);
  // Quantizing needs the range of the whole field on every rank (node_values.hpp).
  const std::array<double, 2> range = vm::detail::lattice_value_range(block, lattice, block.layers());
  p.range = {comm.min(range[0]), comm.max(range[1])};

  // The work of the slabs starting in this block, from the winners at its nodes
  // and at the layers above that those slabs reach.
  const Layers mine = block.layers();
  const SlabRange counted = detail::slabs_starting_in(lattice, mine);
  std::vector<Layers> wants(size_t(comm.size()));
  for (size_t r = 0; r < wants.size(); ++r) {
    const SlabRange s = detail::slabs_starting_in(lattice, p.blocks[r]);
    wants[r] = {p.blocks[r][0],
                s[1] >= s[0] ? std::max(p.blocks[r][1], lattice.layers_of_slabs(s[1], s[1])[1]) : p.blocks[r][1]};
  }
  std::vector<int32_t> winners(block.all_floors().size());
  for (size_t n = 0; n < winners.size(); ++n) winners[n] = block.all_ids()[n * size_t(block.k())];
  const size_t layer_nodes = size_t(grid.nodes()[0] * grid.nodes()[1]);
  const std::vector<int32_t> labels =
      detail::exchange_layers(comm, p.blocks, wants, std::span<const int32_t>(winners), layer_nodes);
  const std::vector<detail::SlabWork> work =
      detail::slab_work(lattice, grid, labels, wants[size_t(comm.rank())], counted);
  const std::vector<detail::SlabWork> all = comm.all_gather(std::span<const detail::SlabWork>(work));
  p.slabs = detail::balance_slabs(all, comm.size());
  for (const SlabRange& s : p.slabs) {
    uint64_t tets = 0;
    for (int slab = s[0]; slab <= s[1]; ++slab) tets += all[size_t(slab)].interface_tets;
    p.interface_tets.push_back(tets);
  }
  return p;
}

/// The layers each rank's create needs: its slabs and one on each side.
std::vector<Layers> windows(const Plan& p, const GridSpec& grid, Lattice kind) {
  const vm::detail::TetLattice lattice(grid, kind);
  std::vector<Layers> w;
  for (const SlabRange& s : p.slabs)
    w.push_back(lattice.layers_of_slabs(std::max(0, s[0] - 1), std::min(lattice.num_slabs() - 1, s[1] + 1)));
  return w;
}

/// Bytes of a rank's part of the mesh per interface tetrahedron of its slabs:
/// create's vertices with their exact keys, triangles and indices, then the
/// MeshPart. One process's peak memory beyond its samples and node values was
/// 200-265 B per cut tetrahedron (the four spheres and voronoi30 at 64^3 to
/// 192^3, `/usr/bin/time -f %M voronoimesh create`); the part adds its copy.
constexpr double kMeshBytesPerInterfaceTet = 300;

std::string grid_text(const GridSpec& grid) {
  return vm::detail::cat("a ", grid.cells[0], "x", grid.cells[1], "x", grid.cells[2], " grid");
}

/// Bytes of the lattice node values of `window`'s grid, every node held
/// (NodeValues from samples): id and quantized value per phase kept (8 B),
/// floor and winner (8 B), snap flag (1 B).
double node_values_bytes(const GridSpec& window, int k, Lattice kind) {
  const double nodes = double(window.cells[0] + 1) * double(window.cells[1] + 1) * double(window.cells[2] + 1);
  return (kind == Lattice::bcc ? nodes / 4 : nodes) * (8.0 * k + 9);
}

/// Refuses, before the windows move, a rank whose peak will not fit in its
/// share of its node: its block and its window's samples (both held while
/// the layers move), the window's lattice node values and its part of the mesh.
void refuse_window_beyond_share(const detail::MemoryShare& share, const SampledField& block, Layers window,
                                SlabRange slabs, uint64_t interface_tets, Lattice kind) {
  GridSpec w = block.grid();
  w.cells[2] = window[1] - window[0];
  const double bytes = double(estimate_sample_memory(block.grid(), block.k(), block.layers())) +
                       double(estimate_sample_memory(block.grid(), block.k(), window)) +
                       node_values_bytes(w, block.k(), kind) + kMeshBytesPerInterfaceTet * double(interface_tets);
  detail::refuse_beyond_share(share, bytes,
                              vm::detail::cat("grid: slabs ", slabs[0], "..", slabs[1], " (layers ", window[0], "..",
                                              window[1], ") of ", grid_text(block.grid())));
}

/// Numbers the vertices of `part` as one process would and gives this rank's
/// share: its own vertices are numbered after those of every lower rank, in
/// order of first appearance; those the rank below made first get their ids
/// from it, matched through the slab both cut (the same limit points, in the
/// same order, on both).
MeshPart number(Comm& comm, const SlabsMesh& part, SlabRange owned) {
  using vm::detail::kBelowOwned;
  using vm::detail::kInOwned;
  MeshPart out;
  out.slabs = owned;
  std::vector<int32_t> local(part.points.size(), -1);
  uint64_t made_here = 0;
  for (size_t v = 0; v < part.points.size(); ++v)
    if ((part.where[v] & kInOwned) && !(part.where[v] & kBelowOwned)) ++made_here;
  const uint64_t first_id = comm.exclusive_sum(made_here);
  out.global_nodes = int64_t(comm.sum(made_here));
  uint64_t next = first_id;
  for (size_t v = 0; v < part.points.size(); ++v) {
    if (!(part.where[v] & kInOwned)) continue;
    local[v] = int32_t(out.points.size());
    out.points.push_back(part.points[v]);
    const bool below = part.where[v] & kBelowOwned;
    out.global_ids.push_back(below ? -1 : int64_t(next++));
    out.owners.push_back(comm.rank() - (below ? 1 : 0));
  }
  // Ids for the rank above: those of the limit points of its first slab that
  // are vertices here. A vertex lies in at most two neighbouring slabs, so each
  // was made here, not below.
  std::vector<std::vector<char>> send(size_t(comm.size()));
  if (comm.rank() + 1 < comm.size()) {
    std::vector<int64_t> ids;
    for (int32_t v : part.slab_above)
      if (part.where[size_t(v)] & kInOwned) {
        if (part.where[size_t(v)] & kBelowOwned)
          throw Error("mpi: internal error: a vertex lies in three slabs (please report this with the input)");
        ids.push_back(out.global_ids[size_t(local[size_t(v)])]);
      }
    send[size_t(comm.rank()) + 1].assign(reinterpret_cast<const char*>(ids.data()),
                                         reinterpret_cast<const char*>(ids.data() + ids.size()));
  }
  const std::vector<std::vector<char>> received = comm.all_to_all(send);
  if (comm.rank() > 0) {
    const std::vector<char>& bytes = received[size_t(comm.rank()) - 1];
    const int64_t* ids = reinterpret_cast<const int64_t*>(bytes.data());
    size_t at = 0, count = bytes.size() / sizeof(int64_t);
    for (int32_t v : part.first_owned_slab)
      if (part.where[size_t(v)] & kBelowOwned) {
        if (at == count) break;
        out.global_ids[size_t(local[size_t(v)])] = ids[at++];
      }
    if (at != count || std::find(out.global_ids.begin(), out.global_ids.end(), -1) != out.global_ids.end())
      throw Error("mpi: internal error: the vertices shared with rank " + std::to_string(comm.rank() - 1) +
                  " do not match (please report this with the input)");
  }
  for (size_t t = part.owned_begin; t < part.owned_end; ++t) {
    const auto& tri = part.triangles[t];
    out.triangles.push_back({local[size_t(tri[0])], local[size_t(tri[1])], local[size_t(tri[2])]});
    out.pairs.push_back(part.pairs[t]);
  }
  const auto first_triangle = int64_t(comm.exclusive_sum(out.triangles.size()));
  for (size_t t = 0; t < out.triangles.size(); ++t) out.triangle_ids.push_back(first_triangle + int64_t(t));
  out.global_triangles = int64_t(comm.sum(out.triangles.size()));
  return out;
}

/// Sums the counters of every rank's statistics; the slowest rank's times.
CreateStats sum_stats(Comm& comm, const CreateStats& mine) {
  CreateStats s = mine; // repair counts and rounds: already the same on every rank
  for (uint64_t CreateStats::*field :
       {&CreateStats::tets_visited, &CreateStats::tets_cut, &CreateStats::polygons, &CreateStats::collapsed_polygons,
        &CreateStats::dropped_triangles, &CreateStats::coincident_pairs, &CreateStats::degenerate_cuts,
        &CreateStats::box_triangles, &CreateStats::snapped_nodes, &CreateStats::held_nodes})
    s.*field = comm.sum(mine.*field);
  s.seconds = comm.max(mine.seconds);
  s.check_seconds = comm.max(mine.check_seconds);
  return s;
}

/// Everything after sampling, for a block of samples that `release` may free
/// once the layers have moved; `field` is what they are samples of (null: not
/// known), with which slow pairs snap less as in one process (NodeValues).
template <class Release>
MeshPart create_from_block(Comm& comm, const detail::MemoryShare& share, const SampledField& block,
                           const PhaseField* field, const CreateParams& params, bool validate,
                           DistributedStats* stats, Release&& release) {
  const Plan p = plan(comm, block, params.lattice);
  const GridSpec grid = block.grid();
  const std::vector<Layers> wanted = windows(p, grid, params.lattice);
  const SlabRange owned = p.slabs[size_t(comm.rank())];
  refuse_window_beyond_share(share, block, wanted[size_t(comm.rank())], owned, p.interface_tets[size_t(comm.rank())],
                             params.lattice);
  const SampledField window = detail::exchange_samples(comm, p.blocks, wanted, block);
  release();
  MpiPeers peers(comm);
  SlabsMesh part;
  // Every node of the window held: winners sure by the field's values need
  // the neighbours' winners, which the window's edges lack.
  const vm::detail::TetLattice lattice(grid, params.lattice);
  const Layers layers = wanted[size_t(comm.rank())];
  const vm::detail::NodeScope scope{lattice.window(layers[0], layers[1]), p.range[0], p.range[1], field};
  vm::detail::NodeValues values(window, lattice, params.snap * grid.h(), kUntieFraction * grid.h(), nullptr, &scope);
  CreateStats mine = vm::detail::create_slabs(window, values, params, owned, peers, part);
  mine.held_nodes = uint64_t(values.held_nodes());
  MeshPart out = number(comm, part, owned);
  out.domain = grid.domain;
  out.grid_spacing = grid.h();
  out.outside_phase = params.close ? int32_t(window.num_phases()) : -1;
  const CreateStats all = sum_stats(comm, mine);
  if (validate && !all.validated)
    throw TopologyError("the created mesh failed validation after " + std::to_string(all.repair_rounds) +
                        " repair rounds (please report this with the input)");
  if (stats) {
    stats->create = all;
    stats->interface_tets = p.interface_tets;
    stats->slabs = p.slabs;
  }
  return out;
}

void finish_stats(DistributedStats* stats, const Comm& comm, std::chrono::steady_clock::time_point start) {
  if (!stats) return;
  stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats->mpi_seconds = comm.mpi_seconds();
  stats->bytes_sent = comm.bytes_sent();
  stats->collectives = comm.collectives();
}

} // namespace

MeshPart create_part(MPI_Comm c, const SampledField& block, const CreateParams& params, DistributedStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  Comm comm(c);
  MeshPart part = comm.collectively([&] {
    const detail::MemoryShare share = detail::memory_share(comm);
    return create_from_block(comm, share, block, nullptr, params, true, stats, [] {});
  });
  finish_stats(stats, comm, start);
  return part;
}

MeshPart create_part(MPI_Comm c, const Scene& scene, const MeshOptions& o, DistributedStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  Comm comm(c);
  MeshPart part = comm.collectively([&] {
    std::optional<tbb::global_control> limit;
    if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
    const GridSpec grid = create_grid(scene, o);
    const CreateParams params = create_params(scene, o);
    // An equal share of the grid layers for each rank to sample.
    const int32_t layers = grid.cells[2] + 1, r = comm.rank(), n = comm.size();
    const Layers block{int32_t(int64_t(layers) * r / n), int32_t(int64_t(layers) * (r + 1) / n) - 1};
    if (block[1] < block[0])
      throw InvalidInput("mpi: " + std::to_string(n) + " ranks need at least as many grid layers, the grid has " +
                         std::to_string(layers));
    const detail::MemoryShare share = detail::memory_share(comm);
    detail::refuse_beyond_share(share, double(estimate_sample_memory(grid, o.top_k, block)),
                                vm::detail::cat("grid: layers ", block[0], "..", block[1], " of ", grid_text(grid)));
    std::optional<SampledField> samples = SampledField::sample(*scene.field, grid, o.top_k, block);
    MeshPart out = create_from_block(comm, share, *samples, scene.field.get(), params, o.validate, stats,
                                     [&] { samples.reset(); });
    NodeMesh names;
    names.domain = grid.domain;
    names.outside_phase = out.outside_phase;
    name_phases(names, *phases_of_mesh(names, scene.field));
    out.phase_names = std::move(names.phase_names);
    out.phase_labels = std::move(names.phase_labels);
    out.phase_colors = std::move(names.phase_colors);
    return out;
  });
  finish_stats(stats, comm, start);
  return part;
}

} // namespace vm::mpi
