#include "mpi/layers.hpp"

#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <string>

namespace vm::mpi::detail {

std::vector<Layers> agree_on_blocks(Comm& comm, Layers mine, int32_t last) {
  const std::vector<Layers> blocks = comm.all_gather(std::span<const Layers>(&mine, 1));
  int32_t next = 0;
  for (size_t r = 0; r < blocks.size(); ++r) {
    if (blocks[r][0] != next || blocks[r][1] < blocks[r][0] || blocks[r][1] > last)
      throw InvalidInput("mpi: the ranks' blocks must cover grid layers 0.." + std::to_string(last) +
                         " once, in rank order; rank " + std::to_string(r) + " holds layers " +
                         std::to_string(blocks[r][0]) + ".." + std::to_string(blocks[r][1]) + ", expected from " +
                         std::to_string(next));
    next = blocks[r][1] + 1;
  }
  if (next != last + 1)
    throw InvalidInput("mpi: the ranks' blocks end at grid layer " + std::to_string(next - 1) + ", the grid at " +
                       std::to_string(last));
  return blocks;
}

template <class T>
std::vector<T> exchange_layers(Comm& comm, const std::vector<Layers>& blocks, const std::vector<Layers>& wants,
                               std::span<const T> mine, size_t per_layer) {
  // In whole layers, straight from `mine` into the window: each layer of the
  // window comes from the one rank whose block holds it.
  const size_t ranks = blocks.size();
  const Layers have = blocks[size_t(comm.rank())], want = wants[size_t(comm.rank())];
  std::vector<int> send_count(ranks, 0), send_at(ranks, 0), recv_count(ranks, 0), recv_at(ranks, 0);
  for (size_t q = 0; q < ranks; ++q) {
    const int32_t lo = std::max(have[0], wants[q][0]), hi = std::min(have[1], wants[q][1]);
    if (lo <= hi) send_count[q] = hi - lo + 1, send_at[q] = lo - have[0];
    const int32_t from = std::max(blocks[q][0], want[0]), to = std::min(blocks[q][1], want[1]);
    if (from <= to) recv_count[q] = to - from + 1, recv_at[q] = from - want[0];
  }
  std::vector<T> window(size_t(want[1] - want[0] + 1) * per_layer);
  comm.all_to_all_in_place(reinterpret_cast<const char*>(mine.data()), send_count, send_at,
                           reinterpret_cast<char*>(window.data()), recv_count, recv_at, per_layer * sizeof(T));
  return window;
}

template std::vector<int32_t> exchange_layers(Comm&, const std::vector<Layers>&, const std::vector<Layers>&,
                                              std::span<const int32_t>, size_t);

SampledField exchange_samples(Comm& comm, const std::vector<Layers>& blocks, const std::vector<Layers>& wants,
                              const SampledField& mine) {
  const GridSpec& grid = mine.grid();
  const size_t nodes = size_t(grid.nodes()[0] * grid.nodes()[1]), k = size_t(mine.k());
  std::vector<int32_t> ids = exchange_layers(comm, blocks, wants, mine.all_ids(), nodes * k);
  std::vector<double> values = exchange_layers(comm, blocks, wants, mine.all_values(), nodes * k);
  std::vector<double> floors = exchange_layers(comm, blocks, wants, mine.all_floors(), nodes);
  return SampledField::from_samples(grid, mine.num_phases(), mine.k(), wants[size_t(comm.rank())], std::move(ids),
                                    std::move(values), std::move(floors));
}

} // namespace vm::mpi::detail
