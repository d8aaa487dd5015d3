#pragma once
/// @file core/clock.hpp
/// Wall time for the timings the library reports.

#include <chrono>

namespace vm::detail {

/// Seconds of wall time since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace vm::detail
