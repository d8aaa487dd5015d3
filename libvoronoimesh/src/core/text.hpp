#pragma once
/// @file core/text.hpp
/// Building one-line messages, and reading numbers from header text.

#include <cctype>
#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>

namespace vm::detail {

/// Concatenates strings and numbers (floating point as %.6g) into one line.
/// (Appending also avoids GCC 12's false -Wrestrict warnings on
/// "literal" + std::string chains.)
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string s;
  auto add = [&s](const auto& p) {
    using T = std::decay_t<decltype(p)>;
    if constexpr (std::is_floating_point_v<T>) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", double(p));
      s += buf;
    } else if constexpr (std::is_arithmetic_v<T>)
      s += std::to_string(p);
    else
      s += std::string_view(p);
  };
  (add(parts), ...);
  return s;
}

/// `text` in single quotes for a message, cut to its first `max` characters
/// with "..." after them when longer (a quote must not carry a whole file).
inline std::string quote(std::string_view text, size_t max = 60) {
  std::string s = "'";
  s += text.size() <= max ? text : text.substr(0, max);
  s += text.size() <= max ? "'" : "...'";
  return s;
}

/// `s` in lower case (ASCII), e.g. to compare file extensions.
inline std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// True when the whole of `s` is a number of type T, stored in `v`.
template <class T>
bool parse_number(std::string_view s, T& v) {
  auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

} // namespace vm::detail
