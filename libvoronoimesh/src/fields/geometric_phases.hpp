#pragma once
/// @file geometric_phases.hpp
/// The closed-form scene kinds that need no expression parser: constant, sphere,
/// seeds (paper eq. 7) and plane. All are immutable, hence thread-safe.

#include "fields/phase_function.hpp"

#include <vector>

namespace vm::detail {

/// phi = c everywhere (typically the "outside" phase of sphere scenes).
class ConstantPhase final : public PhaseFunction {
public:
  explicit ConstantPhase(double c) : c_(c) {}
  double value(const Vec3&) const override { return c_; }
  Vec3 gradient(const Vec3&) const override { return Vec3::Zero(); }

private:
  double c_;
};

/// Signed distance to a sphere, positive inside: phi = r - |x - c| (paper sect. 4.1).
class SpherePhase final : public PhaseFunction {
public:
  SpherePhase(const Vec3& center, double radius) : center_(center), radius_(radius) {}
  double value(const Vec3& x) const override;
  /// -(x - c)/|x - c|; zero at the centre, where phi has no gradient.
  Vec3 gradient(const Vec3& x) const override;

private:
  Vec3 center_;
  double radius_;
};

/// Minus the distance to the nearest of a set of points (paper eq. 7, with the
/// sign flipped so that the region nearest to the points has the largest phi).
class SeedsPhase final : public PhaseFunction {
public:
  /// @pre `points` is not empty.
  explicit SeedsPhase(std::vector<Vec3> points) : points_(std::move(points)) {}
  double value(const Vec3& x) const override;
  /// -(x - p)/|x - p| for the nearest point p (the first one on ties); zero on p.
  Vec3 gradient(const Vec3& x) const override;

private:
  /// Index of the point nearest to x; the lowest index on ties.
  size_t nearest(const Vec3& x) const;
  std::vector<Vec3> points_;
};

/// Signed distance to a plane, positive on the side the normal points to.
class PlanePhase final : public PhaseFunction {
public:
  /// @pre `normal` is not zero; it need not be unit.
  PlanePhase(const Vec3& point, const Vec3& normal) : point_(point), unit_(normal.normalized()) {}
  double value(const Vec3& x) const override { return unit_.dot(x - point_); }
  Vec3 gradient(const Vec3&) const override { return unit_; }

private:
  Vec3 point_, unit_;
};

} // namespace vm::detail
