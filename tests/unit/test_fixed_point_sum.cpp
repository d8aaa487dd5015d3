// core/fixed_point_sum.hpp: sums that do not depend on the order of their
// terms, and rms_edge_length() built on it, which sets the smoothing's rest
// length and must not change with the node numbering (a distributed run
// numbers each rank's part afresh).

#include "core/fixed_point_sum.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

namespace {

using namespace vm;
using detail::FixedPointSum;

TEST(FixedPointSum, total_does_not_depend_on_the_order_or_the_split) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> exponent(-30, 0);
  std::vector<double> terms(20000);
  for (double& t : terms) t = std::exp2(exponent(rng)) * 7.5;
  FixedPointSum forward(8.0);
  for (double t : terms) forward.add(t);
  // Doubles added in another order differ in their last bits (the reason for
  // the fixed point): check that this data shows it, so the test means something.
  std::vector<double> shuffled = terms;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  EXPECT_NE(std::accumulate(terms.begin(), terms.end(), 0.0), std::accumulate(shuffled.begin(), shuffled.end(), 0.0));
  // Shuffled and split into uneven chunks, as threads or ranks would.
  FixedPointSum whole(8.0);
  for (size_t begin = 0, size = 1; begin < shuffled.size(); begin += size, size = size * 3 + 1) {
    FixedPointSum chunk(8.0);
    for (size_t i = begin; i < std::min(shuffled.size(), begin + size); ++i) chunk.add(shuffled[i]);
    whole.add_raw(chunk.raw());
  }
  EXPECT_EQ(whole.raw(), forward.raw());
  EXPECT_EQ(whole.total(), forward.total());
  // Within the resolution of the fixed point (2^-80 of the unit per term).
  long double exact = 0;
  for (double t : terms) exact += t;
  EXPECT_NEAR(forward.total(), double(exact), 1e-12 * double(exact));
}

// Each term becomes term / unit * 2^80 truncated: the same integer the
// library's double-to-128-bit conversion gives, below 2^63 and above it.
TEST(FixedPointSum, each_term_is_its_scaled_value_truncated) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> exponent(-80, 40), mantissa(1, 2);
  for (int i = 0; i < 20000; ++i) {
    const double term = mantissa(rng) * std::exp2(exponent(rng));
    FixedPointSum sum(1.0);
    sum.add(term);
    EXPECT_TRUE(sum.raw() == FixedPointSum::Raw(std::ldexp(term, FixedPointSum::kFractionBits))) << term;
  }
}

TEST(FixedPointSum, ignores_terms_that_are_not_positive_numbers) {
  FixedPointSum s(1.0);
  s.add(0.25);
  s.add(-1.0);
  s.add(std::nan(""));
  s.add(0.0);
  EXPECT_EQ(s.total(), 0.25);
}

TEST(RmsEdgeLength, does_not_change_with_the_node_numbering) {
  const NodeMesh created = test::four_spheres(56);
  ASSERT_GT(created.num_nodes(), 4096u); // more than one chunk of the parallel sum
  // The same mesh with its nodes numbered backwards.
  NodeMesh renumbered = created;
  const auto last = int32_t(created.num_nodes()) - 1;
  std::reverse(renumbered.points.begin(), renumbered.points.end());
  for (auto& t : renumbered.triangles)
    for (int32_t& v : t) v = last - v;
  EXPECT_EQ(rms_edge_length(InterfaceMesh::from_node_mesh(created)),
            rms_edge_length(InterfaceMesh::from_node_mesh(renumbered)));
}

} // namespace
