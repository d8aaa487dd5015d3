#pragma once
/// @file core/fixed_point_sum.hpp
/// A sum of non-negative doubles whose result does not depend on the order of
/// its terms, nor on how they are split among threads, chunks or MPI ranks:
/// every term is rounded down to a multiple of 2^-kFractionBits of a fixed
/// `unit` and added as an integer, and integer addition is associative.
/// Floating-point partial sums are not, so the mean edge length (which sets
/// the smoothing's rest length) would change in its last bits with the node
/// numbering and make a distributed run differ from one process.

#include <cmath>
#include <cstdint>

namespace vm::detail {

class FixedPointSum {
public:
  /// Terms are expected in [0, unit]; larger ones still add correctly while the
  /// total stays below 2^(127 - kFractionBits) units.
  static constexpr int kFractionBits = 80;
  using Raw = __int128;

  explicit FixedPointSum(double unit) : unit_(unit) {}

  void add(double term) { raw_ += to_raw(term); }
  /// Adds another partial sum over the same unit (another chunk, another rank).
  void add_raw(Raw other) { raw_ += other; }
  Raw raw() const { return raw_; }
  double unit() const { return unit_; }
  double total() const { return std::ldexp(double(raw_), -kFractionBits) * unit_; }

private:
  Raw to_raw(double term) const {
    // Negative, NaN and zero-unit terms count as nothing rather than as garbage bits.
    const double scaled = unit_ > 0 ? term / unit_ : 0.0;
    if (!(scaled > 0)) return 0;
    // scaled * 2^80 truncated, as Raw(x) would do it, without the library's
    // slow double-to-128-bit conversion (the passes sum every edge and every
    // triangle's quality each iteration): the high 64 bits, then the rest,
    // which is exact in a double because x and its high part share their last bits.
    const double x = scaled * 0x1p80;
    if (x < 0x1p63) return Raw(int64_t(x));
    if (!(x < 0x1p126)) return Raw(std::ldexp(scaled, kFractionBits)); // beyond any sum this class makes
    const auto high = uint64_t(x * 0x1p-64);
    const double low = x - double(high) * 0x1p64;
    return (Raw(high) << 64) + Raw(uint64_t(low));
  }

  double unit_;
  Raw raw_ = 0;
};

} // namespace vm::detail
