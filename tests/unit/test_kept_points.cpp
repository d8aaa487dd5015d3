// The kept-point check of a flip (improve/kept_points.hpp) against what the
// geometry says: a flip sweeps its surface across its quad's tetrahedron, so
// a kept point inside changes phase, and is lost when it was in its own before.

#include "improve/kept_points.hpp"

#include "fixtures.hpp"

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

// Seen as the flip that made face (a, b, c) of the tetrahedron's surface with
// its fourth corner d off the face, the flip swept the solid tetrahedron: a
// point inside it is now inside the surface (phase 1) and was outside (phase
// 0) before. So the flip loses a kept point of phase 0 there, and none of
// phase 1 (it brought that one in), nor any point outside the tetrahedron.
TEST(KeptPoints, a_flip_loses_a_point_of_the_phase_its_tetrahedron_left) {
  const InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::tetrahedron());
  const Vec3 inside = Vec3(0.2, 0.25, 0.3), outside = Vec3(0.6, 0.6, 0.6);
  for (int32_t face = 0; face < int32_t(mesh.num_triangles()); ++face) {
    const auto& tri = mesh.triangles()[size_t(face)];
    int32_t off = 0;
    while (std::find(tri.begin(), tri.end(), off) != tri.end()) ++off;
    const std::array<int32_t, 4> quad{tri[0], tri[1], tri[2], off};
    EXPECT_TRUE(detail::flip_loses_kept_point(mesh, face, quad, OneKeptPoint(inside, 0))) << "face " << face;
    EXPECT_FALSE(detail::flip_loses_kept_point(mesh, face, quad, OneKeptPoint(inside, 1))) << "face " << face;
    EXPECT_FALSE(detail::flip_loses_kept_point(mesh, face, quad, OneKeptPoint(outside, 0))) << "face " << face;
  }
}

} // namespace
