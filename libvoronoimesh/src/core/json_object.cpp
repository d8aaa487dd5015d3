#include "core/json_object.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <set>
#include <string>
#include <vector>

#include <cmath>

namespace vm::detail {

namespace {

using nlohmann::json;

/// "malformed JSON at line L, column C: <reason>" from nlohmann's message, which
/// reads "[json.exception.parse_error.101] parse error at line L, column C: <reason>"
/// (or "[json.exception.out_of_range.406] number overflow parsing '1e999'").
std::string malformed(const json::exception& e) {
  std::string what = e.what();
  const size_t tag_end = what.find("] ");
  if (what.starts_with("[json.exception.") && tag_end != std::string::npos) what.erase(0, tag_end + 2);
  const std::string marker = "parse error ";
  if (what.starts_with(marker)) return "malformed JSON " + what.substr(marker.size());
  return "malformed JSON: " + what;
}

/// Thrown from the parser's callback, so that parse_json() can say where.
struct Refusal {
  std::string problem;
};

} // namespace

json parse_json(const std::string& text, const std::string& source) {
  // The keys seen in each object being read, innermost last.
  std::vector<std::set<std::string>> keys;
  auto check = [&](int depth, json::parse_event_t event, json& parsed) {
    switch (event) {
    case json::parse_event_t::object_start:
    case json::parse_event_t::array_start:
      if (depth >= kMaxJsonDepth) throw Refusal{"JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels"};
      if (event == json::parse_event_t::object_start) keys.emplace_back();
      break;
    case json::parse_event_t::object_end:
      keys.pop_back();
      break;
    case json::parse_event_t::key:
      if (!keys.back().insert(parsed.get<std::string>()).second)
        throw Refusal{"key " + quote(parsed.get<std::string>()) + " appears twice in one object"};
      break;
    default:
      break;
    }
    return true;
  };
  try {
    return json::parse(text, check);
  } catch (const json::exception& e) {
    throw InvalidInput(located(source, malformed(e)));
  } catch (const Refusal& r) {
    throw InvalidInput(located(source, r.problem));
  }
}

std::string brief(const json& v) {
  if (v.is_array()) return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " item" : " items");
  if (v.is_object()) return "an object of " + std::to_string(v.size()) + (v.size() == 1 ? " key" : " keys");
  std::string s = v.dump(); // a single value: no recursion
  constexpr size_t max_len = 40;
  return s.size() <= max_len ? s : s.substr(0, max_len - 3) + "...";
}

JsonObject::JsonObject(const nlohmann::json& j, std::string source, std::string where)
    : json_(j), source_(std::move(source)), where_(std::move(where)) {
  if (!json_.is_object())
    fail("expected a JSON object { ... }, got " + brief(json_));
}

void JsonObject::fail(const std::string& problem) const {
  throw InvalidInput(located(source_, where_.empty() ? problem : where_ + ": " + problem));
}

void JsonObject::allow_only(std::initializer_list<std::string_view> allowed) const {
  for (const auto& item : json_.items()) {
    bool known = false;
    std::string list;
    for (std::string_view a : allowed) {
      known = known || item.key() == a;
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    if (!known) fail("unknown key '" + item.key() + "' (expected " + list + ")");
  }
}

const nlohmann::json& JsonObject::at(const std::string& key) const {
  auto it = json_.find(key);
  if (it == json_.end()) fail("missing key '" + key + "'");
  return *it;
}

double JsonObject::as_number(const nlohmann::json& v, const std::string& what) const {
  if (!v.is_number()) fail("'" + what + "' must be a number, got " + brief(v));
  const double d = v.get<double>();
  // JSON has no NaN and nlohmann 3.11 refuses overflowing literals; checked all the
  // same, since a non-finite number would only surface much later, mid-sampling.
  if (!std::isfinite(d)) fail("'" + what + "' must be a finite number, got " + brief(v));
  return d;
}

Vec3 JsonObject::as_vec3(const nlohmann::json& v, const std::string& what) const {
  if (!v.is_array() || v.size() != 3)
    fail("'" + what + "' must be an array of 3 numbers, got " + brief(v));
  Vec3 p;
  for (int a = 0; a < 3; ++a)
    p[a] = as_number(v[size_t(a)], what + "[" + std::to_string(a) + "]");
  return p;
}

double JsonObject::number(const std::string& key) const { return as_number(at(key), key); }

Vec3 JsonObject::vec3(const std::string& key) const { return as_vec3(at(key), key); }

std::string JsonObject::string(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_string()) fail("'" + key + "' must be a string, got " + brief(v));
  return v.get<std::string>();
}

JsonObject JsonObject::object(const std::string& key) const {
  const auto& v = at(key);
  if (!v.is_object()) fail("'" + key + "' must be an object { ... }, got " + brief(v));
  return JsonObject(v, source_, where_.empty() ? key : where_ + "." + key);
}

} // namespace vm::detail
