#include "voronoimesh/core/errors.hpp"

#include <cstdio>
#include <utility>

namespace vm {

/// Control characters (a newline in a file name, a key or a quoted value) are
/// escaped, so the result is always the promised single line.
std::string located(const std::string& source, const std::string& message) {
  std::string out;
  for (unsigned char c : source + ": " + message) {
    if (c >= 0x20 && c != 0x7f) {
      out += char(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", unsigned(c));
      out += buf;
    }
  }
  return out;
}

InvalidOption::InvalidOption(std::string option, std::string problem)
    : InvalidInput(located(option, problem)), option_(std::move(option)), problem_(std::move(problem)) {}

} // namespace vm
