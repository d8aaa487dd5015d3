#include "fields/geometric_phases.hpp"

namespace vm::detail {

namespace {

/// Gradient of -|x - p|: the unit vector from x towards p, or zero at p.
Vec3 towards(const Vec3& x, const Vec3& p) {
  const Vec3 d = p - x;
  const double len = d.norm();
  return len > 0 ? Vec3(d / len) : Vec3(Vec3::Zero());
}

} // namespace

double SpherePhase::value(const Vec3& x) const { return radius_ - (x - center_).norm(); }

Vec3 SpherePhase::gradient(const Vec3& x) const { return towards(x, center_); }

size_t SeedsPhase::nearest(const Vec3& x) const {
  size_t best = 0;
  double best_d2 = (points_[0] - x).squaredNorm();
  for (size_t i = 1; i < points_.size(); ++i) {
    const double d2 = (points_[i] - x).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

double SeedsPhase::value(const Vec3& x) const { return -(points_[nearest(x)] - x).norm(); }

Vec3 SeedsPhase::gradient(const Vec3& x) const { return towards(x, points_[nearest(x)]); }

} // namespace vm::detail
