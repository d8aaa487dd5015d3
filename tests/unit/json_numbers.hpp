#pragma once
/// @file json_numbers.hpp
/// Numbers and points as JSON text for scenes written by tests, with 17
/// significant digits so that parsing them gives back the same doubles.

#include "voronoimesh/core/types.hpp"

#include <sstream>
#include <string>

namespace vm::test {

inline std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

inline std::string point(const Vec3& p) { return "[" + num(p.x()) + "," + num(p.y()) + "," + num(p.z()) + "]"; }

} // namespace vm::test
