#pragma once
/// @file exact.hpp
/// Exact integer arithmetic for the topological decisions of create.
/// Phase values are quantized to integers of at most 29 bits (quantize.hpp), so
/// any determinant of up to 4x4 differences fits in __int128 with room to spare:
/// 24 terms of 4 factors below 2^29 stay under 2^121.

#include <array>
#include <cstdint>
#include <utility>

namespace vm::detail {

using i128 = __int128;

inline int sign(i128 v) { return (v > 0) - (v < 0); }

/// Determinant of the leading n x n block of `m` (n in 1..4), exact.
inline i128 det(const std::array<std::array<i128, 4>, 4>& m, int n) {
  switch (n) {
  case 1:
    return m[0][0];
  case 2:
    return m[0][0] * m[1][1] - m[0][1] * m[1][0];
  case 3:
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  default: {
    // Laplace expansion along the first row, with 2x2 minors of the last two rows.
    const auto& a = m[2];
    const auto& b = m[3];
    i128 m01 = a[0] * b[1] - a[1] * b[0], m02 = a[0] * b[2] - a[2] * b[0];
    i128 m03 = a[0] * b[3] - a[3] * b[0], m12 = a[1] * b[2] - a[2] * b[1];
    i128 m13 = a[1] * b[3] - a[3] * b[1], m23 = a[2] * b[3] - a[3] * b[2];
    const auto& r = m[1];
    i128 c0 = r[1] * m23 - r[2] * m13 + r[3] * m12;
    i128 c1 = r[0] * m23 - r[2] * m03 + r[3] * m02;
    i128 c2 = r[0] * m13 - r[1] * m03 + r[3] * m01;
    i128 c3 = r[0] * m12 - r[1] * m02 + r[2] * m01;
    return m[0][0] * c0 - m[0][1] * c1 + m[0][2] * c2 - m[0][3] * c3;
  }
  }
}

inline unsigned __int128 abs_u(i128 v) { return v < 0 ? (unsigned __int128)(-v) : (unsigned __int128)v; }

inline int count_trailing_zeros(uint64_t x) { return __builtin_ctzll(x); }
inline int count_trailing_zeros(unsigned __int128 x) {
  const uint64_t lo = uint64_t(x);
  return lo ? __builtin_ctzll(lo) : 64 + __builtin_ctzll(uint64_t(x >> 64));
}

/// Greatest common divisor (binary), gcd(0, b) = b.
template <class U> U binary_gcd(U a, U b) {
  if (a == 0) return b;
  if (b == 0) return a;
  const int shift = count_trailing_zeros(U(a | b));
  a >>= count_trailing_zeros(a);
  while (b != 0) {
    b >>= count_trailing_zeros(b);
    if (a > b) std::swap(a, b);
    b -= a;
  }
  return a << shift;
}

inline uint64_t gcd(uint64_t a, uint64_t b) { return binary_gcd(a, b); }

/// For 128-bit magnitudes. The binary loop takes a step per bit, a hundred on
/// 128-bit words (most of create's time spent on vertex keys); once the smaller
/// number fits in 64 bits, as it nearly always does, one division brings the
/// larger below it and the loop runs on 64-bit words.
inline unsigned __int128 gcd(unsigned __int128 a, unsigned __int128 b) {
  if (a > b) std::swap(a, b);
  if (a == 0) return b;
  if (a >> 64 == 0) return binary_gcd(uint64_t(a), uint64_t(b % a));
  return binary_gcd(a, b);
}

} // namespace vm::detail
