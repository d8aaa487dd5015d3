#pragma once
/// @file mpi/layers.hpp
/// Grid data moves between ranks by whole layers (z = const): each rank holds
/// a block of layers and asks for the window of layers its slabs need.

#include "mpi/comm.hpp"
#include "voronoimesh/fields/sampled_field.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::mpi::detail {

using Layers = std::array<int32_t, 2>; ///< first and last layer

/// Every rank's block of layers, after checking that they cover layers
/// 0..last once, in rank order (InvalidInput otherwise, naming the rank).
std::vector<Layers> agree_on_blocks(Comm& comm, Layers mine, int32_t last);

/// Layers wants[rank] of an array of `per_layer` values per layer, of
/// which this rank holds layers blocks[rank] in `mine`: each layer comes from
/// the rank whose block holds it. `wants` are every rank's windows.
template <class T>
std::vector<T> exchange_layers(Comm& comm, const std::vector<Layers>& blocks, const std::vector<Layers>& wants,
                               std::span<const T> mine, size_t per_layer);

/// The samples of layers wants[rank], from the ranks' blocks (`mine` is this
/// rank's, holding blocks[rank]).
SampledField exchange_samples(Comm& comm, const std::vector<Layers>& blocks, const std::vector<Layers>& wants,
                              const SampledField& mine);

} // namespace vm::mpi::detail
