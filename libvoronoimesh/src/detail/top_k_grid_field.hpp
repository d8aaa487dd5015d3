#pragma once
/// @file detail/top_k_grid_field.hpp
/// A phase field stored on the nodes of a grid as the K largest phases per node
/// (the same top-K and floor rule as SampledField) and interpolated trilinearly
/// in between, so that label volumes and distance grids with thousands of
/// phases take memory O(nodes x K) and can be evaluated, with gradients, anywhere.

#include "voronoimesh/field.hpp"
#include "voronoimesh/types.hpp"

#include <string>
#include <vector>

namespace vm::detail {

class TopKGridField final : public PhaseField {
public:
  /// An empty store on `grid`'s nodes for `names.size()` phases, k slots per node
  /// (at most the number of phases). `labels` as PhaseField::phase_label (empty = identity).
  TopKGridField(const GridSpec& grid, int k, std::vector<std::string> names, std::vector<int32_t> labels);

  const GridSpec& grid() const { return grid_; }

  /// Offers phase `id` with `value` at node n: kept if among the k largest
  /// offered there. Nodes are independent, so different nodes may be offered
  /// to from different threads at once.
  void offer(int64_t n, int32_t id, float value);
  /// Ends the offers: slots a node did not fill take the lowest ids not kept
  /// there at value `far` (the value of every phase not offered), and each
  /// node gets its floor. Returns the first node that was offered nothing, or -1.
  int64_t finish(float far);

  int num_phases() const override { return int(names_.size()); }
  std::string phase_name(int i) const override { return names_.at(size_t(i)); }
  int32_t phase_label(int i) const override { return labels_.empty() ? i : labels_[size_t(i)]; }
  void values(const Vec3& x, std::span<double> out) const override;
  double value(int i, const Vec3& x) const override;
  Vec3 gradient(int i, const Vec3& x) const override;
  void top_values(const Vec3& x, std::span<int32_t> ids, std::span<double> vals) const override;

private:
  /// The 8 corner nodes of the cell holding x (clamped into the domain), their
  /// trilinear weights and the weights' derivatives along each axis.
  struct Cell {
    int64_t node[8];
    double w[8];
    Vec3 dw[8];
  };
  Cell cell(const Vec3& x) const;
  float node_value(int64_t n, int32_t phase) const;
  double floor_at(const Cell& c) const;

  GridSpec grid_;
  int k_;
  std::vector<std::string> names_;
  std::vector<int32_t> labels_;
  std::vector<int32_t> ids_;
  std::vector<float> values_;
  std::vector<float> floor_;
  std::vector<uint8_t> filled_; ///< slots offered per node, until finish()
};

} // namespace vm::detail
