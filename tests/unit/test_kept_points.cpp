// The kept-point check of a flip (improve/kept_points.hpp) against what the
// geometry says: a flip sweeps its surface across its quad's tetrahedron, so
// a kept point inside changes phase, and is lost when it was in its own before.

#include "improve/kept_points.hpp"

#include <gtest/gtest.h>

namespace {

using namespace vm;

/// Two phases whose only kept point is `point`, kept in `phase`.
class OneKeptPoint final : public PhaseField {
public:
  OneKeptPoint(const Vec3& point, int32_t phase) : point_(point), phase_(phase) {}
  int num_phases() const override { return 2; }
  std::string phase_name(int i) const override { return "phase" + std::to_string(i); }
  void values(const Vec3& x, std::span<double> out) const override {
    for (int i = 0; i < 2; ++i) out[size_t(i)] = value(i, x);
  }
  double value(int i, const Vec3& x) const override { return i == 0 ? x.sum() - 1 : 1 - x.sum(); }
  Vec3 gradient(int i, const Vec3&) const override { return i == 0 ? Vec3::Ones() : Vec3(-Vec3::Ones()); }
  void kept_points(const Vec3& lo, const Vec3& hi, std::vector<Vec3>& out) const override {
    if ((lo.array() <= point_.array()).all() && (point_.array() <= hi.array()).all()) out.push_back(point_);
  }
  int32_t kept_phase(const Vec3&) const override { return phase_; }
  bool keeps_points() const override { return true; }

private:
  Vec3 point_;
  int32_t phase_;
};

// Triangles (i, j, k) and (i, l, j) of a surface folded along i-j; the flip
// makes (i, l, k) and (l, j, k), sweeping the surface across the solid
// tetrahedron (i, j, k, l). The normal of (i, j, k) is +z, into phase 1, and l
// lies above it: a point inside the tetrahedron is in phase 1 before the flip
// and in phase 0 after. So the flip loses a kept point of phase 1 there, and
// none of phase 0 (it brings that one in), nor any point outside it; and one
// of either phase on a new triangle, where no old one passes (a point on a
// surface is in either phase by round-off).
TEST(KeptPoints, a_flip_loses_a_point_of_the_phase_its_tetrahedron_leaves) {
  const std::vector<Vec3> positions{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, -1, 0.5}};
  const std::array<int32_t, 4> quad{0, 1, 2, 3};
  const PhasePair pair{0, 1};
  const Vec3 inside = 0.25 * (positions[0] + positions[1] + positions[2] + positions[3]), outside(5, 5, 5);
  EXPECT_TRUE(detail::flip_loses_kept_point(positions, quad, pair, OneKeptPoint(inside, 1)));
  EXPECT_FALSE(detail::flip_loses_kept_point(positions, quad, pair, OneKeptPoint(inside, 0)));
  EXPECT_FALSE(detail::flip_loses_kept_point(positions, quad, pair, OneKeptPoint(outside, 1)));
  const Vec3 on_new_triangle = (positions[0] + positions[3] + positions[2]) / 3;
  EXPECT_TRUE(detail::flip_loses_kept_point(positions, quad, pair, OneKeptPoint(on_new_triangle, 0)));
  EXPECT_TRUE(detail::flip_loses_kept_point(positions, quad, pair, OneKeptPoint(on_new_triangle, 1)));
  // On an old triangle too: it was as near before.
  const Vec3 on_old_triangle = (positions[0] + positions[1] + positions[2]) / 3;
  EXPECT_FALSE(detail::flip_loses_kept_point(positions, quad, pair, OneKeptPoint(on_old_triangle, 0)));
}

} // namespace
