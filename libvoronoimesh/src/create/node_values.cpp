#include "create/node_values.hpp"

#include "core/atomic_lowest.hpp"
#include "core/huge_pages.hpp"
#include "core/parallel.hpp"

#include <tbb/blocked_range.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>

namespace vm::detail {

namespace {

/// The rate of growth of phi_p - phi_q (per unit length) below which a pair
/// snaps less than by value (NodeValues). At 0.25 (no snap moves an interface
/// more than 0.8 h) the four-ball scene balls_5 folded at 2 edges; at 0.15
/// seeds30_2 kept 6 nodes up to 0.54 h off (0.047 h at 0.2). Of the 22 scenes
/// of bench/junction_scenes.sh and the examples, 0.2 changes seeds30_2,
/// balls_5 and seeds17_2 only (docs/algorithm.md).
constexpr double kSlowRate = 0.2;

/// Nodes along a row asked at once whether the field fills them alone
/// (NodeSource::same_along_row()): long enough to spare most evaluations,
/// short enough that most runs away from interfaces are.
constexpr int32_t kSameRun = 8;

/// Nodes along a row whose neighbours are compared a run at a time when
/// deciding which nodes are held (held_near_interfaces()).
constexpr int32_t kQuietRun = 16;

/// splitmix64's finaliser: well-spread bits from a node and phase.
uint64_t mix_bits(uint64_t x) {
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// The largest float not above `x`.
float float_below(double x) {
  const float f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

} // namespace

std::vector<uint8_t> held_near_interfaces(const TetLattice& lattice, const std::vector<int32_t>& key, bool box) {
  const GridSpec& grid = lattice.grid();
  const bool bcc = lattice.kind() == Lattice::bcc;
  struct Offsets {
    std::vector<int64_t> same, other; // from the node; from its other-kind neighbour at (-1, -1, -1)
  };
  std::array<Offsets, 2> by_parity; // bcc: cube corners (even x), centres (odd x); cube6: one kind
  for (int32_t parity = 0; parity < 2; ++parity) {
    const int32_t c = 2 + parity;
    if (c + 2 > std::min({grid.cells[0], grid.cells[1], grid.cells[2]})) continue; // no inner node of this kind
    const int64_t id = lattice.node_id(c, c, c), base = bcc ? lattice.node_id(c - 1, c - 1, c - 1) : id;
    lattice.for_each_neighbour(id, [&](int64_t n) {
      if (bcc && (lattice.grid_point(n)[0] & 1) != parity)
        by_parity[size_t(parity)].other.push_back(n - base);
      else
        by_parity[size_t(parity)].same.push_back(n - id);
    });
  }
  // How many nodes after each in its row have its key (up to 255): a run of
  // inner nodes whose neighbours' runs all hold its key is decided with two
  // loads per neighbour offset instead of one per neighbour and node.
  std::vector<uint8_t> run_after;
  resize_on_huge_pages(run_after, key.size());
  detail::parallel_for(tbb::blocked_range<int64_t>(0, lattice.num_node_rows(), 16), [&](const auto& rows) {
    for (int64_t r = rows.begin(); r < rows.end(); ++r) {
      const TetLattice::NodeRow row = lattice.node_row(r);
      for (int64_t id = row.first_id + row.count - 2; id >= row.first_id; --id)
        if (key[size_t(id + 1)] == key[size_t(id)])
          run_after[size_t(id)] = uint8_t(std::min(255, run_after[size_t(id + 1)] + 1));
    }
  });
  std::vector<uint8_t> held;
  resize_on_huge_pages(held, key.size());
  detail::parallel_for(tbb::blocked_range<int64_t>(0, lattice.num_node_rows(), 16), [&](const auto& rows) {
    for (int64_t r = rows.begin(); r < rows.end(); ++r) {
      const TetLattice::NodeRow row = lattice.node_row(r);
      const bool inner_row = row.y >= 2 && row.z >= 2 && row.y + 2 <= grid.cells[1] && row.z + 2 <= grid.cells[2];
      const bool box_row = box && (row.y == 0 || row.z == 0 || row.y == grid.cells[1] || row.z == grid.cells[2]);
      const Offsets& around = by_parity[size_t(row.x0 & 1)];
      // Where the other-kind neighbours' offsets start from, for the node at grid x `gx` (bcc).
      auto other_base = [&](int64_t gx) { return lattice.node_id(gx - 1, row.y - 1, row.z - 1); };
      // Runs of inner nodes (neighbours at the fixed offsets, all in their rows)
      // whose own key v is sure and every neighbour's too: none is held.
      const int32_t inner_from = (2 - row.x0 + row.step - 1) / row.step;
      const int32_t inner_to = (grid.cells[0] - 2 - row.x0) / row.step + 1;
      auto all_have = [&](int64_t from, int32_t count, int32_t v) {
        return key[size_t(from)] == v && run_after[size_t(from)] + 1 >= count;
      };
      auto quiet_run = [&](int32_t x, int32_t count) {
        const int64_t id = row.first_id + x;
        const int32_t v = key[size_t(id)];
        if (v < 0 || !all_have(id, count, v)) return false;
        for (const int64_t o : around.same)
          if (!all_have(id + o, count, v)) return false;
        if (bcc) {
          const int64_t base = other_base(row.x0 + row.step * x);
          for (const int64_t o : around.other)
            if (!all_have(base + o, count, v)) return false;
        }
        return true;
      };
      for (int32_t x = 0; x < row.count; ++x) {
        if (inner_row && !around.same.empty() && x >= inner_from && (x - inner_from) % kQuietRun == 0) {
          const int32_t count = std::min(kQuietRun, inner_to - x);
          if (count > 0 && quiet_run(x, count)) {
            x += count - 1; // held stays 0
            continue;
          }
        }
        const int64_t id = row.first_id + x;
        const int32_t gx = row.x0 + row.step * x, own = key[size_t(id)];
        bool h = own < 0 || box_row || (box && (gx == 0 || gx == grid.cells[0]));
        const bool inner = inner_row && gx >= 2 && gx + 2 <= grid.cells[0] && !around.same.empty();
        if (!h && inner) {
          for (const int64_t o : around.same) h |= key[size_t(id + o)] != own;
          if (bcc) {
            const int64_t base = other_base(gx);
            for (const int64_t o : around.other) h |= key[size_t(base + o)] != own;
          }
        } else if (!h) {
          lattice.for_each_neighbour(id, [&](int64_t n) { h |= key[size_t(n)] != own; });
        }
        held[size_t(id)] = h;
      }
    }
  });
  return held;
}

std::array<double, 2> lattice_value_range(const SampledField& field, const TetLattice& lattice,
                                          std::array<int32_t, 2> layers) {
  using Range = std::array<double, 2>;
  const Range none{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  return detail::parallel_reduce(
      tbb::blocked_range<int64_t>(0, lattice.num_node_rows(), 16), none,
      [&](const tbb::blocked_range<int64_t>& rows, Range range) {
        for (int64_t r = rows.begin(); r < rows.end(); ++r) {
          const TetLattice::NodeRow row = lattice.node_row(r);
          if (row.z < layers[0] || row.z > layers[1]) continue;
          for (int32_t x = 0; x < row.count; ++x) {
            const SampledField::NodeSamples at = field.at(row.x0 + int64_t(row.step) * x, row.y, row.z);
            // The floor is below every stored value of its node, and slot 0 is the node's largest.
            range = {std::min(range[0], at.floor), std::max(range[1], at.values[0])};
          }
        }
        return range;
      },
      [](const Range& a, const Range& b) { return Range{std::min(a[0], b[0]), std::max(a[1], b[1])}; });
}

NodeValues::NodeValues(const SampledField& field, const TetLattice& lattice, double snap_eps, double untie_eps,
                       const std::vector<RepairLevel>* repair, const NodeScope* scope)
    : window_(scope ? scope->window : lattice.window(0, field.grid().cells[2])), k_(field.k()),
      field_(scope ? scope->field : nullptr), lattice_(&lattice) {
  const size_t n_nodes = size_t(window_.size()), kk = size_t(k_);
  label_.resize(n_nodes);
  ids_.resize(n_nodes * kk);
  values_.resize(n_nodes * kk);
  floor_.resize(n_nodes);
  snapped_.resize(n_nodes);
  // One global affine map to integers, so equal values stay equal everywhere
  // and every node's numbers mean the same thing in every tetrahedron.
  const std::array<double, 2> whole =
      scope ? std::array{scope->min_value, scope->max_value}
            : lattice_value_range(field, lattice, {0, field.grid().cells[2]});
  set_scale(whole[0], whole[1], snap_eps, untie_eps);

  snapped_nodes_ = detail::parallel_reduce(
      tbb::blocked_range<int64_t>(0, lattice.num_node_rows(), 16), uint64_t(0),
      [&](const tbb::blocked_range<int64_t>& rows, uint64_t snapped) {
        for (int64_t r = rows.begin(); r < rows.end(); ++r) {
          const TetLattice::NodeRow row = lattice.node_row(r);
          if (row.z < window_.z0 || row.z > window_.z1) continue;
          for (int32_t x = 0; x < row.count; ++x) {
            const int64_t id = row.first_id + x, n = window_.local(id);
            snapped += fill(field.at(row.x0 + int64_t(row.step) * x, row.y, row.z), id, n,
                            repair ? (*repair)[size_t(n)] : kSnap);
          }
        }
        return snapped;
      },
      std::plus<>());
}

NodeValues::NodeValues(const NodeSource& source, const TetLattice& lattice, double snap_eps, double untie_eps,
                       bool hold_box_nodes)
    : window_(lattice.window(0, source.grid().cells[2])), k_(source.k()), field_(source.field()),
      lattice_(&lattice) {
  const GridSpec& grid = source.grid();
  const size_t n_nodes = size_t(window_.size()); // the whole lattice: window index = lattice id
  resize_on_huge_pages(label_, n_nodes);
  // Every node's winner before quantizing, its lead over the second phase
  // (a float rounded down: a lead it shows is there) and the range.
  std::vector<float> lead;
  resize_on_huge_pages(lead, n_nodes);
  // The lowest grid node index with a value that is NaN or infinite: the error is the same for any schedule.
  std::atomic<int64_t> first_bad{std::numeric_limits<int64_t>::max()};
  using Range = std::array<double, 2>;
  const Range none{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const Range whole = detail::parallel_reduce(
      tbb::blocked_range<int64_t>(0, lattice.num_node_rows(), 16), none,
      [&](const tbb::blocked_range<int64_t>& rows, Range range) {
        NodeSource::Buffer buffer;
        SampledField::NodeSamples at;
        for (int64_t r = rows.begin(); r < rows.end(); ++r) {
          const TetLattice::NodeRow row = lattice.node_row(r);
          auto point = [&](int32_t x) { return GridPoint{row.x0 + row.step * x, row.y, row.z}; };
          for (int32_t run = 0; run < row.count; run += kSameRun) {
            const int32_t end = std::min(row.count, run + kSameRun);
            // A run the field fills alone has its first node's samples (the
            // same NaN too, reported from there): sampled once.
            const bool same = source.same_along_row(point(run), point(end - 1));
            for (int32_t x = run; x < end; ++x) {
              const size_t id = size_t(row.first_id + x);
              if (same && x > run) {
                label_[id] = label_[id - 1], lead[id] = lead[id - 1];
                continue;
              }
              if (!source.try_at(point(x), buffer, at)) {
                const GridPoint p = point(x);
                lower_atomically(first_bad, grid.node_index(p[0], p[1], p[2]));
                if (same) break;
                continue;
              }
              label_[id] = at.ids[0];
              lead[id] = k_ > 1 ? float_below(at.values[0] - at.values[1]) : std::numeric_limits<float>::infinity();
              // The floor is below every stored value of its node, and slot 0 is the node's largest.
              range = {std::min(range[0], at.floor), std::max(range[1], at.values[0])};
            }
          }
        }
        return range;
      },
      [](const Range& a, const Range& b) { return Range{std::min(a[0], b[0]), std::max(a[1], b[1])}; });
  if (const int64_t bad = first_bad.load(); bad != std::numeric_limits<int64_t>::max())
    throw_not_finite(*source.field(), grid, bad);
  set_scale(whole[0], whole[1], snap_eps, untie_eps);

  // Held: a node whose winner is not sure, or next to one, or next to a node
  // with another winner (a corner of a tetrahedron a cut may read). The key of
  // a node is its winner if sure, -1 if not: held nodes are those whose key or
  // a neighbour's differs from their winner.
  const double margin = hold_margin();
  resize_on_huge_pages(slot_, n_nodes);
  std::vector<int32_t>& key = slot_;
  for (size_t id = 0; id < n_nodes; ++id) key[id] = double(lead[id]) > margin ? label_[id] : -1;
  std::vector<float>().swap(lead);
  const std::vector<uint8_t> held_nodes = held_near_interfaces(lattice, key, hold_box_nodes);
  int32_t held = 0;
  for (size_t id = 0; id < n_nodes; ++id) slot_[id] = held_nodes[id] ? held++ : -1;
  const size_t kk = size_t(k_);
  ids_.resize(size_t(held) * kk);
  values_.resize(size_t(held) * kk);
  floor_.resize(size_t(held));
  snapped_.resize(size_t(held));

  snapped_nodes_ = detail::parallel_reduce(
      tbb::blocked_range<int64_t>(0, lattice.num_node_rows(), 16), uint64_t(0),
      [&](const tbb::blocked_range<int64_t>& rows, uint64_t snapped) {
        NodeSource::Buffer buffer;
        for (int64_t r = rows.begin(); r < rows.end(); ++r) {
          const TetLattice::NodeRow row = lattice.node_row(r);
          for (int32_t x = 0; x < row.count; ++x) {
            const int64_t id = row.first_id + x;
            if (slot_[size_t(id)] >= 0)
              snapped += fill(source.at({row.x0 + row.step * x, row.y, row.z}, buffer), id, id, kSnap);
          }
        }
        return snapped;
      },
      std::plus<>());
}

void NodeValues::set_scale(double lo, double hi, double snap_eps, double untie_eps) {
  lo_ = lo;
  const double range = hi - lo_;
  scale_ = range > 0 ? std::ldexp(1.0, kValueBits) / range : 1.0;
  eps_ = std::llround(snap_eps * scale_);
  // Small against the grid yet far above round-off, so that the caps it opens
  // around a node are triangles validate() takes for non-degenerate.
  untie_ = std::clamp<int64_t>(std::llround(untie_eps * scale_), 1024, int64_t(1) << 19);
}

double NodeValues::hold_margin() const {
  // Snapping moves a phase onto another closer than eps_; a repair level lowers
  // the winner by at most k_ untie_ (its ties and its draw) and raises another
  // phase by at most untie_; quantizing rounds each value by half a quantum.
  return double(std::max(eps_, untie_ * (k_ + 1)) + 2) / scale_;
}

std::vector<int64_t> NodeValues::close_loops(std::vector<LoopClosing> closings) {
  closings_ = std::move(closings);
  std::vector<int64_t> nodes;
  for (const LoopClosing& c : closings_)
    if (nodes.empty() || nodes.back() != c.node) nodes.push_back(c.node);
  return nodes;
}

void NodeValues::add_slots(std::span<const int64_t> nodes) {
  const size_t kk = size_t(k_), first = floor_.size();
  for (size_t i = 0; i < nodes.size(); ++i) slot_[size_t(nodes[i])] = int32_t(first + i);
  const size_t held = first + nodes.size();
  ids_.resize(held * kk);
  values_.resize(held * kk);
  floor_.resize(held);
  snapped_.resize(held);
}

uint64_t NodeValues::hold_nodes(const NodeSource& source, const TetLattice& lattice,
                                const std::vector<RepairLevel>& repair, std::vector<int64_t> nodes) {
  if (slot_.empty()) return 0; // every node is held
  uint64_t snapped = 0;
  while (!nodes.empty()) {
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    std::erase_if(nodes, [&](int64_t id) { return slot_[size_t(id)] >= 0; }); // whole lattice: id = window index
    add_slots(nodes);
    const std::vector<int32_t> before = labels_of(nodes);
    snapped += detail::parallel_reduce(
        tbb::blocked_range<size_t>(0, nodes.size(), 256), uint64_t(0),
        [&](const tbb::blocked_range<size_t>& r, uint64_t sum) {
          NodeSource::Buffer buffer;
          for (size_t i = r.begin(); i < r.end(); ++i) {
            const int64_t id = nodes[i];
            sum += fill(source.at(lattice.grid_point(id), buffer), id, id, repair.empty() ? kSnap : repair[size_t(id)]);
          }
          return sum;
        },
        std::plus<>());
    // A node not held had a sure winner, so this finds none: it keeps the rule
    // true should rounding ever disagree.
    nodes = around_new_winners(lattice, nodes, before);
  }
  return snapped;
}

void NodeValues::redo(const NodeSource& source, const TetLattice& lattice, const std::vector<RepairLevel>& repair,
                      std::span<const int64_t> nodes) {
  const std::vector<int32_t> before = slot_.empty() ? std::vector<int32_t>() : labels_of(nodes);
  // Snapped nodes gained minus those lost: each node is counted once before and once after.
  const int64_t gained = detail::parallel_reduce(
      tbb::blocked_range<size_t>(0, nodes.size(), 256), int64_t(0),
      [&](const tbb::blocked_range<size_t>& r, int64_t sum) {
        NodeSource::Buffer buffer;
        for (size_t i = r.begin(); i < r.end(); ++i) {
          const int64_t id = nodes[i], n = window_.local(id), s = held_slot(n);
          if (s < 0) continue; // its winner is sure at every level: filled at its level once held
          sum -= snapped_[size_t(s)];
          sum += fill(source.at(lattice.grid_point(id), buffer), id, n, repair[size_t(n)]);
        }
        return sum;
      },
      std::plus<>());
  snapped_nodes_ = uint64_t(int64_t(snapped_nodes_) + gained);
  if (!slot_.empty()) snapped_nodes_ += hold_nodes(source, lattice, repair, around_new_winners(lattice, nodes, before));
}

std::vector<int32_t> NodeValues::labels_of(std::span<const int64_t> nodes) const {
  std::vector<int32_t> labels(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) labels[i] = label(nodes[i]);
  return labels;
}

std::vector<int64_t> NodeValues::around_new_winners(const TetLattice& lattice, std::span<const int64_t> nodes,
                                                    const std::vector<int32_t>& before) const {
  std::vector<int64_t> around;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (label(nodes[i]) != before[i]) lattice.for_each_neighbour(nodes[i], [&](int64_t n) { around.push_back(n); });
  return around;
}

void NodeValues::hold(const NodeSource& source, const TetLattice& lattice, const std::vector<RepairLevel>& repair,
                      std::span<const int64_t> nodes) {
  snapped_nodes_ += hold_nodes(source, lattice, repair, std::vector<int64_t>(nodes.begin(), nodes.end()));
}

bool NodeValues::fill(const SampledField::NodeSamples& at, int64_t id, int64_t local, RepairLevel level) {
  const size_t n = size_t(held_slot(local));
  auto quantize = [&](double v) { return int32_t((v - lo_) * scale_ + 0.5); }; // v >= lo_: rounds to nearest
  const auto ids = at.ids;
  const auto vals = at.values;
  std::copy(ids.begin(), ids.end(), ids_.data() + n * size_t(k_));
  int32_t* q = values_.data() + n * size_t(k_);
  for (int s = 0; s < k_; ++s) q[s] = quantize(vals[s]);
  floor_[n] = quantize(at.floor);
  // Pairwise snapping in phase-id order (Algorithm 2, line 1): a later
  // phase takes the earlier phase's value, so earlier snaps are not undone.
  int32_t by_id[16];
  for (int s = 0; s < k_; ++s) { // slots by increasing phase id (k_ <= 16)
    int e = s;
    for (; e > 0 && ids[by_id[e - 1]] > ids[s]; --e) by_id[e] = by_id[e - 1];
    by_id[e] = s;
  }
  if (level >= kFirstUntie && level != kWideSnap) {
    // A phase with r lower ids tied with it drops by r untie, so the
    // symbolic order of tied phases survives, plus the pseudo-random
    // part below untie that every phase drops by. Stored phases stay
    // above the floor (unstored phases stay below it): one that would
    // reach it rises by its random part instead.
    int32_t tied_below[16] = {};
    for (int a = 0; a < k_; ++a)
      for (int b = a + 1; b < k_; ++b) tied_below[b] += q[by_id[a]] == q[by_id[b]];
    for (int b = 0; b < k_; ++b) {
      const uint64_t draw = mix_bits(uint64_t(id) * 0x9E3779B97F4A7C15ull ^ uint64_t(ids[by_id[b]]) ^
                                     uint64_t(level) << 56);
      const int64_t jitter = 1 + int64_t(draw % uint64_t(untie_));
      const int64_t lowered = int64_t(q[by_id[b]]) - untie_ * tied_below[b] - jitter;
      const int64_t raised = std::min(int64_t(q[by_id[b]]) + jitter, int64_t(1) << kValueBits);
      q[by_id[b]] = int32_t(lowered > floor_[n] ? lowered : raised);
    }
  }
  bool changed = false;
  // A pair slower than kSlowRate snaps within eps_ x rate / kSlowRate (the
  // class comment); each phase's gradient is found once, when first asked.
  std::optional<Vec3> position; // the node's, found once, when first asked
  auto node_at = [&]() -> const Vec3& {
    if (!position) {
      const GridPoint g = lattice_->grid_point(id);
      position = lattice_->grid().node_position(g[0], g[1], g[2]);
    }
    return *position;
  };
  std::array<Vec3, 16> grad;
  uint32_t known = 0;
  // The closings of tiny loops at this node (create/tiny_loops.hpp).
  const auto closing = level == kWideSnap ? std::equal_range(closings_.begin(), closings_.end(), LoopClosing{id, 0},
                                                             [](const LoopClosing& x, const LoopClosing& y) {
                                                               return x.node < y.node;
                                                             })
                                          : std::pair{closings_.end(), closings_.end()};
  const bool tie_all = std::any_of(closing.first, closing.second,
                                   [](const LoopClosing& c) { return c.phase == LoopClosing::kTieAll; });
  const int64_t eps = tie_all ? wide_eps_ : eps_;
  auto threshold = [&](int s, int t, int64_t within) {
    if (!field_) return within;
    for (const int u : {s, t})
      if (!(known >> u & 1u)) grad[size_t(u)] = field_->gradient(ids[size_t(u)], node_at()), known |= 1u << u;
    const double rate = (grad[size_t(s)] - grad[size_t(t)]).norm();
    return rate < kSlowRate ? int64_t(double(within) * rate / kSlowRate) : within; // NaN: by value
  };
  // A kept point of the field (a voxel-faithful volume's centre of a voxel in
  // a structure one voxel thin) at this node must stay in its label: nothing
  // snaps there. On flat voxels (CGAL's liver: 0.62 x 0.62 x 1.33) 0.2 h, h
  // the largest spacing, is more than the label's lead at its centre (0.3 of
  // the smallest), and snapping tied a one-voxel sheet's every centre. Asked
  // only of a node where some pair would snap.
  int kept = -1;
  auto is_kept = [&] {
    if (kept < 0) {
      kept = 0;
      if (field_ && field_->keeps_points()) {
        const Vec3 within = 1e-6 * lattice_->grid().spacing();
        thread_local std::vector<Vec3> points;
        points.clear();
        field_->kept_points(node_at() - within, node_at() + within, points);
        kept = !points.empty();
      }
    }
    return kept == 1;
  };
  if (eps > 0 && (level == kSnap || level == kWideSnap))
    for (int a = 0; a < k_; ++a)
      for (int b = a + 1; b < k_; ++b) {
        const int32_t vi = q[by_id[a]];
        int32_t& vj = q[by_id[b]];
        const int64_t gap = std::llabs(int64_t(vi) - vj);
        if (vi != vj && gap < eps && gap < threshold(by_id[a], by_id[b], eps) && !is_kept()) {
          vj = vi;
          changed = true;
        }
      }
  auto leader = [&] {
    int best = 0;
    for (int s = 1; s < k_; ++s)
      if (beats(q[s], ids[s], q[best], ids[best])) best = s;
    return best;
  };
  int best = leader();
  // A tiny loop's phase off its window rises to a tie with the leader, which
  // it then beats or not by phase id alone (create/tiny_loops.hpp).
  for (auto c = closing.first; c != closing.second; ++c) {
    if (c->phase == LoopClosing::kTieAll) continue; // tied by the snap above
    for (int s = 0; s < k_; ++s) {
      const int64_t gap = int64_t(q[best]) - q[s];
      if (ids[s] == c->phase && gap > 0 && gap < threshold(s, best, wide_eps_) && !is_kept()) {
        q[s] = q[best];
        changed = true;
      }
    }
  }
  if (closing.first != closing.second) best = leader();
  snapped_[n] = changed;
  label_[size_t(local)] = ids[best];
  return changed;
}

} // namespace vm::detail
