#include "voronoimesh/check/locate.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>

namespace vm {
namespace {

/// Where a ray crosses a triangle: at x, from phase `from` into `to`; from < 0
/// when it passes exactly through an edge or corner and cannot decide.
struct Crossing {
  double x;
  int32_t from, to;
};

/// Twice the signed area of (p, q, (y, z)) in the yz plane.
double cross_yz(const Vec3& p, const Vec3& q, double y, double z) {
  return (q.y() - p.y()) * (z - p.z()) - (q.z() - p.z()) * (y - p.y());
}

} // namespace

std::vector<int32_t> locate_grid_points(const NodeMesh& closed, const PointGrid& grid) {
  const int64_t nx = grid.size[0], ny = grid.size[1], nz = grid.size[2];
  std::vector<int32_t> phase(size_t(nx * ny * nz), -1);
  if (closed.outside_phase < 0 || phase.empty()) return phase;
  const Vec3 offset(0, 7.31e-4 * grid.spacing.y(), 5.17e-4 * grid.spacing.z());
  // Rows whose ray (j, k) meets each triangle's projection, one list per row.
  std::vector<std::vector<Crossing>> rows(size_t(ny * nz));
  auto index_of = [&](double v, int axis) { return (v - grid.origin[axis]) / grid.spacing[axis]; };
  for (size_t t = 0; t < closed.num_triangles(); ++t) {
    const Vec3& a = closed.points[size_t(closed.triangles[t][0])];
    const Vec3& b = closed.points[size_t(closed.triangles[t][1])];
    const Vec3& c = closed.points[size_t(closed.triangles[t][2])];
    const double normal_x = (b - a).cross(c - a).x();
    if (normal_x == 0) continue; // parallel to the rays
    const Vec3 lo = a.cwiseMin(b).cwiseMin(c) - offset, hi = a.cwiseMax(b).cwiseMax(c) - offset;
    const int64_t k0 = std::max<int64_t>(0, int64_t(std::ceil(index_of(lo.z(), 2))));
    const int64_t k1 = std::min<int64_t>(nz - 1, int64_t(std::floor(index_of(hi.z(), 2))));
    const int64_t j0 = std::max<int64_t>(0, int64_t(std::ceil(index_of(lo.y(), 1))));
    const int64_t j1 = std::min<int64_t>(ny - 1, int64_t(std::floor(index_of(hi.y(), 1))));
    for (int64_t k = k0; k <= k1; ++k)
      for (int64_t j = j0; j <= j1; ++j) {
        const double y = grid.origin.y() + double(j) * grid.spacing.y() + offset.y();
        const double z = grid.origin.z() + double(k) * grid.spacing.z() + offset.z();
        const double wa = cross_yz(b, c, y, z), wb = cross_yz(c, a, y, z), wc = cross_yz(a, b, y, z);
        if (!((wa >= 0 && wb >= 0 && wc >= 0) || (wa <= 0 && wb <= 0 && wc <= 0))) continue;
        auto& row = rows[size_t(j + ny * k)];
        if (wa == 0 || wb == 0 || wc == 0) {
          row.push_back({-INFINITY, -1, -1});
          continue;
        }
        const double x = (wa * a.x() + wb * b.x() + wc * c.x()) / (wa + wb + wc);
        const auto& pair = closed.pairs[t];
        row.push_back(normal_x > 0 ? Crossing{x, pair[0], pair[1]} : Crossing{x, pair[1], pair[0]});
      }
  }
  // Only points strictly inside the box: those on it lie on its surfaces.
  const Box& box = closed.domain;
  auto inside = [&](const Vec3& p) { return (p.array() > box.min.array()).all() && (p.array() < box.max.array()).all(); };
  detail::parallel_for_each_index(rows.size(), [&](size_t r) {
    auto& row = rows[r];
    std::sort(row.begin(), row.end(), [](const Crossing& p, const Crossing& q) { return p.x < q.x; });
    if (!row.empty() && row.front().from < 0) return;
    const int64_t j = int64_t(r) % ny, k = int64_t(r) / ny;
    int32_t current = closed.outside_phase;
    size_t next = 0;
    for (int64_t i = 0; i < nx; ++i) {
      const Vec3 p = grid.origin + grid.spacing.cwiseProduct(Vec3(double(i), double(j), double(k)));
      for (; next < row.size() && row[next].x < p.x(); ++next) {
        if (row[next].from != current) return; // not closed along this ray
        current = row[next].to;
      }
      if (inside(p)) phase[size_t(i + nx * int64_t(r))] = current;
    }
  });
  return phase;
}

} // namespace vm
