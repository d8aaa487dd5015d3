#pragma once
/// @file fields/top_k.hpp
/// The rules every top-K store of phase values shares (SampledField, the grid
/// fields of label volumes and distance grids), so they all describe one
/// consistent field.

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vm::detail {

/// The order of kept phases: larger value first, lower phase id first among equal values.
inline bool ranks_before(double value_a, int32_t a, double value_b, int32_t b) {
  return value_a > value_b || (value_a == value_b && a < b);
}

/// The value every phase not kept at a point takes there, given the largest
/// (`first`) and smallest (`last`) kept values: below `last` by at least the
/// spread of the kept values and at least `h`, so a missing phase does not
/// compete near where it was not kept; nextafter keeps it strictly below when
/// h vanishes next to huge values.
inline double floor_below(double first, double last, double h) {
  const double below = last - std::max(first - last, h);
  // Anything below `last` is at most nextafter(last): the min is `below`. The
  // libm call is skipped (it was 4% of a label volume's run, once per node).
  if (below < last) return below;
  return std::min(below, std::nextafter(last, -HUGE_VAL));
}

} // namespace vm::detail
