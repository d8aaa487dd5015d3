/// @file mesh/triangle_quality.cpp
/// triangle_quality() (voronoimesh/mesh/triangle_quality.hpp).

#include "voronoimesh/mesh/triangle_quality.hpp"

#include <cmath>

namespace vm {

double triangle_quality(const Vec3& a0, const Vec3& b0, const Vec3& c0) {
  // Corners sorted, so that the rounding (and with it every comparison of
  // qualities: flips, the pipeline's quality floor) does not depend on where a
  // triangle's corner list starts, which differs between passes and processes.
  // The passes ask this of every triangle every iteration, in no order a
  // branch predictor could learn: corners almost always differ in x, so the
  // comparison is a flag and each swap two selects, not a branch per corner.
  auto lexicographic = [](const Vec3& u, const Vec3& v) {
    return u[0] != v[0] ? u[0] < v[0] : u[1] != v[1] ? u[1] < v[1] : u[2] < v[2];
  };
  auto order = [&](const Vec3*& lo, const Vec3*& hi) {
    const bool swap = lexicographic(*hi, *lo);
    const Vec3* first = swap ? hi : lo;
    hi = swap ? lo : hi;
    lo = first;
  };
  const Vec3 *pa = &a0, *pb = &b0, *pc = &c0;
  order(pa, pb);
  order(pb, pc);
  order(pa, pb);
  const Vec3 &a = *pa, &b = *pb, &c = *pc;
  const double sum2 = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  const double q = 4.0 * std::sqrt(3.0) * 0.5 * (b - a).cross(c - a).norm() / sum2;
  return std::isfinite(q) ? q : 0.0; // 0/0 for a point triangle, NaN coordinates
}

} // namespace vm
