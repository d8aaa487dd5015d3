#pragma once
/// @file fields/top_k_grid_field.hpp
/// A phase field stored on the nodes of a grid as the K largest phases per node
/// (the same top-K and floor rule as SampledField) and interpolated trilinearly
/// in between, so that label volumes and distance grids with thousands of
/// phases take memory O(nodes x K) and can be evaluated, with gradients, anywhere.
///
/// Nodes are stored in bricks of 4^3. A brick may be *uniform*: every node in it
/// holds one phase at value `top` and no other phase offered, as deep inside a
/// label's region, so a label volume stores values only in a band around its
/// label changes (a few bytes per voxel elsewhere: the brick table).

#include "voronoimesh/core/types.hpp"
#include "voronoimesh/fields/phase_field.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace vm::detail {

class TopKGridField final : public PhaseField {
public:
  static constexpr int64_t kBrick = 4; ///< nodes per brick along each axis

  /// An empty store on `grid`'s nodes for `names.size()` phases, k slots per node
  /// (at most the number of phases). `labels` as PhaseField::phase_label (empty = identity).
  /// `uniform` gives per brick (bricks(), x fastest) the phase of a uniform
  /// brick, or -1 for a brick whose nodes take offers; empty = every brick
  /// takes offers. A uniform brick's nodes hold their phase at `top` and every
  /// other phase as if none was offered (see finish()).
  TopKGridField(const GridSpec& grid, int k, std::vector<std::string> names, std::vector<int32_t> labels,
                std::vector<int32_t> uniform = {}, float top = 0.f);

  const GridSpec& grid() const { return grid_; }
  /// Bricks along each axis: ceil(nodes / kBrick).
  const std::array<int64_t, 3>& bricks() const { return bricks_; }

  /// Offers phase `id` with `value` at node n (or (i, j, k)) of a brick that is
  /// not uniform: kept if among the k largest offered there. Nodes are
  /// independent, so different nodes may be offered to from different threads at once.
  void offer(int64_t n, int32_t id, float value);
  void offer(int64_t i, int64_t j, int64_t k, int32_t id, float value);
  /// After every offer to node (i, j, k): raises phase `id` there, where it is
  /// not already ahead of every other phase by `margin`, to the largest other
  /// value plus `margin` (`far` counts as the value of the phases not offered
  /// when fewer than all were). The node's other values stay as offered.
  void lead(int64_t i, int64_t j, int64_t k, int32_t id, float margin, float far);
  /// Ends the offers: slots a node did not fill take the lowest ids not kept
  /// there at value `far` (the value of every phase not offered), and each
  /// node gets its floor. Returns the first node (linear index) that was
  /// offered nothing, or -1; nodes of uniform bricks count as offered.
  int64_t finish(float far);

  /// Bytes the store holds: per node of a dense brick k ids and values and a
  /// floor, a word per brick, and per phase the ids and values of its uniform
  /// bricks. Grows with the nodes near label changes and with k, barely with
  /// the number of phases.
  size_t bytes() const {
    return ids_.size() * sizeof(int16_t) + values_.size() * sizeof(float) + floor_.size() * sizeof(float) +
           brick_.size() * sizeof(int32_t) + uniform_ids_.size() * sizeof(int16_t) +
           uniform_values_.size() * sizeof(float);
  }

  int num_phases() const override { return int(names_.size()); }
  std::string phase_name(int i) const override { return names_.at(size_t(i)); }
  int32_t phase_label(int i) const override { return labels_.empty() ? i : labels_[size_t(i)]; }
  std::optional<Rgb> phase_color(int i) const override {
    return size_t(i) < colors_.size() ? colors_[size_t(i)] : std::nullopt;
  }
  /// Gives the phases display colours (by phase id; may be shorter than the phases).
  void set_phase_colors(std::vector<std::optional<Rgb>> colors) { colors_ = std::move(colors); }
  void values(const Vec3& x, std::span<double> out) const override;
  double value(int i, const Vec3& x) const override;
  Vec3 gradient(int i, const Vec3& x) const override;
  void top_values(const Vec3& x, std::span<int32_t> ids, std::span<double> vals) const override;
  /// True when every cell the box meets has all its corners in uniform bricks of one phase.
  bool same_top_values(const Vec3& lo, const Vec3& hi) const override;
  /// Makes grid nodes kept points (PhaseField::kept_points()), each in the
  /// phase that leads there: a voxel-faithful label volume's voxel centres.
  /// @param nodes the nodes' linear indices (GridSpec::node_index()), ascending
  void keep_nodes(std::vector<int64_t> nodes);
  void kept_points(const Vec3& lo, const Vec3& hi, std::vector<Vec3>& out) const override;
  bool keeps_points() const override { return !kept_.empty(); }

private:
  /// One node's kept phases: k ids and values, largest first, and the floor.
  struct Node {
    const int16_t* ids;
    const float* vals;
    float floor;
  };
  /// Where x falls in the grid: per axis the cell's lower node (clamped into the
  /// domain), the fraction of the way to the upper node and whether x is inside
  /// the domain along it (else the fraction's derivative is 0); per corner (x
  /// fastest) its brick's word. `uniform` is the phase when all 8 corners are in
  /// uniform bricks of that phase, else -1.
  struct Place {
    uint64_t lower[3];
    Vec3 f;
    bool inside[3];
    int32_t brick[8];
    int32_t uniform;
  };
  /// The 8 corner nodes of the cell holding x, their trilinear weights and the
  /// weights' derivatives along each axis.
  struct Cell {
    Node node[8];
    double w[8];
    Vec3 dw[8];
  };
  /// The cell at x. The passes ask for the value and gradient of each phase of
  /// a vertex one by one at the same point, so the last cell each thread
  /// computed is kept and returned again for the same field and point.
  const Cell& cell(const Vec3& x) const;
  void locate(const Vec3& x, Place& p) const;
  /// Coordinate x along axis a in grid steps.
  double grid_steps(int a, double x) const { return (x - grid_.domain.min[a]) / spacing_[a]; }
  /// Grid steps t along axis a clamped to the grid.
  double clamped(int a, double t) const { return std::clamp(t, 0.0, double(grid_.cells[a])); }
  /// The lower node along axis a of the cell holding grid coordinate t (the last cell holds the far face).
  uint64_t lower_node(int a, double t) const { return uint64_t(std::min<int64_t>(int64_t(t), grid_.cells[a] - 1)); }
  /// The cell at `p`; the weights' derivatives only with `gradients` (sampling needs none).
  void fill_cell(const Place& p, Cell& c, bool gradients) const;
  /// Slot of node (i, j, k) in the dense arrays; precondition: its brick is not uniform.
  size_t slot(int64_t i, int64_t j, int64_t k) const;
  /// The brick (x fastest) that holds node (i, j, k).
  int64_t brick_of(int64_t i, int64_t j, int64_t k) const {
    return i / kBrick + bricks_[0] * (j / kBrick + bricks_[1] * (k / kBrick));
  }
  float node_value(const Node& n, int32_t phase) const;
  double floor_at(const Cell& c) const;

  uint64_t serial_; ///< tells this field's cached cells from another's (cell())
  GridSpec grid_;
  Vec3 spacing_; ///< grid_.spacing(), its three divisions done once rather than per point
  int k_;
  std::vector<std::string> names_;
  std::vector<int32_t> labels_;
  std::vector<std::optional<Rgb>> colors_;
  std::array<int64_t, 3> bricks_{};
  /// Per brick: >= 0 its index among the dense bricks, < 0 a uniform brick of phase -1 - value.
  std::vector<int32_t> brick_;
  /// Per phase, the ids and values every node of a uniform brick of it holds.
  std::vector<int16_t> uniform_ids_;
  std::vector<float> uniform_values_;
  float uniform_floor_ = 0;
  float top_;
  std::vector<int64_t> kept_;          ///< keep_nodes(), ascending
  std::vector<uint8_t> brick_keeps_;   ///< per brick: it holds a kept node
  std::vector<int16_t> ids_; ///< dense bricks, kBrick^3 nodes each (x fastest), k per node
  std::vector<float> values_;
  std::vector<float> floor_;
  std::vector<uint8_t> filled_; ///< slots offered per dense node, until finish()
};

} // namespace vm::detail
