#include "fields/distance_transform.hpp"

#include "core/parallel.hpp"

#include <limits>

namespace vm::detail {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

/// The 1-D transform of n samples f (spacing s) into d: d(q) = min_p f(p) + (s (q - p))^2.
/// `v` and `z` are scratch space (n and n + 1 entries): the parabolas of the
/// lower envelope and the boundaries between them.
void transform_1d(const double* f, double* d, int64_t n, double s, int64_t* v, double* z) {
  int64_t k = -1;
  for (int64_t q = 0; q < n; ++q) {
    if (f[q] == inf) continue; // no parabola
    const double fq = f[q] + (s * double(q)) * (s * double(q));
    double boundary = -inf;
    while (k >= 0) {
      const double fv = f[v[k]] + (s * double(v[k])) * (s * double(v[k]));
      boundary = (fq - fv) / (2 * s * s * double(q - v[k])); // where parabolas q and v[k] meet, in index units
      if (boundary > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -inf : boundary;
    z[k + 1] = inf;
  }
  if (k < 0) {
    for (int64_t q = 0; q < n; ++q) d[q] = inf;
    return;
  }
  int64_t j = 0;
  for (int64_t q = 0; q < n; ++q) {
    while (z[j + 1] < double(q)) ++j;
    const double dq = s * double(q - v[j]);
    d[q] = f[v[j]] + dq * dq;
  }
}

} // namespace

void squared_distance_transform(std::vector<float>& f, const std::array<int64_t, 3>& size, const Vec3& spacing) {
  const std::array<int64_t, 3> stride{1, size[0], size[0] * size[1]};
  for (int a = 0; a < 3; ++a) {
    const int64_t n = size[size_t(a)];
    const int b = (a + 1) % 3, c = (a + 2) % 3; // the other two axes enumerate the lines
    const int64_t lines = size[size_t(b)] * size[size_t(c)];
    parallel_for_each_index(size_t(lines), [&](size_t line) {
      thread_local std::vector<double> in, out, z;
      thread_local std::vector<int64_t> v;
      in.resize(size_t(n)), out.resize(size_t(n)), z.resize(size_t(n) + 1), v.resize(size_t(n));
      const int64_t ib = int64_t(line) % size[size_t(b)], ic = int64_t(line) / size[size_t(b)];
      const int64_t base = ib * stride[size_t(b)] + ic * stride[size_t(c)];
      for (int64_t q = 0; q < n; ++q) in[size_t(q)] = f[size_t(base + q * stride[size_t(a)])];
      transform_1d(in.data(), out.data(), n, spacing[a], v.data(), z.data());
      for (int64_t q = 0; q < n; ++q) f[size_t(base + q * stride[size_t(a)])] = float(out[size_t(q)]);
    }, 16);
  }
}

} // namespace vm::detail
