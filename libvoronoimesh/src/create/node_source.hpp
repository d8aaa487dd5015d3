#pragma once
/// @file create/node_source.hpp
/// Where create reads the samples of a lattice node: the samples a SampledField
/// holds, or the phase field itself, evaluated at the node when create needs it
/// (NodeValues near interfaces only, which then never holds every node's samples).

#include "create/lattice.hpp"
#include "fields/node_sampling.hpp"
#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/fields/sampled_field.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

namespace vm::detail {

class NodeSource {
public:
  /// Room for one node's samples when they are evaluated (k <= 16).
  struct Buffer {
    std::array<int32_t, 16> ids;
    std::array<double, 16> values;
  };

  /// The samples `samples` holds (which must outlive this).
  NodeSource(const SampledField& samples) // NOLINT(google-explicit-constructor): a SampledField is a source
      : samples_(&samples), grid_(samples.grid()), k_(samples.k()), num_phases_(samples.num_phases()),
        layers_(samples.layers()) {}
  /// `field` evaluated at the nodes of `grid`, keeping min(k, N) phases per node
  /// as SampledField::sample() does (`field` must outlive this).
  NodeSource(const PhaseField& field, const GridSpec& grid, int k)
      : field_(&field), grid_(grid), k_(std::min(k, field.num_phases())), num_phases_(field.num_phases()),
        layers_{0, grid.cells[2]} {}

  const GridSpec& grid() const { return grid_; }
  int k() const { return k_; }                           ///< phases per node
  int num_phases() const { return num_phases_; }         ///< N, all phases of the field
  std::array<int32_t, 2> layers() const { return layers_; } ///< the grid layers it has samples of
  /// The field it evaluates, or nullptr when it holds samples.
  const PhaseField* field() const { return field_; }

  /// The samples at grid point p into `out`: where they are held, or evaluated
  /// into `buffer`. False when an evaluated value is NaN or infinite.
  bool try_at(const GridPoint& p, Buffer& buffer, SampledField::NodeSamples& out) const {
    if (samples_) {
      out = samples_->at(p[0], p[1], p[2]);
      return true;
    }
    out.ids = std::span<const int32_t>(buffer.ids.data(), size_t(k_));
    out.values = std::span<const double>(buffer.values.data(), size_t(k_));
    return sample_node(*field_, grid_, p[0], p[1], p[2], std::span<int32_t>(buffer.ids.data(), size_t(k_)),
                       std::span<double>(buffer.values.data(), size_t(k_)), out.floor);
  }
  /// True when every grid point of the row from p to q (along x, y and z as
  /// p's) has p's samples: where the field says so (PhaseField::same_top_values()).
  bool same_along_row(const GridPoint& p, const GridPoint& q) const {
    return field_ &&
           field_->same_top_values(grid_.node_position(p[0], p[1], p[2]), grid_.node_position(q[0], q[1], q[2]));
  }
  /// As try_at(), throwing throw_not_finite()'s error for a value that is NaN or infinite.
  SampledField::NodeSamples at(const GridPoint& p, Buffer& buffer) const {
    SampledField::NodeSamples out;
    if (!try_at(p, buffer, out)) throw_not_finite(*field_, grid_, grid_.node_index(p[0], p[1], p[2]));
    return out;
  }

private:
  const SampledField* samples_ = nullptr;
  const PhaseField* field_ = nullptr;
  GridSpec grid_;
  int k_ = 0, num_phases_ = 0;
  std::array<int32_t, 2> layers_{0, -1};
};

} // namespace vm::detail
