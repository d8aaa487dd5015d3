#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/scene.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

using namespace vm;

namespace {

const std::string examples = VM_EXAMPLES_DIR;

/// phi_i(x) = a_i . x + b_i: orderings change across the box, and the values
/// of phases 4 and 5 are equal everywhere (a tie that must go to the lower id).
class LinearField final : public PhaseField {
public:
  int num_phases() const override { return 6; }
  std::string phase_name(int i) const override { return "lin" + std::to_string(i); }
  void values(const Vec3& x, std::span<double> out) const override {
    for (int i = 0; i < 6; ++i) out[size_t(i)] = value(i, x);
  }
  double value(int i, const Vec3& x) const override { return a_[size_t(i)].dot(x) + b_[size_t(i)]; }
  Vec3 gradient(int i, const Vec3&) const override { return a_[size_t(i)]; }

private:
  std::vector<Vec3> a_{Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0.5), Vec3(0, -2, 0), Vec3(0.3, 0.3, -1),
                       Vec3(0.3, 0.3, -1)};
  std::vector<double> b_{0, 1, -0.2, 0.9, 0.4, 0.4};
};

/// A bump of phase 1 peaking at grid node (1, 0, 0) of the unit box on 6 x 8 x
/// 10 cells, which is no bcc lattice node, in planes of phases 0 and 2.
class PeakField final : public PhaseField {
public:
  int num_phases() const override { return 3; }
  std::string phase_name(int i) const override { return "peak" + std::to_string(i); }
  void values(const Vec3& x, std::span<double> out) const override {
    for (int i = 0; i < 3; ++i) out[size_t(i)] = value(i, x);
  }
  double value(int i, const Vec3& x) const override {
    if (i == 1) return 0.6 - 2 * (x - peak_).squaredNorm();
    return i == 0 ? x.y() - 0.5 : 0.4 - x.z();
  }
  Vec3 gradient(int i, const Vec3& x) const override {
    if (i == 1) return -4 * (x - peak_);
    return i == 0 ? Vec3(0, 1, 0) : Vec3(0, 0, -1);
  }

private:
  Vec3 peak_{1.0 / 6, 0, 0};
};

GridSpec small_grid(int n = 8) {
  GridSpec g;
  g.cells = {n, n + 1, n + 2};
  return g;
}

Scene scene_with(const std::string& expr) {
  return parse_scene(R"({"grid": 4, "phases": [{"kind": "constant", "value": 0},
      {"name": "bad", "kind": "expr", "expr": ")" + expr + "\"}]}",
                     "nan.json");
}

std::string sample_error(const Scene& s) {
  try {
    SampledField::sample(*s.field, s.grid);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

void expect_identical(const SampledField& a, const SampledField& b) {
  ASSERT_EQ(a.grid().node_count(), b.grid().node_count());
  ASSERT_EQ(a.k(), b.k());
  for (int64_t n = 0; n < a.grid().node_count(); ++n) {
    ASSERT_TRUE(std::ranges::equal(a.ids(n), b.ids(n))) << "node " << n;
    ASSERT_TRUE(std::ranges::equal(a.values(n), b.values(n))) << "node " << n;
    ASSERT_EQ(a.floor_value(n), b.floor_value(n)) << "node " << n;
  }
}

} // namespace

TEST(SampledField, keeps_the_k_largest_sorted_with_ties_to_lower_id) {
  LinearField field;
  const GridSpec grid = small_grid();
  const SampledField s = SampledField::sample(field, grid, 3);
  ASSERT_EQ(s.k(), 3);
  ASSERT_EQ(s.num_phases(), 6);
  const auto nodes = grid.nodes();
  for (int64_t k = 0; k < nodes[2]; ++k)
    for (int64_t j = 0; j < nodes[1]; ++j)
      for (int64_t i = 0; i < nodes[0]; ++i) {
        const int64_t n = grid.node_index(i, j, k);
        const Vec3 x = grid.node_position(i, j, k);
        // The expected top 3 by brute force: all phases ordered by (value desc, id asc).
        std::vector<int> all{0, 1, 2, 3, 4, 5};
        std::ranges::stable_sort(all, [&](int a, int b) { return field.value(a, x) > field.value(b, x); });
        for (int slot = 0; slot < 3; ++slot) {
          EXPECT_EQ(s.ids(n)[size_t(slot)], all[size_t(slot)]) << "node " << n;
          EXPECT_EQ(s.values(n)[size_t(slot)], field.value(all[size_t(slot)], x));
        }
        for (int p = 0; p < 6; ++p) {
          const bool stored = std::ranges::find(s.ids(n), p) != s.ids(n).end();
          EXPECT_EQ(s.value(n, p), stored ? field.value(p, x) : s.floor_value(n));
        }
      }
}

TEST(SampledField, floor_is_below_every_stored_value_by_spread_or_h) {
  LinearField field;
  const GridSpec grid = small_grid();
  const SampledField s = SampledField::sample(field, grid, 3);
  const double h = grid.h();
  for (int64_t n = 0; n < grid.node_count(); ++n) {
    const auto v = s.values(n);
    EXPECT_LT(s.floor_value(n), v[2]);
    EXPECT_EQ(s.floor_value(n), v[2] - std::max(v[0] - v[2], h));
    EXPECT_GE(s.floor_value(n), s.min_value());
    EXPECT_LE(v[0], s.max_value());
  }
}

TEST(SampledField, min_and_max_are_attained) {
  LinearField field;
  const SampledField s = SampledField::sample(field, small_grid(), 2);
  bool min_seen = false, max_seen = false;
  for (int64_t n = 0; n < s.grid().node_count(); ++n) {
    min_seen = min_seen || s.floor_value(n) == s.min_value();
    max_seen = max_seen || s.values(n)[0] == s.max_value();
  }
  EXPECT_TRUE(min_seen);
  EXPECT_TRUE(max_seen);
}

TEST(SampledField, equal_values_keep_lowest_ids) {
  const Scene scene = parse_scene(R"({"grid": 2, "phases": [{"kind": "constant", "value": 0},
      {"kind": "constant", "value": 0}, {"kind": "constant", "value": 0}, {"kind": "constant", "value": 0}]})",
                                  "ties.json");
  const SampledField s = SampledField::sample(*scene.field, scene.grid, 2);
  for (int64_t n = 0; n < scene.grid.node_count(); ++n) {
    EXPECT_EQ(s.ids(n)[0], 0);
    EXPECT_EQ(s.ids(n)[1], 1);
    EXPECT_EQ(s.floor_value(n), -scene.grid.h());
    EXPECT_EQ(s.value(n, 3), -scene.grid.h());
  }
}

TEST(SampledField, k_above_phase_count_stores_every_phase) {
  LinearField field;
  const SampledField s = SampledField::sample(field, small_grid(4), 10);
  EXPECT_EQ(s.k(), 6);
  for (int64_t n = 0; n < s.grid().node_count(); ++n) {
    std::vector<int32_t> ids(s.ids(n).begin(), s.ids(n).end());
    std::ranges::sort(ids);
    EXPECT_EQ(ids, (std::vector<int32_t>{0, 1, 2, 3, 4, 5}));
    EXPECT_LT(s.floor_value(n), s.values(n)[5]);
  }
}

TEST(SampledField, k_below_one_is_invalid) {
  LinearField field;
  EXPECT_THROW(SampledField::sample(field, small_grid(), 0), InvalidInput);
}

TEST(SampledField, nan_and_infinity_name_phase_and_point) {
  for (const char* expr : {"sqrt(-1)", "0/0"}) {
    const std::string what = sample_error(scene_with(expr));
    EXPECT_EQ(what, "nan.json: phase bad: value is NaN at (0, 0, 0)") << expr;
  }
  EXPECT_EQ(sample_error(scene_with("1/x")), "nan.json: phase bad: value is infinite at (0, 0, 0)");
  // Whatever the scheduling, the lowest bad node is reported: (3, 0, 0) of a 4-cell grid.
  for (int round = 0; round < 5; ++round)
    EXPECT_EQ(sample_error(scene_with("x > 0.5 ? 0/0 : x")), "nan.json: phase bad: value is NaN at (0.75, 0, 0)");
}

TEST(SampledField, parallel_sampling_of_expressions_equals_serial) {
  Scene scene = load_scene(examples + "/split_sphere.json");
  scene.grid.cells = {40, 40, 40};
  SampledField serial = [&] {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    return SampledField::sample(*scene.field, scene.grid, 2);
  }();
  const SampledField parallel = SampledField::sample(*scene.field, scene.grid, 2);
  expect_identical(serial, parallel);
  // And against direct evaluation, so both cannot be wrong alike.
  const GridSpec& g = scene.grid;
  for (int64_t n = 0; n < g.node_count(); n += 97) {
    const auto nodes = g.nodes();
    const Vec3 x = g.node_position(n % nodes[0], (n / nodes[0]) % nodes[1], n / (nodes[0] * nodes[1]));
    EXPECT_EQ(parallel.values(n)[0], scene.field->value(parallel.ids(n)[0], x));
  }
}

TEST(SampledField, expression_field_is_safe_from_many_plain_threads) {
  const Scene scene = load_scene(examples + "/split_sphere.json");
  const PhaseField& f = *scene.field;
  std::vector<Vec3> points;
  for (int i = 0; i < 400; ++i) points.emplace_back(-5 + 0.025 * i, 4 - 0.02 * i, 0.013 * i - 2);
  std::vector<double> want;
  for (const Vec3& x : points)
    for (int p = 0; p < 3; ++p) {
      want.push_back(f.value(p, x));
      const Vec3 g = f.gradient(p, x);
      want.insert(want.end(), {g.x(), g.y(), g.z()});
    }
  std::vector<std::vector<double>> got(8);
  std::vector<std::thread> threads;
  for (auto& out : got)
    threads.emplace_back([&f, &points, &out] {
      for (int rep = 0; rep < 5; ++rep) {
        out.clear();
        for (const Vec3& x : points)
          for (int p = 0; p < 3; ++p) {
            out.push_back(f.value(p, x));
            const Vec3 g = f.gradient(p, x);
            out.insert(out.end(), {g.x(), g.y(), g.z()});
          }
      }
    });
  for (auto& t : threads) t.join();
  for (const auto& out : got) EXPECT_EQ(out, want);
}

// Create with the bcc lattice reads only nodes whose indices are all even or
// all odd: sampling only those (SampledNodes::bcc) must give them the same
// samples, and create the same mesh bit for bit, though the field's range over
// all nodes (min_value(), max_value()) is not the range over those.
TEST(SampledField, bcc_nodes_hold_what_every_node_sampling_holds_there_and_create_the_same_mesh) {
  const PeakField field;
  GridSpec grid;
  grid.cells = {6, 8, 10};
  const SampledField all = SampledField::sample(field, grid, 3);
  const SampledField bcc = SampledField::sample(field, grid, 3, SampledNodes::bcc);
  EXPECT_EQ(SampledField::count_nodes(grid, SampledNodes::bcc), 4 * 5 * 6 + 3 * 4 * 5);
  EXPECT_EQ(int64_t(bcc.all_floors().size()), SampledField::count_nodes(grid, SampledNodes::bcc));
  const auto nodes = grid.nodes();
  int64_t held = 0;
  for (int64_t k = 0; k < nodes[2]; ++k)
    for (int64_t j = 0; j < nodes[1]; ++j)
      for (int64_t i = 0; i < nodes[0]; ++i) {
        if (i % 2 != j % 2 || j % 2 != k % 2) continue;
        const int64_t n = grid.node_index(i, j, k);
        ++held;
        ASSERT_TRUE(std::ranges::equal(all.ids(n), bcc.ids(n))) << "node " << n;
        ASSERT_TRUE(std::ranges::equal(all.values(n), bcc.values(n))) << "node " << n;
        ASSERT_EQ(all.floor_value(n), bcc.floor_value(n)) << "node " << n;
      }
  EXPECT_EQ(held, SampledField::count_nodes(grid, SampledNodes::bcc));
  // The largest value over all nodes is at (1, 0, 0), no lattice node: the
  // ranges differ, and create must quantize over the lattice's alone.
  EXPECT_GT(all.max_value(), bcc.max_value());
  NodeMesh from_all, from_bcc;
  create_initial_mesh(all, CreateParams{}, from_all);
  create_initial_mesh(bcc, CreateParams{}, from_bcc);
  ASSERT_GT(from_all.num_triangles(), 0u);
  EXPECT_EQ(from_all.points, from_bcc.points);
  EXPECT_EQ(from_all.triangles, from_bcc.triangles);
  EXPECT_EQ(from_all.pairs, from_bcc.pairs);
  grid.cells = {6, 7, 10};
  EXPECT_THROW(SampledField::sample(field, grid, 3, SampledNodes::bcc), InvalidInput);
}
