#include "mpi/layers.hpp"

#include "voronoimesh/errors.hpp"

#include <algorithm>
#include <cstring>
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

std::vector<char> exchange_layers(Comm& comm, const std::vector<Layers>& blocks, const std::vector<Layers>& wants,
                                  std::span<const char> mine, size_t bytes_per_layer) {
  const Layers have = blocks[size_t(comm.rank())];
  std::vector<std::vector<char>> send(size_t(comm.size()));
  for (size_t q = 0; q < send.size(); ++q) {
    const int32_t lo = std::max(have[0], wants[q][0]), hi = std::min(have[1], wants[q][1]);
    if (lo > hi) continue;
    const char* from = mine.data() + size_t(lo - have[0]) * bytes_per_layer;
    send[q].assign(from, from + size_t(hi - lo + 1) * bytes_per_layer);
  }
  const std::vector<std::vector<char>> received = comm.all_to_all(send);
  const Layers want = wants[size_t(comm.rank())];
  std::vector<char> window(size_t(want[1] - want[0] + 1) * bytes_per_layer);
  for (size_t q = 0; q < received.size(); ++q) {
    const int32_t lo = std::max(blocks[q][0], want[0]);
    if (!received[q].empty())
      std::memcpy(window.data() + size_t(lo - want[0]) * bytes_per_layer, received[q].data(), received[q].size());
  }
  return window;
}

namespace {

template <class T> std::vector<T> layers_of(Comm& comm, const std::vector<Layers>& blocks,
                                            const std::vector<Layers>& wants, std::span<const T> mine,
                                            size_t per_layer) {
  const std::vector<char> bytes =
      exchange_layers(comm, blocks, wants, {reinterpret_cast<const char*>(mine.data()), mine.size_bytes()},
                      per_layer * sizeof(T));
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

} // namespace

SampledField exchange_samples(Comm& comm, const std::vector<Layers>& blocks, const std::vector<Layers>& wants,
                              const SampledField& mine) {
  const GridSpec& grid = mine.grid();
  const size_t nodes = size_t(grid.nodes()[0] * grid.nodes()[1]), k = size_t(mine.k());
  std::vector<int32_t> ids = layers_of(comm, blocks, wants, mine.all_ids(), nodes * k);
  std::vector<double> values = layers_of(comm, blocks, wants, mine.all_values(), nodes * k);
  std::vector<double> floors = layers_of(comm, blocks, wants, mine.all_floors(), nodes);
  return SampledField::from_samples(grid, mine.num_phases(), mine.k(), wants[size_t(comm.rank())], std::move(ids),
                                    std::move(values), std::move(floors));
}

} // namespace vm::mpi::detail
